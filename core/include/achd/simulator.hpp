#pragma once
// Time stepping of a chain under the hybrid solver: state (q, qd, t), integrators, the
// effects a scene enables, and tip directions the user holds or accelerates.
//
// Directions are the base axes at the tip: x, y, z (linear) and rx, ry, rz (angular).
//   Hold, linear e:  keeps e . p_tip at its value when the direction was set.
//   Hold, angular e: keeps the integral of e . w_tip since it was set at zero.
//   Accelerate:      the classical tip acceleration along e equals the setpoint.
// A held direction becomes a column of alpha with a Baumgarte-stabilised beta, including
// the velocity-product term that separates spatial from classical acceleration.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/error.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

class DirectionEventLog;

enum class Integrator { ExplicitEuler, SemiImplicitEuler, RK4 };
enum class DirectionMode { Free, Hold, Accelerate };
enum class LimitPolicy { Ignore, Report, Clamp };

constexpr int kNumDirections = 6;
// "x", "y", "z", "rx", "ry", "rz"; index_of_direction returns -1 for anything else.
const char* direction_name(int index);
int index_of_direction(const std::string& name);
const char* integrator_name(Integrator integrator);

// The number of steps of dt in `duration` (seconds, >= 0): duration / dt rounded, when
// that is within 1e-9 (relative) of a whole number. An achd::Error naming the step
// count, dt and duration when it is not whole, exceeds 2^53 (kMaxSteps: beyond it a
// step count is no longer exact in a double), or when dt is below the spacing of
// doubles at the end time (t + dt == t: t = k dt would stop advancing; only possible
// above 2^52 steps).
constexpr std::int64_t kMaxSteps = std::int64_t(1) << 53;
std::int64_t steps_for_duration(double duration, double dt);

// The held set: one mode per direction, with what each mode needs.
struct HeldDirections {
  std::array<DirectionMode, kNumDirections> mode{};
  std::array<double, kNumDirections> setpoint{};  // Accelerate: classical acceleration
  std::array<double, kNumDirections> target{};    // Hold, linear: e . p_tip when set
  std::array<double, kNumDirections> angle{};     // Hold, angular: integral of e . w_tip

  bool active(int k) const { return mode[k] != DirectionMode::Free; }
  int count() const;
};

// Baumgarte frequency used when SimulatorOptions::stabilisation_frequency is 0:
// w_n = kBaumgarteStepFraction / dt (100 rad/s at dt = 1 ms), so w_n dt stays far
// inside the stability region of every integrator (explicit Euler: w_n dt < 2 at
// zeta = 1) and a held error decays by e^-0.1 per step.
constexpr double kBaumgarteStepFraction = 0.1;

// Friction is F tanh(qd / v_f): near qd = 0 it acts as a damper of F / v_f, stiff for
// a light distal joint (KUKA LWR joint 7 at v_f = 0.05: 8300 1/s). The simulator raises
// v_f, per step, so that friction adds at most kFrictionRateLimit / dt to any joint's
// linearised decay rate (b_i + F_i / v_f) / I_i, I_i being the joint's own body inertia
// about its axis (+ rotor): v_f >= F_i dt / (kFrictionRateLimit I_i). Damping's share
// b_i dt / I_i is the caller's choice of dt; the sum must stay inside the real-axis
// stability limit of the integrator (explicit and semi-implicit Euler 2, RK4 2.785).
constexpr double kFrictionRateLimit = 1.0;

// What became of an active direction, from the solve at the start of a step under the
// variable_damping policy (direction_events.cpp has the thresholds):
//   Limited:  damping acts on it (its eigen-direction of K is in the singular region);
//   Released: damping dominates (sigma <= lambda): the direction is no longer followed;
//   Resumed:  it has left the singular region. A released Hold direction resumes from
//             where the tip is: its target (linear: e . p_tip) or held angle (0) is reset
//             then, so the stabilisation does not pull the tip back to the old target.
enum class DirectionEventKind { Limited, Released, Resumed };
struct DirectionEvent {
  double t;            // time of the state whose solve showed the change (s)
  std::int64_t step;   // steps completed at that state (t = t0 + step dt)
  int link;            // index in Model::links of the link whose direction it is (the tip)
  int direction;       // 0..5: x y z rx ry rz
  DirectionEventKind kind;
  double sigma_min;    // the coupling matrix's smallest singular value in that solve
};
// The events a Simulator keeps (reserved at construction; later ones are counted in
// Simulator::events_not_kept()).
constexpr std::size_t kMaxDirectionEvents = 10000;

struct SimulatorOptions {
  Integrator integrator = Integrator::RK4;
  std::uint32_t effects = kAllEffects;       // achd::Effect bits
  Vector3 gravity = Vector3(0, 0, -9.81);
  LimitPolicy limits = LimitPolicy::Report;
  // Baumgarte stabilisation of held directions: beta = -2 zeta w e_dot - w^2 e.
  double stabilisation_frequency = 0;        // w in rad/s; 0 = chosen from dt
  double stabilisation_damping = 1.0;        // zeta
  Options solver = robust_solver();          // policy, tolerances (effects are above)

  // The simulator's solver options: Options' defaults with the variable_damping policy, so
  // that a direction the robot cannot follow is damped, not solved to a force without bound.
  static Options robust_solver() {
    Options o;
    o.policy = SingularityPolicy::VariableDamping;
    return o;
  }
};

