// Kinetic and potential energy of the simulated chain, O(n) from the body velocities.
#include "achd/simulator.hpp"
#include "tip_kinematics.hpp"

namespace achd {

// T = 1/2 sum_i v_i^T I_i v_i (+ 1/2 sum_i rotor_i qd_i^2) = 1/2 qd^T (M + diag(rotor)) qd,
// with v_i turned into body axes (R^T v, about the body origin) to meet I_i there.
double Simulator::kinetic_energy() const {
  body_motion(model_, q, qd, X0_, r_, v_);
  const bool rotor = options_.effects & kRotorInertia;
  double T = 0;
  for (int i = 0; i < model_.num_joints(); ++i) {
    const Body& b = model_.bodies[i];
    const Matrix3& R = X0_[i].R;
    Vector6 vb;
    vb << R.transpose() * v_[i].head<3>(), R.transpose() * v_[i].tail<3>();
    T += vb.dot(b.inertia * vb);
    if (rotor) T += b.rotor_inertia * qd[i] * qd[i];
  }
  return 0.5 * T;
}

// V = - sum_i m_i g . c_i, with c_i = p_i + R_i com_i the body's centre of mass in the base.
double Simulator::potential_energy() const {
  if (!(options_.effects & kGravity)) return 0;
  body_motion(model_, q, qd, X0_, r_, v_);
  double V = 0;
  for (int i = 0; i < model_.num_joints(); ++i)
    V -= mass_[i] * options_.gravity.dot(X0_[i].p + X0_[i].R * com_[i]);
  return V;
}

}  // namespace achd
