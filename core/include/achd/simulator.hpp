#pragma once
// Time stepping of a robot under the hybrid solver: state (q, qd, t), integrators, the
// effects a scene enables, directions the user holds or accelerates on any links, and a
// joint PD controller toward a target pose.
//
// Directions are the base axes at a point of a link (its origin unless set otherwise):
// x, y, z (linear) and rx, ry, rz (angular). Each link has its own set.
//   Hold, linear e:  keeps e . p_point at its value when the direction was set.
//   Hold, angular e: keeps the integral of e . w_link since it was set at zero.
//   Accelerate:      the classical acceleration of the point along e equals the setpoint.
// The directions of a link become one constraint block (Case::constraints) whose columns
// are the active directions, with a Baumgarte-stabilised beta including the
// velocity-product term that separates spatial from classical acceleration.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/error.hpp"
#include "achd/joint_motion.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

class DirectionEventLog;
struct TipState;

// ExplicitEuler, SemiImplicitEuler, RK4: one fixed step of dt per step(dt).
// DormandPrince: the adaptive Dormand-Prince 5(4) pair (dormand_prince.cpp); step(dt)
//   takes as many error-controlled substeps as rtol/atol need to reach t + dt.
// ImplicitEuler: semi-implicit Euler that is implicit in joint damping and friction
//   (implicit_euler.cpp): stable for any dt on stiff passive terms, first order.
// New values go at the end: the enum value is the index of the name (names.hpp).
enum class Integrator { ExplicitEuler, SemiImplicitEuler, RK4, DormandPrince, ImplicitEuler };
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

// The held set of one link: one mode per direction, with what each mode needs (the held
// angles, integrated with the state, are the simulator's: Simulator::held_angles()).
struct HeldDirections {
  std::array<DirectionMode, kNumDirections> mode{};
  std::array<double, kNumDirections> setpoint{};  // Accelerate: classical acceleration
  std::array<double, kNumDirections> target{};    // Hold, linear: e . p_point when set
  // Driver priorities of each direction's column (Case::w_fext, w_ff): 1 = the direction
  // resists f_ext / ff_torques fully; below 1 that share of the driver passes through.
  std::array<double, kNumDirections> w_fext{1, 1, 1, 1, 1, 1}, w_ff{1, 1, 1, 1, 1, 1};

  bool active(int k) const { return mode[k] != DirectionMode::Free; }
  int count() const;
};

// The directions of one link: where they act and their held set.
struct LinkDirections {
  int link = 0;                     // Model::links index
  Vector3 point = Vector3::Zero();  // where the directions act, in the link's frame
  HeldDirections held;
  std::array<double, kNumDirections> max_residual{};  // since each direction was set
};

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

// The adaptive integrator's control (dormand_prince.cpp): a substep of h is accepted when
// the RMS over q, qd and the held angles of err_i / (atol + rtol max(|x_i|, |x_i'|)) is
// at most 1; the next h is h min(5, max(0.2, 0.9 err^-1/5)) (not grown after a rejection).
// A step fails when h falls below kMinSubstepFraction dt, after kMaxRejections
// rejections in a row, or when it has taken kMaxSubstepsPerStep substeps without reaching
// t + dt (a substep that keeps shrinking towards its floor would otherwise take hours).
constexpr double kDefaultRtol = 1e-9;
constexpr double kDefaultAtol = 1e-11;
constexpr double kMinSubstepFraction = 1e-10;
constexpr int kMaxRejections = 40;
constexpr std::int64_t kMaxSubstepsPerStep = 100000;

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
  int link;            // index in Model::links of the link whose direction it is
  int direction;       // 0..5: x y z rx ry rz
  DirectionEventKind kind;
  double sigma_min;    // the coupling matrix's smallest singular value in that solve
};
// The events a Simulator keeps (reserved at construction; later ones are counted in
// Simulator::events_not_kept()).
constexpr std::size_t kMaxDirectionEvents = 10000;

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

// Held angles of the direction sets, kNumDirections per set (Simulator::step integrates them).
using HeldAngles = Eigen::VectorXd;

class Simulator {
 public:
  Simulator(const Model& model, const SimulatorOptions& options = {});
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  // State, root to tip: q holds Model::num_positions() numbers (a floating base's 7 first:
  // position and unit quaternion, kept unit by every step), qd num_rates() (its [v; w]
  // first, world axes). Setting them directly is allowed; reset() also restarts t,
  // releases every direction and clears the drift and limit records.
  // t is t0 + k dt after the k-th step of dt since t was last set (by reset(), by the
  // caller, or by a change of dt): computed, not summed, so that k steps of dt from 0
  // end at exactly the double k * dt.
  Eigen::VectorXd q, qd;
  double t = 0;
  Eigen::VectorXd ff_torques;   // joint torques applied every step (default 0)
  std::vector<Vector6> f_ext;   // wrench per link after the root (base orientation)

