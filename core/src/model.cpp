#include "achd/model.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/dynamics.hpp"
#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"
#include "achd/kinematics.hpp"

namespace achd {

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Prismatic: return "prismatic";
  }
  return "unknown";
}

void Model::set_rotor_inertia(int joint, double value) {
  if (joint < 0 || joint >= num_joints())
    throw Error("set_rotor_inertia: joint index " + std::to_string(joint) + " is out of range [0, " +
                std::to_string(num_joints()) + ")");
  if (!std::isfinite(value) || value < 0)
    throw Error("set_rotor_inertia: joint '" + bodies[joint].joint_name +
                "': rotor inertia must be finite and >= 0");
  bodies[joint].rotor_inertia = value;
}

int Model::joint_index(const std::string& name) const {
  for (int i = 0; i < num_joints(); ++i)
    if (bodies[i].joint_name == name) return i;
  return -1;
}

int Model::link_index(const std::string& name) const {
  for (int i = 0; i < num_links(); ++i)
    if (links[i].name == name) return i;
  return -1;
}

namespace {

bool finite(const Matrix6& m) { return m.allFinite(); }

// Size of the inertia a joint could move: the trace of the rotational (revolute) or
// linear (prismatic) 3x3 block of the composite inertia Ic_i of bodies i..n-1 about
// body i's origin, Ic_i = I_i + X_{i+1}^T Ic_{i+1} X_{i+1} (RBDA 6.2).
std::vector<double> composite_scale(const Model& model, const Eigen::VectorXd& q) {
  const int n = model.num_joints();
  std::vector<double> scale(n);
  Matrix6 Ic = Matrix6::Zero();
  for (int i = n - 1; i >= 0; --i) {
    if (i < n - 1) Ic = inertia_to_parent(joint_transform(model.bodies[i + 1], q[i + 1]), Ic);
    Ic += model.bodies[i].inertia;
    scale[i] = model.bodies[i].type == JointType::Prismatic ? Ic.topLeftCorner<3, 3>().trace()
                                                            : Ic.bottomRightCorner<3, 3>().trace();
  }
  return scale;
}

// A joint moves nothing when D_i = S^T IA_i S vanishes: when nothing after it has inertia
// along its motion (M_ii = S^T Ic_i S = 0) or later joints free that motion again. An
// exact zero comes out of the sweeps as the round-off of the terms they accumulate, at
// most ~ n eps times their size (Ic_i for M_ii, M_ii for D_i); 100 n eps leaves a margin
// of 100. A genuine D can be far below M_ii: a light link ahead of a chain 1e12 times
// heavier gives D / M_ii ~ 1e-10, which is a valid (badly conditioned) robot.
void check_joints_move_something(const Model& model, const Eigen::VectorXd& q) {
  const Eigen::MatrixXd M = crba(model, q, false);
  const std::vector<double> scale = composite_scale(model, q);
  Data data(model);
  Case c = Case::zeros(model);
  c.q = q;
  Options options;
  options.effects = 0;  // pure inertia: D without rotor, no forces
  hybrid_dynamics(model, data, c, options);
  const double round_off = 100 * model.num_joints() * std::numeric_limits<double>::epsilon();
  for (int i = 0; i < model.num_joints(); ++i) {
    if (!(M(i, i) > round_off * scale[i]) || !(data.D[i] > round_off * M(i, i)))
      throw Error("joint '" + model.bodies[i].joint_name +
                  "' moves nothing: the links after it have no mass or inertia along its "
                  "motion (D = S^T IA S = 0)");
  }
}

}  // namespace

void validate(const Model& model) {
  if (model.num_joints() == 0)
    throw Error("the chain from '" + model.root_name + "' to '" + model.tip_name +
                "' has no movable joint");
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    const std::string where = "joint '" + b.joint_name + "'";
    if (b.parent != i - 1) throw Error(where + ": bodies must form a chain in order");
    if (!b.axis.allFinite() || std::abs(b.axis.norm() - 1) > 1e-9)
      throw Error(where + ": axis must be a finite unit vector");
    if (!b.X_tree.R.allFinite() || !b.X_tree.p.allFinite())
      throw Error(where + ": origin is not finite");
    if (!finite(b.inertia)) throw Error("link '" + b.link_name + "': inertia is not finite");
    if (!std::isfinite(b.damping) || b.damping < 0)
      throw Error(where + ": damping must be finite and >= 0");
    if (!std::isfinite(b.friction) || b.friction < 0)
      throw Error(where + ": friction must be finite and >= 0");
    if (!std::isfinite(b.rotor_inertia) || b.rotor_inertia < 0)
      throw Error(where + ": rotor inertia must be finite and >= 0");
    Eigen::SelfAdjointEigenSolver<Matrix6> eig(b.inertia, Eigen::EigenvaluesOnly);
    if (eig.eigenvalues().minCoeff() < -1e-9 * std::max(1.0, eig.eigenvalues().maxCoeff()))
      throw Error("link '" + b.link_name + "': spatial inertia is not positive semi-definite");
  }
  if (model.links.empty() || model.links.back().name != model.tip_name)
    throw Error("the model's last link must be the tip '" + model.tip_name + "'");
  // Two configurations: the zero pose and a generic one (within limits).
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.num_joints());
  check_joints_move_something(model, q);
  for (int i = 0; i < model.num_joints(); ++i) {
    const JointLimits& l = model.bodies[i].limits;
    const double lo = std::max(l.lower, -3.0), hi = std::min(l.upper, 3.0);
    q[i] = lo + (0.3 + 0.37 * ((i * 7) % 5) / 4.0) * (hi - lo);
  }
  check_joints_move_something(model, q);
}

}  // namespace achd
