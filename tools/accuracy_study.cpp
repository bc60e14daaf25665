// The accuracy-versus-time study: runs, the reference, timing, and the knob variants.
#include "accuracy_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <memory>

#include "achd/error.hpp"
#include "pareto_front.hpp"
#include "timing.hpp"

namespace achd::cli {
namespace {

// The integrators whose held drift run_knobs() shows at the scene's Baumgarte frequency
// (each but the scene's own).
constexpr Integrator kDriftIntegrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::RK4};

// The fixed-step integrators of the ladder (Dormand-Prince runs per tolerance instead).
constexpr Integrator kLadderIntegrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler,
                                             Integrator::ImplicitEuler, Integrator::RK4};

std::string number_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

bool uses_friction(const Scene& scene) {
  if (!(scene.options.effects & kFriction)) return false;
  for (const Body& b : scene.model.bodies)
    if (b.friction != 0) return true;
  return false;
}

bool holds_directions(const Scene& scene) {
  if (!(scene.options.effects & kConstraints)) return false;
  for (DirectionMode m : scene.modes)
    if (m == DirectionMode::Hold) return true;
  for (const Scene::LinkSet& set : scene.link_directions)
    for (DirectionMode m : set.modes)
      if (m == DirectionMode::Hold) return true;
  return false;
}

// The error and stability of a run that ended in `end`, against the reference.
void score(const EndState& end, const Reference& ref, StudyRun& r) {
  r.error_q = end.finite ? max_abs_difference(end.q, ref.end.q) : INFINITY;
  r.error_qd = end.finite ? max_abs_difference(end.qd, ref.end.qd) : INFINITY;
  r.stable = end.finite && std::isfinite(r.error_qd) && r.error_q <= kUnstableError;
  r.status = r.stable ? "ok" : end.finite && std::isfinite(r.error_qd) ? "diverged" : "unstable";
  if (r.stable) r.failure.clear();
  else if (!end.finite) r.failure = end.failure;
  else if (r.status == "unstable") r.failure = "the end state is not finite";
  else r.failure = "ends " + number_text(r.error_q) + " rad from the reference (more than " +
                   number_text(kUnstableError) + " rad)";
}

// Error, drifts and stability of a run that ended in `end`, against the reference.
StudyRun measure(const EndState& end, const SimulatorOptions& options, double dt, double duration,
                 const Reference& ref) {
  StudyRun r;
  r.integrator = integrator_name(options.integrator);
  r.dt = dt;
  r.steps = steps_for_duration(duration, dt);
  score(end, ref, r);
  r.energy_drift = end.energy_drift;
  r.substeps = end.substeps;
  r.stiff_substeps = end.stiff_substeps;
  r.rejected_substeps = end.rejected_substeps;
  for (int k = 0; k < kNumDirections; ++k) {  // x, y, z first, then rx, ry, rz
    double& drift = k < 3 ? r.held_drift_linear : r.held_drift_angular;
    drift = std::max(drift, end.held_drift[k]);
  }
  return r;
}

// A run whose cost is still to be timed: its options and output step, and its row.
struct TimedRun {
  SimulatorOptions options;
  double dt = 0;
  std::int64_t steps = 0;
  std::size_t row = 0;  // index into Study::runs
};

