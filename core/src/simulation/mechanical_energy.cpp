// Kinetic and potential energy of the simulated chain, O(n) from the body velocities.
// Each query sweeps the chain into the calling thread's ChainMotion (see simulator.hpp:
// the const queries write nothing in the simulator).
#include "achd/simulator.hpp"
#include "tip_kinematics.hpp"

namespace achd {

namespace {

// T = 1/2 sum_i v_i^T I_i v_i (+ 1/2 sum_i rotor_i qd_i^2) = 1/2 qd^T (M + diag(rotor)) qd,
// with v_i turned into body axes (R^T v, about the body origin) to meet I_i there.
double kinetic(const Model& model, const ChainMotion& m, const Eigen::VectorXd& qd, bool rotor) {
  double T = 0;
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    const Matrix3& R = m.X0[i].R;
    Vector6 vb;
    vb << R.transpose() * m.v[i].head<3>(), R.transpose() * m.v[i].tail<3>();
    T += vb.dot(b.inertia * vb);
    if (rotor) T += b.rotor_inertia * qd[i] * qd[i];
  }
  return 0.5 * T;
}

// V = - sum_i m_i g . c_i, with c_i = p_i + R_i com_i the body's centre of mass in the base.
double potential(const ChainMotion& m, const std::vector<double>& mass,
                 const std::vector<Vector3>& com, const Vector3& gravity) {
  double V = 0;
  for (size_t i = 0; i < mass.size(); ++i) V -= mass[i] * gravity.dot(m.X0[i].p + m.X0[i].R * com[i]);
  return V;
}

}  // namespace

double Simulator::kinetic_energy() const {
  return kinetic(model_, thread_chain_motion(model_, q, qd), qd, options_.effects & kRotorInertia);
}

double Simulator::potential_energy() const {
  if (!(options_.effects & kGravity)) return 0;
  return potential(thread_chain_motion(model_, q, qd), mass_, com_, options_.gravity);
}

double Simulator::energy() const {
  const ChainMotion& m = thread_chain_motion(model_, q, qd);
  const double T = kinetic(model_, m, qd, options_.effects & kRotorInertia);
  return T + (options_.effects & kGravity ? potential(m, mass_, com_, options_.gravity) : 0.0);
}

}  // namespace achd
