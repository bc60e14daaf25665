// The simulator: state, held directions, and one step of the chosen integrator. Every
// state derivative is one hybrid_dynamics solve with the held set as alpha, beta.
#include "achd/simulator.hpp"

#include <cmath>

#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"
#include "held_directions.hpp"
#include "joint.hpp"
#include "tip_kinematics.hpp"

namespace achd {

namespace {

const char* const kDirectionNames[kNumDirections] = {"x", "y", "z", "rx", "ry", "rz"};

void check_direction(int index) {
  if (index < 0 || index >= kNumDirections)
    throw Error("direction index " + std::to_string(index) + " is not in 0..5 (x y z rx ry rz)");
}

void check_state(const Eigen::VectorXd& v, int n, const char* field) {
  if (v.size() != n)
    throw Error(std::string(field) + ": expected " + std::to_string(n) + " values, got " +
                std::to_string(v.size()));
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) throw Error(std::string(field) + "[" + std::to_string(i) + "] is not finite");
}

}  // namespace

const char* direction_name(int index) {
  check_direction(index);
  return kDirectionNames[index];
}

int index_of_direction(const std::string& name) {
  for (int k = 0; k < kNumDirections; ++k)
    if (name == kDirectionNames[k]) return k;
  return -1;
}

const char* integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return "explicit_euler";
    case Integrator::SemiImplicitEuler: return "semi_implicit_euler";
    case Integrator::RK4: return "rk4";
  }
  return "?";
}

Simulator::Simulator(const Model& model, const SimulatorOptions& options)
    : model_(model), options_(options), data_(model_), stage_data_(model_), case_(Case::zeros(model_)) {
  const int n = model_.num_joints();
  q = qd = ff_torques = Eigen::VectorXd::Zero(n);
  case_.qd = case_.ff_torques = Eigen::VectorXd::Zero(n);
  case_.f_ext.reserve(model_.num_links());
  limit_hits_.reserve(n);
  X0_.resize(n);
  r_.assign(n, Vector3::Zero());
  v_.assign(n, Vector6::Zero());
  q0_ = qd0_ = q_stage_ = qd_stage_ = Eigen::VectorXd::Zero(n);
  for (auto& k : k_q_) k = Eigen::VectorXd::Zero(n);
  for (auto& k : k_qd_) k = Eigen::VectorXd::Zero(n);
  // Mass and centre of mass from the spatial inertia [m 1, -m [c]x; m [c]x, I_o].
  for (const Body& b : model_.bodies) {
    const double m = b.inertia(0, 0);
    const Matrix3 mc = b.inertia.block<3, 3>(3, 0);  // m [c]x
    mass_.push_back(m);
    com_.push_back(m > 0 ? Vector3(Vector3(mc(2, 1), mc(0, 2), mc(1, 0)) / m) : Vector3::Zero());
    axial_inertia_.push_back(subspace_dot(b, inertia_times_subspace(b, b.inertia)));
  }
}

void Simulator::reset(const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0) {
  const int n = model_.num_joints();
  check_state(q0, n, "q0");
  if (qd0.size()) check_state(qd0, n, "qd0");
  q = q0;
  if (qd0.size()) qd = qd0;
  else qd.setZero(n);
  t = 0;
  held_ = HeldDirections{};
  direction_columns(held_, case_.alpha);
  max_residual_.fill(0);
  limit_hits_.clear();
}

void Simulator::set_direction(int index, DirectionMode mode, double setpoint) {
  check_direction(index);
  if (!std::isfinite(setpoint))
    throw Error(std::string("direction ") + kDirectionNames[index] + ": setpoint is not finite");
  held_.mode[index] = mode;
  held_.setpoint[index] = mode == DirectionMode::Accelerate ? setpoint : 0;
  held_.angle[index] = 0;
  held_.target[index] = 0;
  if (mode == DirectionMode::Hold && is_linear_direction(index))
    held_.target[index] = direction_axis(index).dot(tip_pose().p);
  max_residual_[index] = 0;
  direction_columns(held_, case_.alpha);
}