class Simulator {
 public:
  Simulator(const Model& model, const SimulatorOptions& options = {});
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  // State, root to tip. Setting them directly is allowed; reset() also restarts t,
  // releases every direction and clears the drift and limit records.
  // t is t0 + k dt after the k-th step of dt since t was last set (by reset(), by the
  // caller, or by a change of dt): computed, not summed, so that k steps of dt from 0
  // end at exactly the double k * dt.
  Eigen::VectorXd q, qd;
  double t = 0;
  Eigen::VectorXd ff_torques;   // joint torques applied every step (default 0)
  std::vector<Vector6> f_ext;   // wrench per link after the root (base orientation)

  void reset(const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0);
  void set_direction(int index, DirectionMode mode, double setpoint = 0);
  DirectionMode direction_mode(int index) const;
  // One step of dt. A step whose solve fails (an achd::Error from the solver) or whose
  // state is not finite is undone: q, qd, t, the held angles and data() stay those of
  // the last good step, and an achd::Error names the step, the time, the integrator
  // stage, the held and accelerated directions and the cause. A q or qd the caller set
  // that is not finite is an achd::Error naming it ("q[3] is not finite"). The success
  // path does not allocate.
  void step(double dt);
  // `steps` (>= 0) steps of dt; stops at the first failed step (see step()).
  void run(std::int64_t steps, double dt);
  // Steps completed since construction or reset().
  std::int64_t steps_taken() const { return steps_taken_; }

  // The queries below (residuals to energy) compute from q and qd into scratch storage
  // of the calling thread and write nothing in the simulator: two threads may call them
  // at once on one simulator (while neither steps it nor sets its state). A thread's
  // first query (and its first of a longer chain) allocates that storage.
  // Held-direction residuals in m or rad (0 for directions that are not held).
  std::array<double, kNumDirections> residuals() const;
  // The largest |residual| of each direction since it was set (or since reset()).
  std::array<double, kNumDirections> max_residuals() const;
  double setpoint(int index) const;
  const HeldDirections& directions() const { return held_; }
  // Pose of the tip link in the base frame and its velocity [v; w] (base orientation).
  Transform tip_pose() const;
  Vector6 tip_velocity() const;
  double kinetic_energy() const;
  double potential_energy() const;  // gravity only; 0 when gravity is off
  double energy() const;  // kinetic_energy() + potential_energy(), from one sweep
  // The solve at the start of the last completed step (nu, joint torques, ...).
  const Data& data() const { return data_[current_]; }
  // The friction smoothing velocity a step of dt uses: max(options().solver.friction_velocity,
  // the stability floor above).
  double friction_velocity(double dt) const;
  const Model& model() const { return model_; }
  const SimulatorOptions& options() const { return options_; }
  SimulatorOptions& options() { return options_; }
  // Joints that were at or past a limit in the last step (LimitPolicy Report/Clamp).
  const std::vector<int>& limit_hits() const { return limit_hits_; }
  // Direction events since construction or reset(), oldest first (at most
  // kMaxDirectionEvents), and how many more happened but were not kept.
  const std::vector<DirectionEvent>& events() const;
  std::int64_t events_not_kept() const;

 private:
  // Joint accelerations (into `out`) and held-angle rates at one state.
  void evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const std::array<double, kNumDirections>& angle, double w_n, Data& out,
                std::array<double, kNumDirections>& angle_rate);
  // Each writes its first solve (at the step's start) into `first`.
  void step_explicit_euler(double dt, double w_n, Data& first);
  void step_semi_implicit_euler(double dt, double w_n, Data& first);
  void step_rk4(double dt, double w_n, Data& first);
  void apply_limits();
  void resume_from_tip(unsigned directions);  // bit k: direction k
  // The error of a failed step, `cause` put in context (step, t, directions).
  Error step_failure(double dt, const std::string& cause) const;

  Model model_;
  SimulatorOptions options_;
  Options solver_;
  // data_[current_] is the first solve of the last completed step; a step solves into
  // the other one and makes it current only when the step succeeds.
  std::array<Data, 2> data_;
  int current_ = 0;
  Data stage_data_;
  // t = t_origin_ + t_steps_ * t_dt_ (see t above); t_written_ is the last t step() wrote.
  double t_origin_ = 0, t_dt_ = 0, t_written_ = 0;
  std::int64_t t_steps_ = 0, steps_taken_ = 0;
  int stage_ = 0;  // the integrator stage being evaluated (RK4: 0..3), for messages
  Case case_;
  HeldDirections held_, stage_held_;
  std::array<double, kNumDirections> max_residual_{};
  std::vector<int> limit_hits_;
  std::unique_ptr<DirectionEventLog> events_;  // direction_events.hpp
  std::vector<double> mass_;   // per body, from the spatial inertia
  std::vector<Vector3> com_;   // per body, body frame
  std::vector<double> axial_inertia_;  // S^T I S of each body alone
  // Workspace of step() (sized once): body poses and velocities, integrator stages.
  std::vector<Transform> X0_;
  std::vector<Vector3> r_;
  std::vector<Vector6> v_;
  Eigen::VectorXd q0_, qd0_, q_stage_, qd_stage_, k_q_[4], k_qd_[4];
  std::array<double, kNumDirections> angle0_{}, angle_stage_{}, k_angle_[4]{};
};

}  // namespace achd
