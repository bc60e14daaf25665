// The free joint's poses and its conversions between public and solver coordinates
// (free_joint.hpp states the equations).
#include "free_joint.hpp"

#include <cmath>

namespace achd {
namespace {

// Frames whose z axis is the world (or root) x and y axis: columns (e_y, e_z, e_x) and
// (e_z, e_x, e_y), right-handed.
Matrix3 z_along_x() {
  Matrix3 Q;
  Q << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  return Q;
}
Matrix3 z_along_y() {
  Matrix3 Q;
  Q << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  return Q;
}

}  // namespace

Matrix3 free_joint_rotation(const double* quaternion) {
  // Divided by its largest component first, so that neither 1e-200 nor 1e200 under- or
  // overflows on the way to unit length.
  const Eigen::Vector4d x = Eigen::Map<const Eigen::Vector4d>(quaternion);
  const Eigen::Vector4d unit = (x / x.lpNorm<Eigen::Infinity>()).normalized();
  const Eigen::Quaterniond h(unit[3], unit[0], unit[1], unit[2]);  // (w, x, y, z)
  return h.toRotationMatrix();
}

void free_joint_poses(const double* q, Transform* X0, Vector3* r) {
  const Vector3 p(q[0], q[1], q[2]);
  const Matrix3 R = free_joint_rotation(q + 3);
  const Matrix3 Qx = z_along_x(), Qy = z_along_y();
  const Matrix3 axes[kFreeJointBodies] = {Qx, Qy, Matrix3::Identity(), R * Qx, R * Qy, R};
  for (int k = 0; k < kFreeJointBodies; ++k) {
    X0[k] = Transform{axes[k], p};
    r[k] = k == 0 ? p : Vector3::Zero().eval();  // body 0 from the world origin, then none
  }
}

namespace {

// y = R x and y = R^T x on three numbers, y may be x. Written out in scalars: Emscripten
// 3.1.6's clang (-msimd128) got the first two rows of these Eigen products wrong when
// they were inlined into free_joint_results (the last row right: the wasm results of a
// floating base differed from the native ones there).
void rotate(const Matrix3& R, const double* x, double* y) {
  const double a = x[0], b = x[1], c = x[2];
  y[0] = R(0, 0) * a + R(0, 1) * b + R(0, 2) * c;
  y[1] = R(1, 0) * a + R(1, 1) * b + R(1, 2) * c;
  y[2] = R(2, 0) * a + R(2, 1) * b + R(2, 2) * c;
}
void rotate_back(const Matrix3& R, const double* x, double* y) {
  const double a = x[0], b = x[1], c = x[2];
  y[0] = R(0, 0) * a + R(1, 0) * b + R(2, 0) * c;
  y[1] = R(0, 1) * a + R(1, 1) * b + R(2, 1) * c;
  y[2] = R(0, 2) * a + R(1, 2) * b + R(2, 2) * c;
}

}  // namespace

void free_joint_rates(const Matrix3& R, const double* in, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = in[k];
  rotate_back(R, in + 3, out + 3);
}

Vector3 free_joint_rotation_product(const Matrix3& R, const double* u) {
  const Vector3 w3 = R.col(0) * u[0], w4 = R.col(1) * u[1], w5 = R.col(2) * u[2];
  return w3.cross(w4) + (w3 + w4).cross(w5);
}

void free_joint_accelerations_to_public(const Matrix3& R, const double* rates, double* qdd) {
  const Vector3 c = free_joint_rotation_product(R, rates + 3);
  rotate(R, qdd + 3, qdd + 3);
  for (int k = 0; k < 3; ++k) qdd[3 + k] += c[k];
}

void free_joint_accelerations_to_solver(const Matrix3& R, const double* rates, const double* in, double* out) {
  const Vector3 c = free_joint_rotation_product(R, rates + 3);
  const double x[3] = {in[3] - c[0], in[4] - c[1], in[5] - c[2]};
  for (int k = 0; k < 3; ++k) out[k] = in[k];
  rotate_back(R, x, out + 3);
}

void free_joint_torques_to_solver(const Matrix3& R, const double* in, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = in[k];
  rotate_back(R, in + 3, out + 3);
}

void free_joint_torques_to_public(const Matrix3& R, const double* in, double* out) {
  for (int k = 0; k < 3; ++k) out[k] = in[k];
  rotate(R, in + 3, out + 3);
}

JointInputs free_joint_inputs(const Matrix3& R, const Case& in, bool prescribed, Eigen::VectorXd& qd,
                              Eigen::VectorXd& ff_torques, Eigen::VectorXd& qdd_given) {
  if (in.qd.size()) qd = in.qd;
  else qd.setZero();
  free_joint_rates(R, qd.data(), qd.data());
  if (in.ff_torques.size()) ff_torques = in.ff_torques;
  else ff_torques.setZero();
  free_joint_torques_to_solver(R, ff_torques.data(), ff_torques.data());
  if (!prescribed) return {qd, ff_torques, in.qdd_given};
  qdd_given = in.qdd_given;
  if (in.prescribed[0]) free_joint_accelerations_to_solver(R, qd.data(), in.qdd_given.data(), qdd_given.data());
  return {qd, ff_torques, qdd_given};
}

void free_joint_results(const Eigen::VectorXd& solver_qd, Data& d) {
  const Matrix3& R = d.X0[kFreeJointBodies - 1].R;
  free_joint_accelerations_to_public(R, solver_qd.data(), d.qdd.data());
  for (Eigen::VectorXd* tau : {&d.constraint_torques, &d.total_torques, &d.joint_torques, &d.virtual_torques,
                               &d.prescribed_torques})
    free_joint_torques_to_public(R, tau->data(), tau->data());
}

}  // namespace achd
