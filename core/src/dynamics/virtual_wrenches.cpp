// J^T f for wrenches f_l on links l (each at its link's origin, base axes): joint i's
// torque is its axis' share of the wrenches on every link it carries, moved to its origin,
//   tau_i = S_i^T F_i,   F_i = sum of the links' f_l on body i (moved to its origin)
//                              + the children's F_c moved from their origins,
// one inward pass instead of a Jacobian per link.
#include "virtual_wrenches.hpp"

#include "joint_subspace.hpp"

namespace achd {

void virtual_torques(const Model& model, Data& d, const Case& c) {
  Data::Workspace& w = d.workspace;
  const int n = model.num_rates();
  for (int i = 0; i < n; ++i) w.virtual_force[i].setZero();
  for (int l = 0; l < model.num_links(); ++l) {
    const int b = model.links[l].body;
    if (b < 0) continue;  // a link fixed to the root: no joint moves it
    w.virtual_force[b] += force_shift(c.f_virtual[l], d.X0[b].R * model.links[l].offset.p);
  }
  for (int i = n - 1; i >= 0; --i) {
    const JointSubspace S = body_subspace(model, d, i);
    const Vector6& F = w.virtual_force[i];
    d.virtual_torques[i] = S.z.dot(S.rotational ? F.tail<3>() : F.head<3>());
    const int p = model.bodies[i].parent;
    if (p >= 0) w.virtual_force[p] += force_shift(F, d.r[i]);
  }
}

}  // namespace achd