  void reset(const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0);
  // Direction `index` (0..5: x y z rx ry rz) of link `link` (Model::links index; the
  // root link of a floating base is not one: a link fixed to it is) held, accelerated at
  // `setpoint` (m/s^2 or rad/s^2) or freed. A held linear direction keeps the point where
  // it is now. Up to kMaxConstraintColumns active directions on all links together; an
  // achd::Error names the link and direction otherwise.
  void set_direction(int link, int index, DirectionMode mode, double setpoint = 0);
  // Where link `link`'s directions act, in its frame (default its origin). Its held
  // directions are re-anchored at the new point (linear targets where it is now, angles 0).
  void set_direction_point(int link, const Vector3& point);
  DirectionMode direction_mode(int link, int index) const;
  double setpoint(int link, int index) const;
  // The driver priorities of a direction (each in [0, 1], default 1; kept when its mode
  // changes). A held direction with a weight below 1 yields to that driver: after every
  // step its target is re-anchored where the point is (linear: e . p_point; angular: held
  // angle 0), so that the yielding shows and the stabilisation does not pull it back.
  void set_direction_weights(int link, int index, double w_fext, double w_ff);
  // The links that have directions (set, freed again, or weighted), in the order their
  // constraint blocks take in nu (a link with no active direction has no block).
  const std::vector<LinkDirections>& direction_sets() const { return sets_; }
  // Held-direction residuals of link `link` in m or rad (0 for directions not held), and
  // the largest |residual| of each since it was set (or since reset()).
  std::array<double, kNumDirections> residuals(int link) const;
  std::array<double, kNumDirections> max_residuals(int link) const;
  // Pose of link `link` at its directions' point in the base frame, and its velocity [v; w].
  Transform link_pose(int link) const;
  Vector6 link_velocity(int link) const;
  // The same on a chain's tip (a model loaded with a tip; an achd::Error on a tree).
  void set_direction(int index, DirectionMode mode, double setpoint = 0);
  DirectionMode direction_mode(int index) const;
  double setpoint(int index) const;
  void set_direction_weights(int index, double w_fext, double w_ff);
  // The joint PD controller (JointControl): target of num_positions() finite numbers,
  // gains per joint, finite and >= 0, 0 on a floating base's free joint (or a frequency
  // > 0 and a damping ratio >= 0, from which joint_control() then holds the gains); an
  // achd::Error names the field, joint and value otherwise. Kept by reset().
  void set_joint_control(const JointControl& control);
  void clear_joint_control();
  bool joint_control_on() const { return control_on_; }
  const JointControl& joint_control() const { return control_; }
  // Prescribed joint motion (joint_motion.hpp): from now on joint `joint` follows
  // `motion` in the simulated time t. It is put on the trajectory at once (q, qd at t),
  // every solve gives it the trajectory's acceleration at the solve's time
  // (Case::prescribed: the other joints and the held directions are solved around it, and
  // data().prescribed_torques holds the torque it takes), and after every step its q and
  // qd are set to the trajectory's at the new t (the integrator's values differ from them
  // by its error only). Under LimitPolicy::Clamp a prescribed joint is not stopped at its
  // limits (its motion is given; limit_hits() still lists it past one), and the impacts of
  // the other joints leave its velocity as it is. reset() releases every prescribed joint.
  // An achd::Error names the joint on a bad index or motion parameter.
  void prescribe(int joint, const JointMotion& motion);
  // The joint is driven by its torques again, from its current q and qd.
  void release(int joint);
  bool prescribed(int joint) const;
  const JointMotion& motion(int joint) const;  // of a prescribed joint
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
  // Integrator substeps accepted and rejected since construction or reset(): a fixed-step
  // integrator takes one substep per step and rejects none.
  std::int64_t substeps() const { return substeps_; }
  std::int64_t rejected_substeps() const { return rejected_substeps_; }

  // The queries below (residuals to energy) compute from q and qd into scratch storage
  // of the calling thread and write nothing in the simulator: two threads may call them
  // at once on one simulator (while neither steps it nor sets its state). A thread's
  // first query (and its first of a longer chain) allocates that storage.
  // The tip's residuals, max_residuals (as the link's above), pose and velocity [v; w].
  std::array<double, kNumDirections> residuals() const;
  std::array<double, kNumDirections> max_residuals() const;
  Transform tip_pose() const;
  Vector6 tip_velocity() const;
  double kinetic_energy() const;
  double potential_energy() const;  // gravity only; 0 when gravity is off
  double energy() const;  // kinetic_energy() + potential_energy(), from one sweep
  // The solve at the start of the last completed step (nu, joint torques, ...).
  const Data& data() const { return data_[current_]; }
  const Model& model() const { return model_; }
  const SimulatorOptions& options() const { return options_; }
  SimulatorOptions& options() { return options_; }
  // Joints that were at or past a limit in the last step (LimitPolicy Report/Clamp).
  const std::vector<int>& limit_hits() const { return limit_hits_; }
  // LimitPolicy::Clamp: the stop joint i rests on, -1 (lower limit), +1 (upper) or 0 (free).
  int limit_stop(int joint) const;
  // Direction events since construction or reset(), oldest first (at most
  // kMaxDirectionEvents), and how many more happened but were not kept.
  const std::vector<DirectionEvent>& events() const;
  std::int64_t events_not_kept() const;