DirectionMode Simulator::direction_mode(int index) const {
  check_direction(index);
  return held_.mode[index];
}

double Simulator::setpoint(int index) const {
  check_direction(index);
  return held_.setpoint[index];
}

Transform Simulator::tip_pose() const {
  body_motion(model_, q, qd, X0_, r_, v_);
  return tip_state(model_, X0_, v_).pose;
}

Vector6 Simulator::tip_velocity() const {
  body_motion(model_, q, qd, X0_, r_, v_);
  const TipState tip = tip_state(model_, X0_, v_);
  Vector6 out;
  out << tip.v, tip.w;
  return out;
}

std::array<double, kNumDirections> Simulator::residuals() const {
  body_motion(model_, q, qd, X0_, r_, v_);
  const TipState tip = tip_state(model_, X0_, v_);
  std::array<double, kNumDirections> r{};
  for (int k = 0; k < kNumDirections; ++k) r[k] = direction_error(held_, k, tip);
  return r;
}

std::array<double, kNumDirections> Simulator::max_residuals() const {
  std::array<double, kNumDirections> r = residuals();
  for (int k = 0; k < kNumDirections; ++k) r[k] = std::max(std::abs(r[k]), max_residual_[k]);
  return r;
}

// x' = f(x) at x = (q, qd, angle): the held set's alpha (set with the directions) and
// beta at this state, one solve, and the held angles' rates e . w_tip.
void Simulator::evaluate(const Eigen::VectorXd& q_at, const Eigen::VectorXd& qd_at,
                         const std::array<double, kNumDirections>& angle, double w_n, Data& out,
                         std::array<double, kNumDirections>& angle_rate) {
  body_motion(model_, q_at, qd_at, X0_, r_, v_);
  const TipState tip = tip_state(model_, X0_, v_);
  stage_held_ = held_;
  stage_held_.angle = angle;
  direction_targets(stage_held_, tip, w_n, options_.stabilisation_damping,
                    options_.effects & kVelocityProducts, case_.beta);
  for (int k = 0; k < kNumDirections; ++k)
    angle_rate[k] = held_.mode[k] == DirectionMode::Hold && !is_linear_direction(k)
                        ? direction_axis(k).dot(tip.w) : 0.0;
  case_.q = q_at;
  case_.qd = qd_at;
  hybrid_dynamics(model_, out, case_, solver_);
}

void Simulator::step(double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw Error("step: dt must be positive and finite");
  solver_ = options_.solver;
  solver_.effects = options_.effects;
  solver_.convention = Convention::Physical;
  solver_.friction_velocity = friction_velocity(dt);
  case_.gravity = options_.gravity;
  case_.ff_torques = ff_torques;
  case_.f_ext = f_ext;
  // Record the residuals of the state this step starts from.
  body_motion(model_, q, qd, X0_, r_, v_);
  const TipState tip = tip_state(model_, X0_, v_);
  for (int k = 0; k < kNumDirections; ++k)
    max_residual_[k] = std::max(max_residual_[k], std::abs(direction_error(held_, k, tip)));

  const double w_n = options_.stabilisation_frequency > 0 ? options_.stabilisation_frequency
                                                          : kBaumgarteStepFraction / dt;
  switch (options_.integrator) {
    case Integrator::ExplicitEuler: step_explicit_euler(dt, w_n); break;
    case Integrator::SemiImplicitEuler: step_semi_implicit_euler(dt, w_n); break;
    case Integrator::RK4: step_rk4(dt, w_n); break;
  }
  t += dt;
  apply_limits();
}

// v_f >= F_i dt / (kFrictionRateLimit I_i), from F_i / v_f dt / I_i <= kFrictionRateLimit.
double Simulator::friction_velocity(double dt) const {
  double v_f = options_.solver.friction_velocity;
  if (!(options_.effects & kFriction)) return v_f;
  const bool rotor = options_.effects & kRotorInertia;
  for (int i = 0; i < model_.num_joints(); ++i) {
    const Body& b = model_.bodies[i];
    const double inertia = axial_inertia_[i] + (rotor ? b.rotor_inertia : 0.0);
    v_f = std::max(v_f, b.friction * dt / (kFrictionRateLimit * inertia));
  }
  return v_f;
}

