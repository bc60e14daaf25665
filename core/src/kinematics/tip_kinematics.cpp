#include "tip_kinematics.hpp"

#include "achd/kinematics.hpp"
#include "free_joint.hpp"
#include "joint.hpp"

namespace achd {

void body_motion(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                 std::vector<Transform>& X0, std::vector<Vector3>& r, std::vector<Vector6>& v) {
  body_poses(model, q, X0, r);
  double free_rates[kFreeJointBodies];  // a floating base's rates in the solver's form
  if (model.floating) free_joint_rates(X0[kFreeJointBodies - 1].R, qd.data(), free_rates);
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    const double rate = model.floating && i < kFreeJointBodies ? free_rates[i] : qd[i];
    const Vector3 zq = X0[i].R.col(2) * rate;  // S qd: about (revolute) or along z
    Vector6& vi = v[i];
    if (b.parent < 0) vi.setZero();
    else vi = motion_shift(v[b.parent], r[i]);
    if (is_rotational(b)) vi.tail<3>() += zq;
    else vi.head<3>() += zq;
  }
}

const ChainMotion& thread_chain_motion(const Model& model, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& qd) {
  thread_local ChainMotion m;
  const size_t n = model.num_rates();
  if (m.X0.size() < n) {
    m.X0.resize(n);
    m.r.resize(n);
    m.v.resize(n);
  }
  body_motion(model, q, qd, m.X0, m.r, m.v);
  return m;
}

TipState link_state(const Model& model, const std::vector<Transform>& X0, const std::vector<Vector6>& v,
                    int link, const Vector3& point) {
  const Link& l = model.links[link];
  Transform at = l.offset;
  if (point.x() != 0 || point.y() != 0 || point.z() != 0) at.p += l.offset.R * point;  // (the origin: as is)
  TipState s;
  if (l.body < 0) {
    s.pose = at;
    return s;
  }
  const Transform& X = X0[l.body];
  const Vector6& vb = v[l.body];
  s.pose = X * at;
  s.w = vb.tail<3>();
  s.v = vb.head<3>() + vb.tail<3>().cross(X.R * at.p);
  return s;
}

TipState tip_state(const Model& model, const std::vector<Transform>& X0,
                   const std::vector<Vector6>& v) {
  return link_state(model, X0, v, model.num_links() - 1, Vector3::Zero());
}

}  // namespace achd