// The cost of every queued run, timed in interleaved rounds: each round runs every
// configuration once, in turn, for min(steps, timing_steps) output steps from the scene's
// start (round 0 warms the caches and is discarded), so that a change in the machine's
// speed hits all configurations alike; the cost is the median over the rounds of the
// thread CPU time per output step.
void time_interleaved(const Scene& scene, const std::vector<TimedRun>& queue, const StudyConfig& config,
                      std::vector<StudyRun>& runs, const StepObserver& observe) {
  std::vector<std::unique_ptr<Simulator>> sims;
  for (const TimedRun& t : queue) sims.push_back(std::make_unique<Simulator>(scene.model, t.options));
  std::vector<std::vector<double>> samples(queue.size());
  for (int round = 0; round <= config.timing_repeats; ++round)
    for (std::size_t i = 0; i < queue.size(); ++i) {
      Simulator& sim = *sims[i];
      const std::int64_t n = std::max<std::int64_t>(1, std::min(queue[i].steps, config.timing_steps));
      start_scene(scene, sim);
      const double t0 = now_ns();
      try {
        sim.run(n, queue[i].dt);
      } catch (const Error&) {
        // An unstable run may stop early; its cost is still the time per step taken.
      }
      const double ns = now_ns() - t0;
      if (round > 0) samples[i].push_back(ns / static_cast<double>(std::max<std::int64_t>(1, sim.steps_taken())));
      if (observe) observe(sim.steps_taken());
    }
  for (std::size_t i = 0; i < queue.size(); ++i) {
    std::vector<double>& s = samples[i];
    std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
    StudyRun& r = runs[queue[i].row];
    r.ns_per_step = s[s.size() / 2];
    r.cpu_s_per_sim_s = r.ns_per_step * 1e-9 / r.dt;
  }
}

// The step the knobs run at: the scene's, unless the scene's integrator is unstable there
// in the ladder; then the ladder's largest step at which it is stable (0: none).
double knob_step(const Scene& scene, const std::vector<StudyRun>& ladder) {
  const std::string integrator = integrator_name(scene.options.integrator);
  double largest_stable = 0;
  bool unstable_at_scene_dt = false;
  for (const StudyRun& r : ladder) {
    if (r.integrator != integrator) continue;
    if (r.stable) largest_stable = std::max(largest_stable, r.dt);
    else if (r.dt == scene.dt) unstable_at_scene_dt = true;
  }
  return unstable_at_scene_dt ? largest_stable : scene.dt;
}

// The knobs other than the integrator and the step, each a variant of the default solve
// (the scene's integrator at knob_step): error against the reference and change against
// the default.
// Keep knob_runs() below in step with the runs added here.
void run_knobs(const Scene& scene, const SimulatorOptions& base, const StudyConfig& config,
               const Reference& ref, std::vector<StudyRun>& runs, std::vector<EndState>& ends,
               std::vector<TimedRun>& queue, const StepObserver& observe) {
  const double dt = knob_step(scene, runs);
  if (!(dt > 0)) return;
  // The default solve of each integrator, computed when a knob first needs it.
  std::map<Integrator, EndState> standard;
  auto add = [&](const std::string& kind, const std::string& setting, const SimulatorOptions& o) {
    if (!standard.count(o.integrator)) {
      SimulatorOptions d = base;
      d.integrator = o.integrator;
      standard[o.integrator] = run_to_end(scene, d, dt, config.duration, observe);
    }
    const EndState end = run_to_end(scene, o, dt, config.duration, observe);
    StudyRun r = measure(end, o, dt, config.duration, ref);
    r.kind = kind;
    r.setting = setting;
    const EndState& d = standard[o.integrator];
    r.change_q = end.finite && d.finite ? max_abs_difference(end.q, d.q) : INFINITY;
    queue.push_back({o, dt, r.steps, runs.size()});
    runs.push_back(r);
    ends.push_back(end);
  };
  add("default", "", base);
  SimulatorOptions o = base;
  o.effects &= ~kVelocityProducts;
  add("velocity_products", "off", o);
  for (double tol : {1e-8, 1e-4, 1e-2}) {
    o = base;
    o.solver.policy = SingularityPolicy::Truncate;
    o.solver.tolerance = tol;
    add("truncate_tolerance", number_text(tol), o);
  }
  for (double damping : {1e-6, 1e-4, 1e-2, 1e-1}) {
    o = base;
    o.solver.policy = SingularityPolicy::Damped;
    o.solver.damping = damping;
    add("damped_policy", number_text(damping), o);
  }
  if (uses_friction(scene)) {
    // Smoother friction than the scene's (other physics: change_q is the model's change).
    o = base;
    for (double factor : {2.0, 8.0}) {
      o.solver.friction_velocity = base.solver.friction_velocity * factor;
      add("friction_velocity", number_text(o.solver.friction_velocity), o);
    }
  }
  if (holds_directions(scene)) {
    o = base;
    o.stabilisation_frequency = 10;
    add("stabilisation_frequency", "10", o);
    o.stabilisation_frequency = 1000;
    add("stabilisation_frequency", "1000", o);
    // The held drift the other integrators show with the scene's frequency.
    for (Integrator integrator : kDriftIntegrators) {
      if (integrator == base.integrator) continue;
      o = base;
      o.integrator = integrator;
      add("stabilisation_frequency", number_text(base.stabilisation_frequency), o);
    }
  }
}

