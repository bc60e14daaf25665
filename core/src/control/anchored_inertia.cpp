#include "anchored_inertia.hpp"

#include <algorithm>

#include "achd/kinematics.hpp"

namespace achd {

Eigen::VectorXd anchored_joint_inertias(const Model& model, const Eigen::VectorXd& q,
                                        const std::vector<int>& anchors) {
  const int n = model.num_rates(), first = model.free_joint_rates();
  std::vector<Transform> X0(n);
  std::vector<Vector3> r(n);
  body_poses(model, q, X0, r);
  // Bodies are in depth-first order: joint i's subtree is bodies i .. last[i].
  std::vector<int> last(n);
  for (int i = 0; i < n; ++i) last[i] = i;
  for (int j = n - 1; j >= 0; --j)
    if (model.bodies[j].parent >= 0) last[model.bodies[j].parent] = std::max(last[model.bodies[j].parent], last[j]);
  Eigen::VectorXd m = Eigen::VectorXd::Zero(n);
  for (int i = first; i < n; ++i) {
    const Vector3 z = X0[i].R.col(2), p = X0[i].p;
    const bool prismatic = model.bodies[i].type == JointType::Prismatic;
    double inside = 0, outside = 0;
    for (int b = 0; b < n; ++b) {
      // body b's twist [v; w] at its origin, its own axes, for joint i at unit rate
      const Vector3 w = prismatic ? Vector3::Zero() : z;
      const Vector3 v = prismatic ? z : Vector3(z.cross(X0[b].p - p));
      Vector6 V;
      V << X0[b].R.transpose() * v, X0[b].R.transpose() * w;
      const double e = V.dot(model.bodies[b].inertia * V);
      (b >= i && b <= last[i] ? inside : outside) += e;
    }
    bool anchor_in = false, anchor_out = !model.floating;  // a fixed base: the root
    for (int a : anchors) (a >= i && a <= last[i] ? anchor_in : anchor_out) = true;
    m[i] = (anchor_in && !anchor_out ? outside : anchor_in && anchor_out ? std::max(inside, outside) : inside) +
           model.bodies[i].rotor_inertia;
  }
  return m;
}

}  // namespace achd
