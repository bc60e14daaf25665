#pragma once
// What a Simulator is set up with: its integrator, effects, limits, the stabilisation of
// held directions, the adaptive integrator's tolerances, and the joint PD controller.
#include <cstdint>

#include <Eigen/Core>

#include "achd/options.hpp"
#include "achd/spatial.hpp"

namespace achd {

// ExplicitEuler, SemiImplicitEuler, RK4: one fixed step of dt per step(dt).
// DormandPrince: the adaptive Dormand-Prince 5(4) pair (integrators/dormand_prince.cpp);
//   step(dt) takes as many error-controlled substeps as rtol/atol need to reach t + dt.
// ImplicitEuler: semi-implicit Euler that is implicit in joint damping and friction
//   (integrators/implicit_euler.cpp): stable for any dt on stiff passive terms, first order.
// New values go at the end: the enum value is the index of the name (names.hpp).
enum class Integrator { ExplicitEuler, SemiImplicitEuler, RK4, DormandPrince, ImplicitEuler };
enum class LimitPolicy { Ignore, Report, Clamp };

const char* integrator_name(Integrator integrator);

// The number of steps of dt in `duration` (seconds, >= 0): duration / dt rounded, when
// that is within 1e-9 (relative) of a whole number. An achd::Error naming the step
// count, dt and duration when it is not whole, exceeds 2^53 (kMaxSteps: beyond it a
// step count is no longer exact in a double), or when dt is below the spacing of
// doubles at the end time (t + dt == t: t = k dt would stop advancing; only possible
// above 2^52 steps).
constexpr std::int64_t kMaxSteps = std::int64_t(1) << 53;
std::int64_t steps_for_duration(double duration, double dt);

// Joint PD control toward a target pose (Simulator::set_joint_control): every solve adds
//   tau_i = kp_i (q_target,i - q_i) - kd_i qd_i + tau_hold,i
// to ff_torques for each joint (its position index for q). A floating base's free joint
// takes none (its gains are 0: nothing between the world and the root is actuated).
// The gains are given per joint (kp, kd), or by a natural frequency f (Hz) and a damping
// ratio zeta, the same for every joint (kp and kd left empty):
//   kp_i = m_i (2 pi f)^2,  kd_i = 2 zeta m_i (2 pi f),
// m_i the inertia joint i moves at the target while the other joints and the held links
// stay still (the joint-space inertia's M_ii when nothing is held; the rest of the robot
// for an ankle whose foot is held: anchored_inertia.hpp), so that each joint alone rings
// at f whatever it carries. They are recomputed when the held set changes.
// With hold, tau_hold are the torques that keep the robot at rest at the target under
// gravity with the held directions (hold_torques.hpp), recomputed when the target or the
// held set changes; without it, tau_hold = 0.
struct JointControl {
  Eigen::VectorXd target;  // Model::num_positions() numbers, a pose as q
  Eigen::VectorXd kp, kd;  // per joint, >= 0 (N m/rad or N/m; N m s/rad or N s/m)
  double frequency = 0;      // Hz, > 0 when kp and kd are empty
  double damping_ratio = 0;  // >= 0, with frequency
  bool hold = false;
};

// The physics of a scene does not depend on the step: friction's smoothing velocity
// (Options::friction_velocity, 0.05 by default) and the Baumgarte stabilisation of held
// directions are model parameters with fixed defaults. The default frequency, 100 rad/s
// at zeta = 1 (a held error decays as (1 + w t) e^-w t: to 1e-6 of itself within 0.2 s),
// keeps w dt inside the real-axis stability limit of every fixed-step integrator up to
// dt = 10 ms (explicit Euler: w dt < 2 at zeta = 1; RK4 2.785) and is the value the
// simulator used at its 1 ms default step when the frequency was derived from dt.
constexpr double kDefaultStabilisationFrequency = 100;

// The adaptive integrator's control (integrators/dormand_prince.cpp): a substep of h is
// accepted when the RMS over q, qd and the held angles of
// err_i / (atol + rtol max(|x_i|, |x_i'|)) is at most 1; the next h is
// h min(5, max(0.2, 0.9 err^-1/5)) (not grown after a rejection). A step fails when h
// falls below kMinSubstepFraction dt, after kMaxRejections rejections in a row, or when it
// has taken kMaxSubstepsPerStep substeps without reaching t + dt (a substep that keeps
// shrinking towards its floor would otherwise take hours).
constexpr double kDefaultRtol = 1e-9;
constexpr double kDefaultAtol = 1e-11;
constexpr double kMinSubstepFraction = 1e-10;
constexpr int kMaxRejections = 40;
constexpr std::int64_t kMaxSubstepsPerStep = 100000;

struct SimulatorOptions {
  Integrator integrator = Integrator::DormandPrince;
  std::uint32_t effects = kAllEffects;       // achd::Effect bits
  Vector3 gravity = Vector3(0, 0, -9.81);
  LimitPolicy limits = LimitPolicy::Report;
  // Baumgarte stabilisation of held directions: beta = -2 zeta w e_dot - w^2 e.
  double stabilisation_frequency = kDefaultStabilisationFrequency;  // w, rad/s, > 0
  double stabilisation_damping = 1.0;        // zeta
  // Tolerances of Integrator::DormandPrince (relative, absolute in rad, rad/s, m, m/s).
  double rtol = kDefaultRtol;
  double atol = kDefaultAtol;
  Options solver = robust_solver();          // policy, tolerances (effects are above)

  // The simulator's solver options: Options' defaults with the variable_damping policy, so
  // that a direction the robot cannot follow is damped, not solved to a force without bound.
  static Options robust_solver() {
    Options o;
    o.policy = SingularityPolicy::VariableDamping;
    return o;
  }
};

}  // namespace achd
