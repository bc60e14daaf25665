#pragma once
// The joint torques of a wrench along a path to the base, J^T w: the constraint forces'
// torques after a solve (constraint_sweep.cpp's constraint_wrenches_and_joint_torques and
// constraint_force_torques).
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "free_joint.hpp"
#include "joint_subspace.hpp"

namespace achd {

// With the free joint's 6-DoF step every path ends in the free joint's six bodies, which
// share the root's origin p: the wrenches are summed there, [f; n + (x - p) x f] for a
// wrench [f; n] at x, and the six joints take the sum once (free_joint_wrench_torques).
struct RootWrench {
  Vector3 f = Vector3::Zero(), n = Vector3::Zero();
  void add(const Vector3& x_from_p, const Vector3& fx, const Vector3& nx) {
    f += fx;
    n += nx + x_from_p.cross(fx);
  }
};

// The joints of `last` and after on the path from body b: tau_i += sign z_i . (n + (x -
// p_i) x f) (revolute) or sign z_i . f (prismatic) for the wrench [f; n] at x; what is left
// for the free joint's bodies goes into root (when last > 0). Returns the finite probe.
template <int Sign>
inline double wrench_torques(const Model& model, Data& d, int b, const Vector3& x, const Vector3& f, const Vector3& n,
                             int last, RootWrench& root) {
  double probe = 0;
  for (int i = b; i >= last; i = model.bodies[i].parent) {
    const JointSubspace S = body_subspace(model, d, i);
    const double along = S.rotational ? S.z.dot(n + (x - d.X0[i].p).cross(f)) : S.z.dot(f);
    if constexpr (Sign > 0) d.joint_torques[i] += along;
    else d.joint_torques[i] -= along;
    probe += d.joint_torques[i] * 0.0;
  }
  if (last > 0) {
    if constexpr (Sign > 0) root.add(x - d.X0[kFreeJointBodies - 1].p, -f, -n);
    else root.add(x - d.X0[kFreeJointBodies - 1].p, f, n);
  }
  return probe;
}

// The opposite wrench [f; n] of a relative block at its second point Q, along Q's path
// (tau_i += ..., wrench_torques). (Out of line: the blocks on one link never come here.)
__attribute__((noinline)) inline double add_opposite_wrench(const Model& model, Data& d, const ConstraintSource& s,
                                                            const Vector3& f, const Vector3& n, int last,
                                                            RootWrench& root) {
  const Vector3 q = s.body_b < 0 ? s.arm_b : Vector3(d.X0[s.body_b].p + s.arm_b);
  return wrench_torques<+1>(model, d, s.body_b, q, f, n, last, root);
}

// The wrench [f; n] of source s at its point p, on every joint of its path
// (tau_i -= ..., wrench_torques).
inline double subtract_wrench_torques(const Model& model, Data& d, const ConstraintSource& s, const Vector3& f,
                                      const Vector3& n, int last, RootWrench& root) {
  const Vector3 p = s.body < 0 ? s.arm : Vector3(d.X0[s.body].p + s.arm);
  return wrench_torques<-1>(model, d, s.body, p, f, n, last, root);
}

// The sum of the opposite wrenches at a shared second body b's origin, along b's path.
// (Out of line: other blocks never come here.)
__attribute__((noinline)) inline double add_shared_opposite_wrench(const Model& model, Data& d, int b,
                                                                   const Vector3& f, const Vector3& n, int last,
                                                                   RootWrench& root) {
  ConstraintSource shared;  // acting at b's origin: arm_b = 0
  shared.body_b = b;
  return add_opposite_wrench(model, d, shared, f, n, last, root);
}

// The free joint's six torques from the wrench summed at the root's origin:
// tau_k -= z_k . f (prismatic, bodies 0 to 2) or z_k . n (revolute, 3 to 5).
inline double free_joint_wrench_torques(const Model& model, Data& d, const RootWrench& root) {
  double probe = 0;
  for (int k = 0; k < kFreeJointBodies; ++k) {
    const JointSubspace S = body_subspace(model, d, k);
    d.joint_torques[k] -= S.z.dot(S.rotational ? root.n : root.f);
    probe += d.joint_torques[k] * 0.0;
  }
  return probe;
}

}  // namespace achd
