#include "achd/model.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "joint.hpp"

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

// The trace of the rotational (revolute) or linear (prismatic) 3x3 block of a spatial
// inertia about its frame origin: the size of what a joint of that type could move.
double block_trace(const Body& b, const Matrix6& I) {
  return b.type == JointType::Prismatic ? I.topLeftCorner<3, 3>().trace()
                                        : I.bottomRightCorner<3, 3>().trace();
}

// A joint moves nothing when D_i = S^T IA_i S vanishes: when nothing after it has inertia
// along its motion (M_ii = S^T Ic_i S = 0) or later joints free that motion again. An
// exact zero comes out of the sweeps as the round-off of the terms they accumulate, at
// most ~ n eps times their size (the composite inertia Ic_i for M_ii, M_ii for D_i);
// 100 n eps leaves a margin of 100. A genuine D can be far below M_ii: a light link
// ahead of a chain 1e12 times heavier gives D / M_ii ~ 1e-10, a valid (badly
// conditioned) robot. Inward sweep, from the tip (RBDA 6.2 and 7.3):
//   Ic_i = I_i + X^T Ic_{i+1} X,   IA_i = I_i + X^T (IA_{i+1} - U U^T / D_{i+1}) X,
//   U = IA_i S,  D_i = S^T U,  M_ii = S^T Ic_i S.
void check_joints_move_something(const Model& model, const Eigen::VectorXd& q) {
  const int n = model.num_joints();
  const double round_off = 100 * n * std::numeric_limits<double>::epsilon();
  Matrix6 Ic = Matrix6::Zero(), Ia = Matrix6::Zero();  // of body i+1, in its own frame
  for (int i = n - 1; i >= 0; --i) {
    const Body& b = model.bodies[i];
    Matrix6 IA = b.inertia;
    Matrix6 IC = b.inertia;
    if (i < n - 1) {
      const Transform X = joint_transform(model.bodies[i + 1], q[i + 1]);
      IA += inertia_to_parent(X, Ia);
      IC += inertia_to_parent(X, Ic);
    }
    const Vector6 S = subspace_times(b, 1.0);
    const Vector6 U = IA * S;
    const double D = S.dot(U), M_ii = S.dot(IC * S);
    if (!(M_ii > round_off * block_trace(b, IC)) || !(D > round_off * M_ii))
      throw Error("joint '" + b.joint_name + "' moves nothing: the links after it have no mass "
                  "or inertia along its motion (D = S^T IA S = 0)");
    Ia = IA - U * U.transpose() / D;
    Ic = IC;
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
    if (!b.X_tree.R.allFinite() || !b.X_tree.p.allFinite())
      throw Error(where + ": origin is not finite");
    if (!(b.X_tree.R.transpose() * b.X_tree.R).isIdentity(1e-9) || b.X_tree.R.determinant() < 0)
      throw Error(where + ": origin rotation is not a rotation matrix");
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