// The runs run_knobs() adds (`knobs`) and the default runs it compares them with
// (`standards`).
struct KnobRuns {
  int knobs = 0, standards = 0;
};
KnobRuns knob_runs(const Scene& scene) {
  const bool friction = uses_friction(scene), held = holds_directions(scene);
  int drift = 0;  // kDriftIntegrators other than the scene's
  for (Integrator integrator : kDriftIntegrators) drift += integrator != scene.options.integrator;
  // default, velocity products, 3 tolerances, 4 dampings; 2 friction velocities; 2
  // Baumgarte frequencies and the other integrators at the default one (each with its
  // default run to compare with).
  return {9 + (friction ? 2 : 0) + (held ? 2 + drift : 0), 1 + (held ? drift : 0)};
}

}  // namespace

double planned_steps(const Scene& scene, const StudyConfig& config) {
  const double D = config.duration;
  const double timed = static_cast<double>(config.timing_repeats + 1);  // + the warm-up round
  const auto timing = [&](double steps) { return timed * std::max(1.0, std::min(steps, double(config.timing_steps))); };
  double total = D / config.reference_dt + D / (config.reference_dt / 2);
  for (double dt : config.dts) total += std::size(kLadderIntegrators) * (D / dt + timing(D / dt));
  const double adaptive_dt = *std::max_element(config.dts.begin(), config.dts.end());
  total += static_cast<double>(config.rtols.size()) * (D / adaptive_dt + timing(D / adaptive_dt));
  if (config.knobs) {
    const KnobRuns k = knob_runs(scene);
    total += (k.knobs + k.standards) * (D / scene.dt) + k.knobs * timing(D / scene.dt);
  }
  return total;
}

double max_abs_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

EndState run_to_end(const Scene& scene, const SimulatorOptions& options, double dt, double duration,
                    const StepObserver& observe) {
  Scene variant = scene;
  variant.options = options;
  const bool conserves = variant.conserves_energy();
  Simulator sim(scene.model, options);
  start_scene(scene, sim);
  EndState end;
  const double E0 = sim.energy();
  double max_kinetic = sim.kinetic_energy(), max_energy_error = 0;
  std::int64_t steps = 0;
  try {
    steps = steps_for_duration(duration, dt);
  } catch (const Error& e) {
    throw Error(std::string("accuracy: ") + e.what());
  }
  for (std::int64_t s = 0; s < steps; ++s) {
    try {
      sim.step(dt);
    } catch (const Error& e) {
      end.finite = false;  // the state left the finite numbers or the solver refused it
      end.failure = e.what();
      break;
    }
    if (conserves) {
      max_kinetic = std::max(max_kinetic, sim.kinetic_energy());
      max_energy_error = std::max(max_energy_error, std::abs(sim.energy() - E0));
    }
    if (observe) observe(1);
  }
  end.q = sim.q;
  end.qd = sim.qd;
  end.substeps = sim.substeps();
  end.stiff_substeps = sim.stiff_substeps();
  end.rejected_substeps = sim.rejected_substeps();
  if (conserves && max_kinetic > 0) end.energy_drift = max_energy_error / max_kinetic;
  if (end.finite)  // over every link with directions (the tip's among them)
    for (const LinkDirections& set : sim.direction_sets()) {
      const std::array<double, kNumDirections> drift = sim.max_residuals(set.link);
      for (int k = 0; k < kNumDirections; ++k) end.held_drift[k] = std::max(end.held_drift[k], drift[k]);
    }
  return end;
}

