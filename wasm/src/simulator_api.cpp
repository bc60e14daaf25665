// The simulator: achd::Simulator stepping a robot, its state (q, qd, t, ff_torques,
// f_ext) exposed to JS as views on the Simulator's own Eigen buffers.
#include <algorithm>
#include <limits>
#include <vector>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"
#include "boundary.hpp"
#include "c_api.hpp"

using achd::wasm::Robot;

// integrator, limits, policy: enum values (indices into the integrators, limit_policies
// and singularity_policies of achd_constants()); gravity: 3 doubles, or null for
// SimulatorOptions' default. The rest are the scene file's friction_velocity,
// stabilisation_frequency, stabilisation_damping, rtol, atol, singular_region and
// max_damping.
ACHD_EXPORT achd::Simulator* achd_sim_create(const Robot* r, int integrator, unsigned effects,
                                             const double* gravity, int limits,
                                             double friction_velocity, double stabilisation_frequency,
                                             double stabilisation_damping, double rtol, double atol,
                                             int policy, double singular_region, double max_damping) {
  achd::Simulator* sim = nullptr;
  achd::wasm::guarded([&] {
    achd::SimulatorOptions o;
    o.integrator = static_cast<achd::Integrator>(integrator);
    o.effects = effects;
    if (gravity) o.gravity = achd::Vector3(gravity);
    o.limits = static_cast<achd::LimitPolicy>(limits);
    o.solver.friction_velocity = friction_velocity;
    o.stabilisation_frequency = stabilisation_frequency;
    o.stabilisation_damping = stabilisation_damping;
    o.rtol = rtol;
    o.atol = atol;
    o.solver.policy = static_cast<achd::SingularityPolicy>(policy);
    o.solver.singular_region = singular_region;
    o.solver.max_damping = max_damping;
    sim = new achd::Simulator(*r->model, o);
    if (sim->f_ext.empty()) sim->f_ext.assign(r->model->num_links(), achd::Vector6::Zero());
  });
  return sim;
}

ACHD_EXPORT void achd_sim_delete(achd::Simulator* sim) { delete sim; }

// The buffers behind the JS views, by achd::wasm::SimulatorBuffer index (f_ext: 6 per link).
ACHD_EXPORT double* achd_sim_buffer(achd::Simulator* sim, int which) {
  switch (which) {
    case achd::wasm::kSimQ: return sim->q.data();
    case achd::wasm::kSimQd: return sim->qd.data();
    case achd::wasm::kSimT: return &sim->t;
    case achd::wasm::kSimFfTorques: return sim->ff_torques.data();
    case achd::wasm::kSimFExt: return sim->f_ext.front().data();
    default: return nullptr;
  }
}

// At most 2^31 - 1 steps per call: the wrapper (Simulator.step) splits larger counts.
ACHD_EXPORT int achd_sim_run(achd::Simulator* sim, int steps, double dt) {
  return achd::wasm::guarded([&] { sim->run(steps, dt); });
}

// Steps completed since construction or reset(), as a double (exact below 2^53).
ACHD_EXPORT double achd_sim_steps_taken(const achd::Simulator* sim) {
  return static_cast<double>(sim->steps_taken());
}

// The integrator's substeps accepted and rejected since construction or reset(), as doubles.
ACHD_EXPORT double achd_sim_substeps(const achd::Simulator* sim) { return static_cast<double>(sim->substeps()); }
ACHD_EXPORT double achd_sim_rejected_substeps(const achd::Simulator* sim) {
  return static_cast<double>(sim->rejected_substeps());
}
ACHD_EXPORT double achd_sim_stiff_substeps(const achd::Simulator* sim) {
  return static_cast<double>(sim->stiff_substeps());
}

ACHD_EXPORT int achd_sim_reset(achd::Simulator* sim, const double* q, const double* qd) {
  return achd::wasm::guarded([&] {
    // q: num_positions() numbers (a floating base's 7 first), qd: num_rates()
    const int nq = static_cast<int>(sim->q.size()), n = static_cast<int>(sim->qd.size());
    sim->reset(Eigen::Map<const Eigen::VectorXd>(q, nq), Eigen::Map<const Eigen::VectorXd>(qd, n));
  });
}

// In the direction calls, link is a Model::links index, or -1 for a chain's tip (an error
// on a tree).
// mode: an achd::DirectionMode value (index into direction_modes of achd_constants());
// Accelerate: classical acceleration of the link's point = setpoint.
ACHD_EXPORT int achd_sim_set_direction(achd::Simulator* sim, int link, int index, int mode, double setpoint) {
  return achd::wasm::guarded([&] {
    const auto m = static_cast<achd::DirectionMode>(mode);
    if (link < 0) sim->set_direction(index, m, setpoint);
    else sim->set_direction(link, index, m, setpoint);
  });
}

