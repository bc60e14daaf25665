#pragma once
// Pose and velocity of a point of a link (the tip's origin, or any link's point) in the
// base frame, with a caller-owned workspace so that the simulator's step never allocates.
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

struct TipState {
  Transform pose;  // base frame -> the link's frame moved to the point
  Vector3 v = Vector3::Zero();  // linear velocity of the point, base orientation
  Vector3 w = Vector3::Zero();  // angular velocity, base orientation
};

// Body poses (kinematics.hpp's body_poses, as the solver sees them) and body velocities
// of the whole chain, in base axes about each body's origin:
// v_i = [v_p + w_p x r_i; w_p] + S qd_i. X0, r and v must hold num_rates() entries.
void body_motion(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                 std::vector<Transform>& X0, std::vector<Vector3>& r, std::vector<Vector6>& v);

// body_motion's output for the simulator's const queries, which must not write the
// simulator's workspace (two threads may query one simulator).
struct ChainMotion {
  std::vector<Transform> X0;
  std::vector<Vector3> r;
  std::vector<Vector6> v;
};

// body_motion into the calling thread's own ChainMotion, grown to the longest chain the
// thread has swept and never shrunk (entries past num_rates() are stale), so a thread
// allocates only on its first query of a longer chain. The reference is valid until the
// thread's next call.
const ChainMotion& thread_chain_motion(const Model& model, const Eigen::VectorXd& q,
                                       const Eigen::VectorXd& qd);

// Point `point` (link frame) of link `link` (Model::links index) from body_motion's
// output: p = X0_b * (offset * point);  v_p = v_b + w_b x (R0 o), w_p = w_b, with o the
// point's offset from its body's origin (base axes: R0 o = p - p_b).
TipState link_state(const Model& model, const std::vector<Transform>& X0, const std::vector<Vector6>& v,
                    int link, const Vector3& point);

// The tip link's origin (link_state of the last link at its origin).
TipState tip_state(const Model& model, const std::vector<Transform>& X0,
                   const std::vector<Vector6>& v);

}  // namespace achd
