#pragma once
// The free joint of a floating base (Model::floating), between the world and the root link.
//
// Its public coordinates (the case format, docs/guide/trees-and-constraints.md, "Floating base"):
//   q  = [x, y, z, qx, qy, qz, qw]: the root link's origin p in the world and its orientation
//        as a unit quaternion (scalar last; normalised before use), R its rotation matrix;
//   qd = [v; w]: the velocity of the root's origin and its angular velocity, world axes;
//   qdd = [dv/dt; dw/dt];  its torques: a wrench [f; n] on the root, world axes, about p.
//
// Inside the solvers the free joint is six bodies, 0 to 5, of one-axis joints meeting at p:
// prismatic along the world x, y, z, then revolute about the root's own x, y, z axes
// (R e_x, R e_y, R e_z); body 5 carries the root link. Their poses come from q (never from
// angles of their own, so no orientation is singular) and their rates are
//   qd_s = [v; u],  u = R^T w   (since w = sum_k (R e_k) u_k).
// In this chain the velocity-product accelerations of the revolute bodies add up to
//   c = [v x w;  w3 x w4 + (w3 + w4) x w5],  w_k = (R e_k) u_k,
// so the root's spatial acceleration is a = [qdd_s,lin; R qdd_s,rot] + c, and with
// dv/dt = a_lin + w x v (spatial to classical acceleration of the origin):
//   dv/dt = qdd_s,lin,   dw/dt = R qdd_s,rot + c_rot.
// Torques map as the power they do: tau_s,lin = f, tau_s,rot = R^T n.
#include <Eigen/Core>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "joint_inputs.hpp"

namespace achd {

constexpr int kFreeJointBodies = 6;

// R from q[3..6] = (qx, qy, qz, qw), normalised; the quaternion must be finite and nonzero
// (Case validation checks it).
Matrix3 free_joint_rotation(const double* quaternion);

// The six free-joint bodies' poses and shifts r (body_poses's outputs) from q[0..6].
void free_joint_poses(const double* q, Transform* X0, Vector3* r);

// [v; w] (world) -> [v; R^T w], the bodies' rates. `in` and `out` may be the same.
void free_joint_rates(const Matrix3& R, const double* in, double* out);
// c_rot of the revolute bodies for rates u = qd_s[3..5] (above).
Vector3 free_joint_rotation_product(const Matrix3& R, const double* u);
// Solver accelerations qdd_s -> [dv/dt; dw/dt] = [qdd_lin; R qdd_rot + c_rot], in place.
void free_joint_accelerations_to_public(const Matrix3& R, const double* rates, double* qdd);
// [dv/dt; dw/dt] -> qdd_s = [dv/dt; R^T (dw/dt - c_rot)].
void free_joint_accelerations_to_solver(const Matrix3& R, const double* rates, const double* in, double* out);
// Torques: [f; R^T n] <-> [f; n] (in place allowed).
void free_joint_torques_to_solver(const Matrix3& R, const double* in, double* out);
void free_joint_torques_to_public(const Matrix3& R, const double* in, double* out);

// The case's joint inputs in the solver's coordinates: qd and ff_torques, and when
// `prescribed` (in.any_prescribed()) qdd_given, copied full length into the given vectors
// (of the model's num_rates(), so that nothing is allocated) with the free joint's entries
// converted by R, free_joint_rotation of in.q (body 5's pose: a solve has it in its X0).
// Without prescribed joints qdd_given is the case's own (not read).
JointInputs free_joint_inputs(const Matrix3& R, const Case& in, bool prescribed, Eigen::VectorXd& qd,
                              Eigen::VectorXd& ff_torques, Eigen::VectorXd& qdd_given);
// The results of a solve in the solver's coordinates back in the public ones: qdd and
// every torque vector of `d` (solver_qd: the rates the solve took).
void free_joint_results(const Eigen::VectorXd& solver_qd, Data& d);

}  // namespace achd
