#pragma once
// The accuracy-versus-time study of a scene (`achd accuracy`): each fixed-step integrator
// (explicit, semi-implicit and implicit Euler, RK4) at a ladder of time steps, the adaptive
// Dormand-Prince for a ladder of tolerances (at the largest output step), and the solver
// knobs at the scene's step, each run measured by
//   error  = max_i |q_i(T) - q_ref,i(T)| in rad (the end-state joint positions; the
//            velocities' max|qd - qd_ref| in rad/s is reported beside it),
//   cost   = CPU time of the simulating thread per output step, the median over rounds
//            that each run every configuration in turn (interleaved: a change in the
//            machine's speed hits them alike; on an idle core CPU time equals wall time,
//            on a shared machine it leaves out the time spent descheduled), and per
//            simulated second: ns_per_step / dt.
// The reference is RK4 at dt_ref; its own error is estimated as max|q(dt_ref) -
// q(dt_ref / 2)| (the change when its step is halved). A study then halves dt_ref again
// (refine_reference) until that estimate is at most a tenth of the smallest error it
// measured, so that its best rows are ranked by their own errors, not the reference's.
//
// Every run is the simulator as a user configures it with the scene: the same equations
// at every dt (friction's smoothing velocity and the Baumgarte frequency are the scene's
// parameters, not derived from the step), so the differences are the integrators'. The
// knobs show what changing a parameter or the solver's policy changes.
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scene_json.hpp"

namespace achd::cli {

// What a run of a scene ends with.
struct EndState {
  Eigen::VectorXd q, qd;  // at the end, or after the last step that succeeded
  bool finite = true;  // false: a step failed (its state was not finite or the solver
                       // refused it); `failure` says which and why (Simulator::step)
  std::string failure;
  // max |E(t) - E(0)| / max kinetic energy over the run; NaN when the scene does not
  // conserve energy.
  double energy_drift = std::numeric_limits<double>::quiet_NaN();
  // The largest |residual| of each held direction (m or rad), over every link with
  // directions; 0 for free directions.
  std::array<double, kNumDirections> held_drift{};
  // The integrator's accepted substeps (one per step for the fixed-step ones), of them
  // the stiff ones (Dormand-Prince's extrapolated implicit Euler substeps), and the
  // rejected ones.
  std::int64_t substeps = 0, stiff_substeps = 0, rejected_substeps = 0;
};

// Told the number of steps just taken, after every step of every run of a study (the
// CLI's progress and Ctrl-C: it may throw to stop the study).
using StepObserver = std::function<void(std::int64_t)>;

// Runs `scene` with `options` for `duration` at `dt`; duration must be a whole number of
// steps (steps_for_duration; an achd::Error otherwise: the end states would belong to
// different times).
EndState run_to_end(const Scene& scene, const SimulatorOptions& options, double dt, double duration,
                    const StepObserver& observe = {});

// max_i |a_i - b_i|.
double max_abs_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

struct Reference {
  double dt = 0;
  EndState end;          // RK4 at dt
  EndState finer;        // RK4 at dt / 2
  double self_error_q = 0;   // max|q(dt) - q(dt / 2)|, rad
  double self_error_qd = 0;  // max|qd(dt) - qd(dt / 2)|, rad/s
  int halvings = 0;          // of the study's reference_dt by refine_reference
  std::int64_t refinement_steps = 0;  // the steps refine_reference ran, kept or not
};
Reference reference_run(const Scene& scene, const SimulatorOptions& options, double dt, double duration,
                        const StepObserver& observe = {});

// The most times refine_reference halves the reference's step (each costs as many steps as
// the reference's two runs together, doubled every time).
constexpr int kMaxReferenceHalvings = 4;

// Halves ref's step (its run at dt / 2 becomes the reference, a run at dt / 4 its check)
// while its self error is above `wanted`, at most kMaxReferenceHalvings times, and stops
// when a halving no longer cuts the self error by 4 (RK4's error falls 16x per halving
// until round-off takes over) or when the next halving would pass `max_steps` steps.
void refine_reference(const Scene& scene, const SimulatorOptions& options, double duration, double wanted,
                      double max_steps, Reference& ref, const StepObserver& observe = {});

// A run is unstable when its state left the finite numbers or its error exceeds this.
constexpr double kUnstableError = 1.0;  // rad

struct StudyRun {
  std::string kind;        // "integrator" or the knob's name
  std::string integrator;  // integrator_name()
  std::string setting;     // the knob's value ("" for the integrator ladder)
  double dt = 0;
  std::int64_t steps = 0;
  bool stable = true;      // false: "unstable" or "diverged" below
  std::string status;      // "ok"; "unstable": NaN/Inf (or the solver refused the
                           // state); "diverged": finite but error_q > kUnstableError
  std::string failure;     // why a run is not "ok": the failed step's message, or the
                           // diverged run's error ("" when ok)
  double error_q = 0, error_qd = 0;  // against the reference
  double change_q = 0;               // knobs: max|q - q_default| (same integrator and dt)
  double energy_drift = 0;           // NaN where the scene does not conserve energy
  double held_drift_linear = 0;      // m, the largest over held linear directions
  double held_drift_angular = 0;     // rad, the largest over held angular directions
  std::int64_t substeps = 0, stiff_substeps = 0, rejected_substeps = 0;  // EndState's
  double ns_per_step = 0;
  double cpu_s_per_sim_s = 0;        // ns_per_step * 1e-9 / dt
  double order = std::numeric_limits<double>::quiet_NaN();  // vs the previous dt
  bool pareto = false;               // on the error-cost front of the integrator ladder
};

struct StudyConfig {
  double duration = 0;                 // simulated seconds of each run
  std::vector<double> dts;             // the ladder, largest first
  // Dormand-Prince's tolerances (rtol; atol = rtol / 100), each run at the largest of dts.
  std::vector<double> rtols{1e-3, 1e-5, 1e-7, 1e-9, 1e-11};
  double reference_dt = 0;             // RK4 reference step
  int timing_repeats = 5;
  std::int64_t timing_steps = 400;     // steps of each timed run (at most the run's)
  bool knobs = true;
};

struct Study {
  std::string scene;
  StudyConfig config;
  double friction_velocity = 0;        // m/s or rad/s, fixed for every run (see above)
  double stabilisation_frequency = 0;  // rad/s, fixed for every run (see above)
  Reference reference;
  std::vector<StudyRun> runs;    // the integrator ladder, then the knobs
  double wall_seconds = 0;       // the whole study
};

// The ladder 10, 5, 2, 1, 0.5, 0.2, 0.1, 0.05 ms over the scene's duration, the
// reference at 1/4 of the smallest step. quick: 0.5 s at most, 10 ms down to 0.2 ms.
StudyConfig default_config(const Scene& scene, bool quick);

// The steps a study of `scene` takes: the reference, the ladder, the knobs (at the
// scene's dt) and the timing runs; and, not known before the runs, the reference's
// refinement (Reference::refinement_steps). A double: it may be far beyond any integer type.
double planned_steps(const Scene& scene, const StudyConfig& config);

// The most steps run_study() takes on: about 5 minutes on the 7-DoF arm (docs/guide/accuracy-cost.md's
// 2 s studies take 8.5e5 steps); a larger study is refused with an achd::Error naming
// its step count.
constexpr double kMaxStudySteps = 1e8;

Study run_study(const Scene& scene, const StudyConfig& config, const StepObserver& observe = {});

}  // namespace achd::cli