// Driver priorities of a direction (Simulator::set_direction_weights).
ACHD_EXPORT int achd_sim_set_direction_weights(achd::Simulator* sim, int link, int index, double w_fext,
                                               double w_ff) {
  return achd::wasm::guarded([&] {
    if (link < 0) sim->set_direction_weights(index, w_fext, w_ff);
    else sim->set_direction_weights(link, index, w_fext, w_ff);
  });
}

// Where a link's directions act, 3 doubles in its frame (Simulator::set_direction_point).
ACHD_EXPORT int achd_sim_set_direction_point(achd::Simulator* sim, int link, const double* point) {
  return achd::wasm::guarded([&] { sim->set_direction_point(link, achd::Vector3(point)); });
}

// The links with directions (Simulator::direction_sets), in the order of nu: their count,
// and with out != nullptr per set its link index and its number of active directions.
ACHD_EXPORT int achd_sim_direction_sets(const achd::Simulator* sim, int* out) {
  const std::vector<achd::LinkDirections>& sets = sim->direction_sets();
  if (out)
    for (const achd::LinkDirections& s : sets) {
      *out++ = s.link;
      *out++ = s.held.count();
    }
  return static_cast<int>(sets.size());
}

// The joint PD controller (Simulator::set_joint_control): target num_positions()
// doubles; kp and kd num_rates() each, or both null for gains from frequency (Hz) and
// damping_ratio; hold != 0 adds the hold feed-forward (JointControl::hold).
ACHD_EXPORT int achd_sim_set_joint_control(achd::Simulator* sim, const double* target, const double* kp,
                                           const double* kd, double frequency, double damping_ratio, int hold) {
  return achd::wasm::guarded([&] {
    const int nq = static_cast<int>(sim->q.size()), n = static_cast<int>(sim->qd.size());
    achd::JointControl c;
    c.target = Eigen::Map<const Eigen::VectorXd>(target, nq);
    if (kp) c.kp = Eigen::Map<const Eigen::VectorXd>(kp, n);
    if (kd) c.kd = Eigen::Map<const Eigen::VectorXd>(kd, n);
    c.frequency = frequency;
    c.damping_ratio = damping_ratio;
    c.hold = hold != 0;
    sim->set_joint_control(c);
  });
}
ACHD_EXPORT void achd_sim_clear_joint_control(achd::Simulator* sim) { sim->clear_joint_control(); }
ACHD_EXPORT int achd_sim_joint_control_on(const achd::Simulator* sim) { return sim->joint_control_on() ? 1 : 0; }

// Prescribed joint motion (Simulator::prescribe): kind an index into motion_kinds of
// achd_constants(), the parameters of achd::JointMotion.
ACHD_EXPORT int achd_sim_prescribe(achd::Simulator* sim, int joint, int kind, double position, double velocity,
                                   double amplitude, double frequency, double phase) {
  return achd::wasm::guarded([&] {
    achd::JointMotion m;
    m.kind = static_cast<achd::MotionKind>(kind);
    m.position = position;
    m.velocity = velocity;
    m.amplitude = amplitude;
    m.frequency = frequency;
    m.phase = phase;
    sim->prescribe(joint, m);
  });
}

ACHD_EXPORT int achd_sim_release(achd::Simulator* sim, int joint) {
  return achd::wasm::guarded([&] { sim->release(joint); });
}

ACHD_EXPORT int achd_sim_prescribed(const achd::Simulator* sim, int joint) { return sim->prescribed(joint) ? 1 : 0; }

// -1 on an error (achd_last_error: a tree's tip, an index out of range).
ACHD_EXPORT int achd_sim_direction_mode(const achd::Simulator* sim, int link, int index) {
  int mode = -1;
  achd::wasm::guarded([&] {
    mode = static_cast<int>(link < 0 ? sim->direction_mode(index) : sim->direction_mode(link, index));
  });
  return mode;
}

// out: the 6 held-direction residuals (m or rad) of a link (-1: the tip).
ACHD_EXPORT int achd_sim_residuals(const achd::Simulator* sim, int link, double* out) {
  return achd::wasm::guarded([&] {
    const std::array<double, achd::kNumDirections> r = link < 0 ? sim->residuals() : sim->residuals(link);
    for (int k = 0; k < achd::kNumDirections; ++k) out[k] = r[k];
  });
}

