#pragma once
// Forward kinematics, link velocities, the tip Jacobian and any link's Jacobian, each in two forms: one that
// returns a new value, and one that writes into caller-owned storage with a
// ChainWorkspace and allocates nothing (for loops: sizes stay those of the first call).
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// Scratch storage of the workspace forms of forward_kinematics, link_velocities,
// tip_jacobian, link_jacobian (kinematics.hpp), rnea and crba (dynamics.hpp): every vector holds one
// entry per body, sized by the constructor for `model`. One workspace per thread; its
// contents between calls mean nothing.
struct ChainWorkspace {
  explicit ChainWorkspace(const Model& model);
  std::vector<Transform> X0;        // body poses in the base (body_poses)
  std::vector<Vector3> r;           // body origin minus parent origin, base axes
  std::vector<Vector6> v, a, f;     // body velocities, accelerations, forces (RNEA)
  std::vector<Transform> Xup;       // parent body frame -> body frame (CRBA)
  std::vector<Matrix6> Ic;          // composite inertias (CRBA)
};

// Pose in the root frame of every link after the root (Model::links order).
std::vector<Transform> forward_kinematics(const Model& model, const Eigen::VectorXd& q);
// The same into `poses`, which is resized to num_links() if it is not that size already.
void forward_kinematics(const Model& model, const Eigen::VectorXd& q, ChainWorkspace& ws,
                        std::vector<Transform>& poses);

// Spatial velocity of every link after the root: linear velocity of the link origin and
// angular velocity, both in base orientation (zero for links fixed to the root).
std::vector<Vector6> link_velocities(const Model& model, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& qd);
// The same into `velocities`, resized to num_links() if it is not that size already.
void link_velocities(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     ChainWorkspace& ws, std::vector<Vector6>& velocities);

// Tip Jacobian (6 x nj): rows [linear; angular] of the tip link's origin, base
// orientation, so that [v_tip; w_tip] = J qd.
Eigen::MatrixXd tip_jacobian(const Model& model, const Eigen::VectorXd& q);
// The same into `J`, resized to 6 x nj if it is not that size already.
void tip_jacobian(const Model& model, const Eigen::VectorXd& q, ChainWorkspace& ws,
                  Eigen::MatrixXd& J);

// Jacobian (6 x nj) of link `link` (Model::links index) at `point` (in the link's frame):
// rows [linear velocity of the point; angular velocity], base orientation, so that
// [v_point; w_link] = J qd. Column j is joint j's unit motion seen at the point
// ([z_j x (p_point - p_j); z_j] revolute, [z_j; 0] prismatic) for the joints on the path
// from the root to the link, zero for every other joint (other branches of a tree, and
// all of them for a link fixed to the root). Throws achd::Error on a link index out of range.
Eigen::MatrixXd link_jacobian(const Model& model, const Eigen::VectorXd& q, int link,
                              const Vector3& point = Vector3::Zero());
// The same into `J`, resized to 6 x nj if it is not that size already.
void link_jacobian(const Model& model, const Eigen::VectorXd& q, int link, const Vector3& point,
                   ChainWorkspace& ws, Eigen::MatrixXd& J);

// The configuration reached from q by moving with the rates v (one per joint, as qd) for
// a time h: each joint's position by h v_i; a floating base's origin by h v_lin and its
// orientation by the turn exp(h w) about the world axes (its quaternion multiplied on the
// left by [sin(|h w|/2) w/|w|, cos(|h w|/2)], then normalised). What the integrators use
// for q' = "q + h qd". `out` may be q; sized as q; allocates nothing when it has that size.
void integrate(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double h,
               Eigen::VectorXd& out);

// dq/dt for the rates v: v_i for each joint; a floating base's position v_lin and its
// quaternion 1/2 [w; 0] (x) quaternion (w in world axes). The integrators of the simulator
// combine these as vectors, then normalise_configuration(); sized as q.
void configuration_rate(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        Eigen::VectorXd& rate);
// A floating base's quaternion made unit again (nothing else changes).
void normalise_configuration(const Model& model, Eigen::VectorXd& q);

// Joint transform of one body at q: parent body frame -> body frame.
Transform joint_transform(const Body& body, double q);

// Every body's pose at q, the one computation of it that the solver, RNEA and the
// kinematics share (so that they see the same rounded geometry): X0_i = X0_parent Xup_i,
// the pose in the base, with R_i = (R_parent R_tree) Rz(q_i) for a revolute joint, and
// r_i = p_i - p_parent in base axes, computed as R_parent p_tree (+ q_i z_i, prismatic)
// rather than as a difference. The vectors must hold num_rates() entries; nothing is
// allocated.
void body_poses(const Model& model, const Eigen::VectorXd& q, std::vector<Transform>& X0,
                std::vector<Vector3>& r);

// Checks a model built in code: rotations orthonormal, inertias physical, positions and
// inertias shifted along the chain finite (no overflow), every joint with something to
// move (D > 0) at the zero and a generic configuration. Throws achd::Error naming the
// joint or link. The URDF loader calls it; call it after building a Model by hand. (It
// moves the model through its configurations, hence its place beside the kinematics.)
void validate(const Model& model);

}  // namespace achd
