#pragma once
// Time stepping of a robot under the hybrid solver: the state (q, qd, t and the held
// angles), the directions the user holds or accelerates on any links (directions.hpp),
// prescribed joint motion, joint limits and a joint PD controller (simulator_options.hpp).
// Each step checks the state, evaluates x' = f(x) with one hybrid_dynamics solve per
// integrator stage, integrates, applies the joint limits and records the direction events.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/directions.hpp"
#include "achd/error.hpp"
#include "achd/joint_motion.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"
#include "achd/simulator_options.hpp"

namespace achd {

// t after k steps of dt: t0 + k dt, computed, not summed, so that k steps of dt from 0
// end at exactly the double k * dt. The count restarts (t0 = t, k = 0) when t was set by
// anyone but the last step, or dt changes.
class StepClock {
 public:
  void start(double t, double dt) {
    if (t != written_ || dt != dt_) origin_ = t, dt_ = dt, steps_ = 0;
  }
  // The time after `more` further steps of the current dt.
  double after(std::int64_t more) const { return origin_ + static_cast<double>(steps_ + more) * dt_; }
  // One step done: the new t.
  double advance() {
    ++steps_;
    return written_ = after(0);
  }

 private:
  double origin_ = 0, dt_ = 0, written_ = 0;
  std::int64_t steps_ = 0;
};

// The state a Simulator advances, x = (q, qd, held angles) at time t (the integrators
// advance x; the clock advances t).
// q holds Model::num_positions() numbers, root to tip (a floating base's 7 first: position
// and unit quaternion, kept unit by every step), qd num_rates() (its [v; w] first, world
// axes). held_angles: kNumDirections per direction set, in the order of
// Simulator::direction_sets(), the integral of e . w_link of each held angular direction
// since it was set (0 for the others).
struct SimulationState {
  Eigen::VectorXd q, qd;
  double t = 0;
  HeldAngles held_angles;
  StepClock clock;
};

struct TipState;
class DirectionSets;
struct IntegratorWorkspace;

class Simulator : public SimulationState {
 public:
  Simulator(const Model& model, const SimulatorOptions& options = {});
  ~Simulator();
  Simulator(Simulator&&) noexcept;
  Simulator& operator=(Simulator&&) noexcept;

  // The state (SimulationState: q, qd, t, held_angles). Setting q, qd or t directly is
  // allowed; reset() also restarts t, releases every direction and clears the drift and
  // limit records. t is t0 + k dt after the k-th step of dt since t was last set (by
  // reset(), by the caller, or by a change of dt): clock (StepClock).
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
  const std::vector<LinkDirections>& direction_sets() const;
  // Held-direction residuals of link `link` in m or rad (0 for directions not held), and
  // the largest |residual| of each since it was set (or since reset()) while it was
  // followed: the intervals it was released (events()) do not count.
  std::array<double, kNumDirections> residuals(int link) const;
  std::array<double, kNumDirections> max_residuals(int link) const;
  // How long (s) each direction of link `link` was released since it was set, and the same
  // for the directions of loop joint `loop` (of its loop frame) since reset().
  std::array<double, kNumDirections> released_seconds(int link) const;
  std::array<double, kNumDirections> loop_released_seconds(int loop) const;
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
  // `motion` in the simulated time t. It is put on the trajectory at once (q, qd at t);
  // with held directions, loops or coupled joints, the free joints then move back, as
  // little as the joint-space inertia's metric allows, so that the held directions keep
  // where and how fast they were and the loops stay closed (a limit stop's position
  // projection and impact; a scene that holds its tip and drives a joint moving at t = 0
  // starts with the tip at rest). Every solve gives it the trajectory's acceleration at the solve's time
  // (Case::prescribed: the other joints and the held directions are solved around it, and
  // data().prescribed_torques holds the torque it takes), and after every step its q and
  // qd are set to the trajectory's at the new t (the integrator's values differ from them
  // by its error only). Under LimitPolicy::Clamp a prescribed joint is not stopped at its
  // limits (its motion is given; limit_hits() still lists it past one), and the impacts of
  // the other joints leave its velocity as it is. reset() releases every prescribed joint.
  // An achd::Error names the joint on a bad index or motion parameter, or when the jump's
  // solve fails; q, qd and the prescribed joints are then unchanged.
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
  std::int64_t substeps() const;
  std::int64_t rejected_substeps() const;
  // Of the accepted substeps, those Dormand-Prince took as the extrapolated implicit Euler
  // method's after detecting stiffness (integrators/dormand_prince.cpp).
  std::int64_t stiff_substeps() const;

