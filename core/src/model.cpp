#include "achd/model.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/dynamics.hpp"
#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"

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

// D_i = S^T IA_i S at configuration q must be a healthy fraction of the composite
// inertia M_ii = S^T I^c_i S: both vanish when nothing after the joint has inertia
// about its axis, and D alone vanishes when a later joint frees that motion again.
void check_joints_move_something(const Model& model, const Eigen::VectorXd& q) {
  const Eigen::MatrixXd M = crba(model, q, false);
  Data data(model);
  Case c = Case::zeros(model);
  c.q = q;
  Options options;
  options.effects = 0;  // pure inertia: D without rotor, no forces
  hybrid_dynamics(model, data, c, options);
  for (int i = 0; i < model.num_joints(); ++i) {
    if (!(M(i, i) > 0) || !(data.D[i] > 1e-9 * M(i, i)))
      throw Error("joint '" + model.bodies[i].joint_name +
                  "' moves nothing: the links after it have no mass or inertia about its axis "
                  "(D = 0)");
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