Reference reference_run(const Scene& scene, const SimulatorOptions& options, double dt, double duration,
                        const StepObserver& observe) {
  SimulatorOptions o = options;
  o.integrator = Integrator::RK4;
  Reference ref;
  ref.dt = dt;
  ref.end = run_to_end(scene, o, dt, duration, observe);
  const EndState half = run_to_end(scene, o, dt / 2, duration, observe);
  for (const auto& [end, step] : {std::pair<const EndState&, double>{ref.end, dt}, {half, dt / 2}})
    if (!end.finite)
      throw Error("accuracy: the RK4 reference run at dt " + number_text(step) + " s failed: " + end.failure);
  ref.self_error_q = max_abs_difference(ref.end.q, half.q);
  ref.self_error_qd = max_abs_difference(ref.end.qd, half.qd);
  ref.finer = half;
  return ref;
}

void refine_reference(const Scene& scene, const SimulatorOptions& options, double duration, double wanted,
                      double max_steps, Reference& ref, const StepObserver& observe) {
  SimulatorOptions o = options;
  o.integrator = Integrator::RK4;
  double steps = 0;
  while (ref.self_error_q > wanted && ref.halvings < kMaxReferenceHalvings) {
    const double dt = ref.dt / 4;
    steps += duration / dt;
    if (steps > max_steps) return;
    const EndState finest = run_to_end(scene, o, dt, duration, observe);
    ref.refinement_steps += steps_for_duration(duration, dt);
    if (!finest.finite) return;  // the coarser pair stays the reference
    const double self_error_q = max_abs_difference(ref.finer.q, finest.q);
    if (!(self_error_q <= ref.self_error_q / 4)) return;  // round-off: halving gains nothing
    ref.dt /= 2;
    ref.end = ref.finer;
    ref.finer = finest;
    ref.self_error_q = self_error_q;
    ref.self_error_qd = max_abs_difference(ref.end.qd, ref.finer.qd);
    ++ref.halvings;
  }
}

StudyConfig default_config(const Scene& scene, bool quick) {
  StudyConfig c;
  c.duration = quick ? std::min(scene.duration, 0.5) : scene.duration;
  c.dts = quick ? std::vector<double>{10e-3, 5e-3, 2e-3, 1e-3, 0.5e-3, 0.2e-3}
                : std::vector<double>{10e-3, 5e-3, 2e-3, 1e-3, 0.5e-3, 0.2e-3, 0.1e-3, 0.05e-3};
  c.reference_dt = c.dts.back() / 4;
  return c;
}