// out: how long (s) each of the 6 directions of a link (-1: the tip) was released since
// it was set (Simulator::released_seconds).
ACHD_EXPORT int achd_sim_released_seconds(const achd::Simulator* sim, int link, double* out) {
  return achd::wasm::guarded([&] {
    if (link < 0 && !sim->model().has_tip())
      throw achd::Error("releasedSeconds: the model is a tree (loaded without a tip); name the link whose directions these are");
    const std::array<double, achd::kNumDirections> r =
        sim->released_seconds(link < 0 ? sim->model().num_links() - 1 : link);
    for (int k = 0; k < achd::kNumDirections; ++k) out[k] = r[k];
  });
}

// out: how long (s) each of the 6 directions of loop joint `loop` (of its loop frame) was
// released since reset (Simulator::loop_released_seconds).
ACHD_EXPORT int achd_sim_loop_released_seconds(const achd::Simulator* sim, int loop, double* out) {
  return achd::wasm::guarded([&] {
    const std::array<double, achd::kNumDirections> r = sim->loop_released_seconds(loop);
    for (int k = 0; k < achd::kNumDirections; ++k) out[k] = r[k];
  });
}

// out: 6 doubles per constraint block of the last solve (the links of
// achd_sim_direction_sets with active directions, in order, then the loop joints):
// alpha nu at the block's point, what link (a) exerts on its constraint
// (Data::constraint_wrenches).
ACHD_EXPORT int achd_sim_constraint_wrenches(const achd::Simulator* sim, double* out) {
  const std::vector<achd::Vector6>& w = sim->data().constraint_wrenches;
  if (out)
    for (const achd::Vector6& f : w)
      for (int k = 0; k < 6; ++k) *out++ = f[k];
  return static_cast<int>(w.size());
}

// Loop joint `loop`'s closure error now (which = 0) or its largest since reset (1), m or
// rad; NaN with the reason in achd_last_error() on a bad index.
ACHD_EXPORT double achd_sim_loop_error(const achd::Simulator* sim, int loop, int which) {
  double out = std::numeric_limits<double>::quiet_NaN();
  achd::wasm::guarded([&] { out = which ? sim->loop_drift(loop) : sim->loop_error(loop); });
  return out;
}

ACHD_EXPORT double achd_sim_kinetic_energy(const achd::Simulator* sim) { return sim->kinetic_energy(); }
ACHD_EXPORT double achd_sim_potential_energy(const achd::Simulator* sim) { return sim->potential_energy(); }

// The solve at the start of the last step, by achd::wasm::SimulatorResult index.
ACHD_EXPORT const double* achd_sim_result(const achd::Simulator* sim, int which) {
  const achd::Data& d = sim->data();
  switch (which) {
    case achd::wasm::kSimNu: return d.nu.data();
    case achd::wasm::kSimJointTorques: return d.joint_torques.data();
    case achd::wasm::kSimQdd: return d.qdd.data();
    case achd::wasm::kSimPrescribedTorques: return d.prescribed_torques.data();
    default: return nullptr;
  }
}
ACHD_EXPORT int achd_sim_nu_size(const achd::Simulator* sim) { return static_cast<int>(sim->data().nu.size()); }

// Joints at or past a limit after the last step (limits 'report' or 'clamp'): their
// count, and with out != nullptr their indices, root to tip.
ACHD_EXPORT int achd_sim_limit_hits(const achd::Simulator* sim, int* out) {
  const std::vector<int>& hits = sim->limit_hits();
  if (out) std::copy(hits.begin(), hits.end(), out);
  return static_cast<int>(hits.size());
}

// The simulator's options, as achd::wasm::describe writes them; valid until the next call.
ACHD_EXPORT const char* achd_sim_options(const achd::Simulator* sim) {
  static std::string json;
  json = achd::wasm::describe(sim->options());
  return json.c_str();
}

// Direction events (Simulator::events()): their count, and with out != nullptr nine
// doubles each: t, step, link (index after the root; -1 for a loop's), loop (index into
// the model's loops; -1 for a link's), direction (0..5), kind (index into
// direction_event_kinds of achd_constants()), sigma_min, unmet, effort_ratio.
ACHD_EXPORT int achd_sim_events(const achd::Simulator* sim, double* out) {
  const std::vector<achd::DirectionEvent>& events = sim->events();
  if (out)
    for (const achd::DirectionEvent& e : events) {
      *out++ = e.t;
      *out++ = static_cast<double>(e.step);
      *out++ = e.link;
      *out++ = e.loop;
      *out++ = e.direction;
      *out++ = static_cast<int>(e.kind);
      *out++ = e.sigma_min;
      *out++ = e.unmet;
      *out++ = e.effort_ratio;
    }
  return static_cast<int>(events.size());
}

// Events that happened beyond the kept ones (kMaxDirectionEvents).
ACHD_EXPORT double achd_sim_events_not_kept(const achd::Simulator* sim) {
  return static_cast<double>(sim->events_not_kept());
}
