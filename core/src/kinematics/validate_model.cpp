// validate(Model): the checks of a model built in code or loaded. They sit above the
// model, in the kinematics layer, because two of them move the model: the origins and
// inertias shifted along the tree must stay finite, and every joint must move something
// at the configurations free_motions.hpp picks.
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "free_motions.hpp"

namespace achd {

namespace {

bool finite(const Matrix6& m) { return m.allFinite(); }

// Origins whose shifts overflow: every body's position from the root and every composite
// inertia (what a joint carries, moved to the joint before it) must be finite at q. Each
// origin and inertia is finite on its own (checked before); their sums and the shift's
// m |p|^2 can still overflow (two joints 1e200 m apart). Names the joint whose origin
// made the number overflow.
void check_no_overflow(const Model& model, const Eigen::VectorXd& q) {
  const int n = model.num_rates();
  std::vector<Transform> X(n), pose(n);  // parent -> body; body in the root frame
  for (int i = 0; i < n; ++i) {
    const int p = model.bodies[i].parent;
    X[i] = joint_transform(model.bodies[i], q[i]);
    pose[i] = p < 0 ? X[i] : pose[p] * X[i];
    if (!pose[i].p.allFinite())
      throw Error("joint '" + model.bodies[i].joint_name +
                  "': origin overflows: its position from the root is not finite");
  }
  // Composite inertia of the subtree of body i, in body i's frame: its own (finite,
  // checked before), plus each child's composite moved to it (children come after their
  // parent, so a body's composite is complete when the loop reaches it).
  std::vector<Matrix6> Ic(n);
  for (int i = 0; i < n; ++i) Ic[i] = model.bodies[i].inertia;
  for (int i = n - 1; i >= 0; --i) {
    const int p = model.bodies[i].parent;
    if (p < 0) continue;
    Matrix6 next = Ic[p];
    add_inertia_to_parent(X[i], Ic[i], next);
    if (!finite(next))
      throw Error("joint '" + model.bodies[i].joint_name + "': origin overflows: the inertia of the "
                  "links after it, moved to joint '" + model.bodies[p].joint_name + "', is not finite");
    Ic[p] = next;
  }
}

}  // namespace

void validate(const Model& model) {
  if (model.num_rates() == 0)
    throw Error(model.has_tip() ? "the chain from '" + model.root_name + "' to '" + model.tip_name +
                                      "' has no movable joint"
                                : "the tree below '" + model.root_name + "' has no movable joint");
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    const std::string where = "joint '" + b.joint_name + "'";
    if (b.parent < -1 || b.parent >= i)
      throw Error(where + ": its parent body must come before it (parent " + std::to_string(b.parent) + ")");
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
      throw Error("link '" + b.link_name + "': spatial inertia is not positive semi-definite (with the links fixed "
                  "to it); a URDF loads with the inertia option 'repair' (CLI --inertia repair), which makes each "
                  "link's inertia physical");
  }
  if (model.has_tip() && (model.links.empty() || model.links.back().name != model.tip_name))
    throw Error("the model's last link must be the tip '" + model.tip_name + "'");
  for (int l = 0; l < model.num_links(); ++l)
    if (model.links[l].body < -1 || model.links[l].body >= model.num_rates())
      throw Error("link '" + model.links[l].name + "': rides on body " + std::to_string(model.links[l].body) +
                  ", not a body of the model");
  if (model.couplings.size() > static_cast<size_t>(kMaxCouplings))
    throw Error("the model has " + std::to_string(model.couplings.size()) + " coupled joints, more than " +
                std::to_string(kMaxCouplings));
  std::vector<bool> follows(model.num_rates(), false);
  for (const JointCoupling& c : model.couplings) {
    const int first = model.free_joint_rates();
    if (c.follower < first || c.follower >= model.num_rates() || c.leader < first || c.leader >= model.num_rates())
      throw Error("a coupling names joint " + std::to_string(c.follower) + " or " + std::to_string(c.leader) +
                  ", not a movable joint of the model");
    const std::string where = "joint '" + model.bodies[c.follower].joint_name + "'";
    if (c.follower == c.leader) throw Error(where + ": coupled to itself");
    if (follows[c.follower]) throw Error(where + ": coupled twice");
    follows[c.follower] = true;
    if (!std::isfinite(c.multiplier) || !std::isfinite(c.offset))
      throw Error(where + ": coupling multiplier and offset must be finite");
  }
  for (const Eigen::VectorXd& q : check_configurations(model)) {
    check_no_overflow(model, q);
    const int i = joint_moving_nothing(model, q);
    if (i >= 0)
      throw Error("joint '" + model.bodies[i].joint_name + "' moves nothing: the links after it have no "
                  "mass or inertia along its motion, or later joints take that motion up (D = S^T IA S = 0); "
                  "a URDF loads with the inertia option 'repair' (CLI --inertia repair), which gives them a "
                  "floor mass, or with the joint held (--lock " + model.bodies[i].joint_name + "=VALUE)");
  }
}

}  // namespace achd