  // The queries below (residuals to energy) compute from q and qd into scratch storage
  // of the calling thread and write nothing in the simulator: two threads may call them
  // at once on one simulator (while neither steps it nor sets its state). A thread's
  // first query (and its first of a longer chain) allocates that storage.
  // The tip's residuals, max_residuals (as the link's above), pose and velocity [v; w].
  std::array<double, kNumDirections> residuals() const;
  std::array<double, kNumDirections> max_residuals() const;
  Transform tip_pose() const;
  Vector6 tip_velocity() const;
  // Loop joint `loop` (Model::loops index): its closure error now (the largest over its
  // held directions, m or rad: loop_closure.hpp) and the largest since reset() while the
  // loop was enforced (a direction of it released: not counted; loop_released_seconds).
  double loop_error(int loop) const;
  double loop_drift(int loop) const;
  double kinetic_energy() const;
  double potential_energy() const;  // gravity only; 0 when gravity is off
  double energy() const;  // kinetic_energy() + potential_energy(), from one sweep
  // The solve at the start of the last completed step (nu, joint torques, ...). Its
  // solves compute the accelerations of the links with directions (direction_sets())
  // alone (Data::set_link_outputs: the other links' entries hold 0); any link's motion
  // is link_pose() and link_velocity().
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
  // The step's parts (simulator.cpp): its checks and inputs, the chosen integrator, and
  // what follows a good step (trajectories, limits, events, anchors).
  void check_step(double dt);
  void advance(double dt, double w_n, double zeta, Data& first);
  void finish_step(const Data& first);
  // x' = f(x) (evaluate.cpp): joint accelerations (into `out`) and held-angle rates at
  // state x, at its time x.t (the prescribed joints' accelerations are their
  // trajectories' then), the held directions, loops and couplings stabilised at w_n and
  // zeta; and the held-angle rates alone, from the kinematics.
  void evaluate(const SimulationState& x, double w_n, double zeta, Data& out, HeldAngles& angle_rates);
  // The solve of a linearly implicit step of h from x (evaluate.cpp).
  void evaluate_implicit(const SimulationState& x, double h, double w_n, double zeta, Data& out,
                         HeldAngles& angle_rates);
  void held_angle_rates(const SimulationState& x, HeldAngles& angle_rates);
  // The tip's link index; an achd::Error naming `what` on a tree.
  int tip_link(const std::string& what) const;
  // The set of link `link`, created (in the order of nu, with its held angles) if none.
  LinkDirections& set_of(int link);
  // case_.constraints from the sets, and the control terms that follow the held set.
  void update_blocks();
  // The PD torques at (q, qd) added to ff_torques, into case_.ff_torques.
  void apply_joint_control(const Eigen::VectorXd& q, const Eigen::VectorXd& qd);
  // Recomputes the frequency gains (JointControl::frequency) and hold_torques_
  // (JointControl::hold) for the current target and held set.
  void update_control_terms();
  void check_joint(int joint, const char* what) const;
  // Puts the prescribed joints on their trajectories at time t_at (q and qd).
  void follow_trajectories(double t_at);
  void apply_limits();
  // LimitPolicy::Clamp (joint_limits.cpp): before a step, the joints that the solve pulls
  // off their stops are freed (one solve when a joint rests on a stop); after it, the
  // joints that reached a limit stop by an inelastic impact that the held directions
  // respect, and rest on it (their acceleration prescribed as 0 in every solve).
  void update_limit_stops(double w_n, double zeta);
  void stop_at_limits();
  // Impacts (joint_limits.cpp): one solve of impact_case_ (`what` and the joint put on its
  // trajectory, or -1 for the joints at their limits, name it in an error); its blocks, the
  // held columns of every set (beta 0); the held columns' and loops' changes since
  // impact_points_ (record_impact_points) into their beta (positions or velocities),
  // returning the largest; q moved (Newton) until each joint marked in
  // impact_case_.prescribed is at impact_target_ with the held quantities unchanged and
  // the loops closed; and the impulse that changes each marked joint's qd by
  // impact_case_.qdd_given and gives the held directions back their velocities.
  void solve_impact(const char* what, int joint);
  void set_impact_blocks();
  double held_changes(bool velocity);
  double loop_changes(bool velocity);
  double coupling_changes(bool velocity);  // each coupling's error, its beta the change -e
  void record_impact_points();  // each set's point state now (and the body motion)
  // `moved`: q already moved (the held quantities and loops count from the first iteration)
  void project_positions(int joint, bool moved);
  void project_velocities(const char* what, int joint);
  // prescribe(): joint `joint` put at q_at and qd_at as an inelastic jump that the held
  // directions, loops and coupled joints respect (nothing changed when it throws).
  void jump_onto_trajectory(int joint, double q_at, double qd_at);
  // Re-anchors the held directions with bit k set in bits[s] of set s where the point is
  // (linear: target = e . p_point; angular: held angle 0).
  void anchor_directions(const std::vector<unsigned>& bits);
  // The error of a failed step, `cause` put in context (step, t, directions).
  Error step_failure(const std::string& cause) const;

  Model model_;
  SimulatorOptions options_;
  Options solver_;
  // data_[current_] is the first solve of the last completed step; a step solves into
  // the other one and makes it current only when the step succeeds.
  std::array<Data, 2> data_;
  int current_ = 0;
  std::int64_t steps_taken_ = 0;
  Case case_;
  std::unique_ptr<DirectionSets> directions_;      // direction_sets.hpp
  std::unique_ptr<IntegratorWorkspace> integrator_;  // integrators/integrators.hpp
  SimulationState saved_;  // the state a failed step returns to
  std::vector<TipState> impact_points_;  // joint_limits.cpp: each set's point before an impact
  JointControl control_;
  bool control_on_ = false;
  double control_lead_ = 0;  // evaluate_implicit's h: the PD position term at q + h qd
  Eigen::VectorXd hold_torques_;  // JointControl::hold's tau_hold (zeros without it)
  std::vector<int> limit_hits_;
  std::vector<double> loop_drift_;  // per loop: the largest closure error at a step's start
  std::vector<double> mass_;   // per body, from the spatial inertia
  std::vector<Vector3> com_;   // per body, body frame
  // Body poses and velocities of step() (sized once).
  std::vector<Transform> X0_;
  std::vector<Vector3> r_;
  std::vector<Vector6> v_;
  // LimitPolicy::Clamp: the stop each joint rests on (limit_stop()), the joints that
  // reached a limit in this step, and the impact solve's case and result (sized once).
  std::vector<signed char> limit_stop_, limit_reached_;
  // Prescribed joint motion: per joint its motion and whether it is prescribed.
  std::vector<JointMotion> motions_;
  std::vector<char> moving_;
  Case impact_case_;
  Eigen::VectorXd impact_target_;  // per joint: where project_positions() puts a marked one
  Data limit_data_;
  HeldAngles limit_angle_rate_;
};

}  // namespace achd