 private:
  // Joint accelerations (into `out`) and held-angle rates at one state, at time t_at
  // (the prescribed joints' accelerations are their trajectories' then).
  void evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const HeldAngles& angles, double t_at,
                double w_n, Data& out, HeldAngles& angle_rates);
  // The held angles in use: kNumDirections per set (angles_ and the stage vectors hold
  // room for every link; the integrators work on this many).
  Eigen::Index held_angle_count() const { return static_cast<Eigen::Index>(kNumDirections * sets_.size()); }
  // The tip's link index; an achd::Error naming `what` on a tree.
  int tip_link(const std::string& what) const;
  // The set of link `link`, created (in the order of nu) when `create`; nullptr if none.
  LinkDirections* find_set(int link, bool create);
  const LinkDirections* find_set(int link) const;
  // case_.constraints from the sets: one block per link with active directions.
  void update_blocks();
  // The PD torques at (q, qd) added to ff_torques, into case_.ff_torques.
  void apply_joint_control(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  void check_joint(int joint, const char* what) const;
  // Puts the prescribed joints on their trajectories at time t_at (q and qd).
  void follow_trajectories(double t_at);
  // Each writes its first solve (at the step's start) into `first`.
  void step_explicit_euler(double dt, double w_n, Data& first);
  void step_semi_implicit_euler(double dt, double w_n, Data& first);
  void step_rk4(double dt, double w_n, Data& first);
  void step_dormand_prince(double dt, double w_n, Data& first);
  void step_implicit_euler(double dt, double w_n, Data& first);
  void apply_limits();
  // LimitPolicy::Clamp (joint_limits.cpp): before a step, the joints that the solve pulls
  // off their stops are freed (one solve when a joint rests on a stop); after it, the
  // joints that reached a limit stop by an inelastic impact that the held directions
  // respect, and rest on it (their acceleration prescribed as 0 in every solve).
  void update_limit_stops(double w_n);
  void stop_at_limits();
  void solve_impact(const char* what);
  // Re-anchors the held directions with bit k set in bits[s] of set s where the point is
  // (linear: target = e . p_point; angular: held angle 0).
  void anchor_directions(const std::vector<unsigned>& bits);
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
  // The directions of every link that has some, and their held angles (kNumDirections
  // per set, set s at s * kNumDirections; sized for every link once: no step allocates).
  std::vector<LinkDirections> sets_;
  std::vector<int> block_set_;     // case_.constraints[b] is the block of sets_[block_set_[b]]
  HeldAngles angles_;
  std::vector<unsigned> anchored_;  // per set, the directions a step re-anchors
  std::vector<TipState> impact_points_;  // joint_limits.cpp: each set's point before an impact
  JointControl control_;
  bool control_on_ = false;
  Eigen::VectorXd hold_torques_;  // JointControl::hold's tau_hold (zeros without it)
  // Recomputes the frequency gains (JointControl::frequency) and hold_torques_
  // (JointControl::hold) for the current target and held set.
  void update_control_terms();
  std::vector<int> limit_hits_;
  std::unique_ptr<DirectionEventLog> events_;  // direction_events.hpp
  std::vector<double> mass_;   // per body, from the spatial inertia
  std::vector<Vector3> com_;   // per body, body frame
  // Workspace of step() (sized once): body poses and velocities, integrator stages.
  std::vector<Transform> X0_;
  std::vector<Vector3> r_;
  std::vector<Vector6> v_;
  // Stage derivatives k_s of (q, qd, held angles): RK4 uses 4, Dormand-Prince 7.
  static constexpr int kMaxStages = 7;
  Eigen::VectorXd q0_, qd0_, q_stage_, qd_stage_, k_q_[kMaxStages], k_qd_[kMaxStages];
  Eigen::VectorXd q_next_, qd_next_;  // Dormand-Prince: the 5th-order solution of a substep
  HeldAngles angle_next_, angle0_, angle_stage_, k_angle_[kMaxStages];
  // Dormand-Prince: the substep size proposed for the next substep (0: none yet).
  double substep_ = 0;
  std::int64_t substeps_ = 0, rejected_substeps_ = 0;
  // Implicit Euler: a copy of model_ whose rotor inertias carry dt times each joint's
  // passive-torque derivative, and whether evaluate() solves with it.
  Model implicit_model_;
  bool implicit_solve_ = false;
  // LimitPolicy::Clamp: the stop each joint rests on (limit_stop()), the joints that
  // reached a limit in this step, and the impact solve's case and result (sized once).
  std::vector<signed char> limit_stop_, limit_reached_;
  // Prescribed joint motion: per joint its motion and whether it is prescribed.
  std::vector<JointMotion> motions_;
  std::vector<char> moving_;
  Case impact_case_;
  Data limit_data_;
  HeldAngles limit_angle_rate_;
};

}  // namespace achd