void Simulator::run(int steps, double dt) {
  for (int s = 0; s < steps; ++s) step(dt);
}

// x_{k+1} = x_k + dt f(x_k)
void Simulator::step_explicit_euler(double dt, double w_n) {
  evaluate(q, qd, held_.angle, w_n, data_, k_angle_[0]);
  q += dt * qd;
  qd += dt * data_.qdd;
  for (int k = 0; k < kNumDirections; ++k) held_.angle[k] += dt * k_angle_[0][k];
}

// qd_{k+1} = qd_k + dt qdd(q_k, qd_k);  q_{k+1} = q_k + dt qd_{k+1}; the held angles
// (positions too) advance with the new velocity: dt e . w(q_k, qd_{k+1}).
void Simulator::step_semi_implicit_euler(double dt, double w_n) {
  evaluate(q, qd, held_.angle, w_n, data_, k_angle_[0]);
  qd += dt * data_.qdd;
  body_motion(model_, q, qd, X0_, r_, v_);
  const Vector3 w = tip_state(model_, X0_, v_).w;
  for (int k = 0; k < kNumDirections; ++k)
    if (held_.mode[k] == DirectionMode::Hold && !is_linear_direction(k))
      held_.angle[k] += dt * direction_axis(k).dot(w);
  q += dt * qd;
}

// Classical Runge-Kutta: k1 = f(x), k2 = f(x + dt/2 k1), k3 = f(x + dt/2 k2),
// k4 = f(x + dt k3);  x_{k+1} = x + dt/6 (k1 + 2 k2 + 2 k3 + k4).
void Simulator::step_rk4(double dt, double w_n) {
  q0_ = q;
  qd0_ = qd;
  angle0_ = held_.angle;
  static constexpr double kStageStep[4] = {0, 0.5, 0.5, 1.0};
  for (int s = 0; s < 4; ++s) {
    Data& out = s == 0 ? data_ : stage_data_;
    if (s == 0) {
      evaluate(q0_, qd0_, angle0_, w_n, out, k_angle_[0]);
    } else {
      const double h = kStageStep[s] * dt;
      q_stage_ = q0_ + h * k_q_[s - 1];
      qd_stage_ = qd0_ + h * k_qd_[s - 1];
      for (int k = 0; k < kNumDirections; ++k) angle_stage_[k] = angle0_[k] + h * k_angle_[s - 1][k];
      evaluate(q_stage_, qd_stage_, angle_stage_, w_n, out, k_angle_[s]);
    }
    k_q_[s] = s == 0 ? qd0_ : qd_stage_;
    k_qd_[s] = out.qdd;
  }
  const double w = dt / 6;
  q = q0_ + w * (k_q_[0] + 2 * k_q_[1] + 2 * k_q_[2] + k_q_[3]);
  qd = qd0_ + w * (k_qd_[0] + 2 * k_qd_[1] + 2 * k_qd_[2] + k_qd_[3]);
  for (int k = 0; k < kNumDirections; ++k)
    held_.angle[k] = angle0_[k] + w * (k_angle_[0][k] + 2 * k_angle_[1][k] + 2 * k_angle_[2][k] + k_angle_[3][k]);
}

// Report: list the joints at or past a limit. Clamp: also put q back on the limit and
// zero the velocity component that points further into it.
void Simulator::apply_limits() {
  limit_hits_.clear();
  if (options_.limits == LimitPolicy::Ignore) return;
  for (int i = 0; i < model_.num_joints(); ++i) {
    const JointLimits& l = model_.bodies[i].limits;
    const bool low = q[i] <= l.lower, high = q[i] >= l.upper;
    if (!low && !high) continue;
    limit_hits_.push_back(i);
    if (options_.limits != LimitPolicy::Clamp) continue;
    q[i] = low ? l.lower : l.upper;
    if ((low && qd[i] < 0) || (high && qd[i] > 0)) qd[i] = 0;
  }
}

}  // namespace achd
