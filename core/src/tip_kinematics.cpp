#include "tip_kinematics.hpp"

#include "achd/kinematics.hpp"
#include "joint.hpp"

namespace achd {

void body_motion(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                 std::vector<Transform>& X0, std::vector<Vector6>& v) {
  for (int i = 0; i < model.num_joints(); ++i) {
    const Body& b = model.bodies[i];
    const Transform Xup = joint_transform(b, q[i]);
    const Vector6 vJ = subspace_times(b, qd[i]);
    if (b.parent < 0) {
      X0[i] = Xup;
      v[i] = vJ;
    } else {
      X0[i] = X0[b.parent] * Xup;
      v[i] = Xup.motion_to_child(v[b.parent]) + vJ;
    }
  }
}

TipState tip_state(const Model& model, const std::vector<Transform>& X0,
                   const std::vector<Vector6>& v) {
  const Link& tip = model.tip();
  TipState s;
  if (tip.body < 0) {
    s.pose = tip.offset;
    return s;
  }
  const Transform& X = X0[tip.body];
  const Vector6& vb = v[tip.body];
  s.pose = X * tip.offset;
  s.w = X.R * vb.tail<3>();
  s.v = X.R * (vb.head<3>() + vb.tail<3>().cross(tip.offset.p));
  return s;
}

}  // namespace achd