Study run_study(const Scene& scene, const StudyConfig& config, const StepObserver& observe) {
  if (!(config.duration > 0)) throw Error("accuracy: duration must be positive");
  if (config.dts.empty()) throw Error("accuracy: no time steps to study");
  const double planned = planned_steps(scene, config);
  if (!(planned <= kMaxStudySteps))
    throw Error("accuracy: the study of " + number_text(config.duration) + " s would take " + number_text(planned) +
                " steps, more than the limit of " + number_text(kMaxStudySteps) +
                ": use --quick (at most 0.5 s) or a scene with a shorter duration");
  const auto wall0 = std::chrono::steady_clock::now();
  Study study;
  study.scene = scene.source;
  study.config = config;
  // The scene's equations, the same at every step (the simulator derives nothing from dt).
  const SimulatorOptions base = scene.options;
  study.friction_velocity = base.solver.friction_velocity;
  study.stabilisation_frequency = base.stabilisation_frequency;

  study.reference = reference_run(scene, base, config.reference_dt, config.duration, observe);
  std::vector<TimedRun> queue;
  std::vector<EndState> ends;  // of each run, to score it again against a refined reference
  for (Integrator integrator : kLadderIntegrators) {
    SimulatorOptions o = base;
    o.integrator = integrator;
    for (std::size_t i = 0; i < config.dts.size(); ++i) {
      const double dt = config.dts[i];
      ends.push_back(run_to_end(scene, o, dt, config.duration, observe));
      StudyRun r = measure(ends.back(), o, dt, config.duration, study.reference);
      r.kind = "integrator";
      queue.push_back({o, dt, r.steps, study.runs.size()});
      study.runs.push_back(r);
    }
  }
  // The adaptive integrator, one run per tolerance (atol = rtol / 100), at the ladder's
  // largest output step: a substep never spans more than one output step, so at a small
  // one the output step rather than the tolerance would set the substeps.
  const double adaptive_dt = *std::max_element(config.dts.begin(), config.dts.end());
  for (double rtol : config.rtols) {
    SimulatorOptions o = base;
    o.integrator = Integrator::DormandPrince;
    o.rtol = rtol;
    o.atol = rtol / 100;
    ends.push_back(run_to_end(scene, o, adaptive_dt, config.duration, observe));
    StudyRun r = measure(ends.back(), o, adaptive_dt, config.duration, study.reference);
    r.kind = "integrator";
    r.setting = "rtol " + number_text(rtol);
    queue.push_back({o, adaptive_dt, r.steps, study.runs.size()});
    study.runs.push_back(r);
  }
  if (config.knobs) run_knobs(scene, base, config, study.reference, study.runs, ends, queue, observe);
  // A reference a tenth of the smallest stable integrator error off, or as close as
  // refine_reference gets: the smallest error measured against a coarse reference is
  // partly the reference's own, so each refinement scores the runs again and asks anew.
  for (;;) {
    double smallest = INFINITY;
    for (const StudyRun& r : study.runs)
      if (r.kind == "integrator" && r.stable) smallest = std::min(smallest, r.error_q);
    const int halvings = study.reference.halvings;
    if (std::isfinite(smallest))
      refine_reference(scene, base, config.duration, smallest / 10, kMaxStudySteps - planned, study.reference,
                       observe);
    if (study.reference.halvings == halvings) break;
    for (std::size_t i = 0; i < study.runs.size(); ++i) score(ends[i], study.reference, study.runs[i]);
  }
  // Observed order p from e ~ C dt^p between each ladder step and the previous one.
  for (std::size_t i = 1; i < study.runs.size(); ++i) {
    StudyRun& r = study.runs[i];
    const StudyRun& previous = study.runs[i - 1];
    if (r.kind == "integrator" && r.setting.empty() && previous.integrator == r.integrator &&
        previous.setting.empty() && previous.kind == "integrator" && previous.stable && r.stable)
      r.order = std::log(previous.error_q / r.error_q) / std::log(previous.dt / r.dt);
  }
  time_interleaved(scene, queue, config, study.runs, observe);
  // The error-cost front of the integrator runs (fixed steps and tolerances together).
  std::vector<CostError> points;
  std::vector<std::size_t> stable_runs;
  for (std::size_t i = 0; i < study.runs.size(); ++i) {
    const StudyRun& r = study.runs[i];
    if (r.kind != "integrator" || !r.stable) continue;
    points.push_back({r.cpu_s_per_sim_s, r.error_q});
    stable_runs.push_back(i);
  }
  const std::vector<bool> front = pareto_front(points);
  for (std::size_t i = 0; i < front.size(); ++i) study.runs[stable_runs[i]].pareto = front[i];
  study.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return study;
}

}  // namespace achd::cli
