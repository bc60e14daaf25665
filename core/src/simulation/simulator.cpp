// The simulator: its construction, reset, and one step: check, evaluate and integrate
// (the chosen integrator, integrators/), limits, events.
#include "achd/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "achd/error.hpp"
#include "achd/kinematics.hpp"
#include "direction_sets.hpp"
#include "integrators.hpp"
#include "loop_closure.hpp"
#include "message_number.hpp"
#include "held_directions.hpp"
#include "simulator_checks.hpp"
#include "tip_kinematics.hpp"

namespace achd {

Simulator::Simulator(const Model& model, const SimulatorOptions& options)
    : model_(model),
      options_(options),
      data_{{Data(model_, kMaxConstraintColumns), Data(model_, kMaxConstraintColumns)}},
      case_(Case::zeros(model_)),
      directions_(std::make_unique<DirectionSets>(model_)),
      integrator_(std::make_unique<IntegratorWorkspace>(model_, model_.num_links() * kNumDirections)),
      limit_data_(model_, kMaxConstraintColumns) {
  // (the directions and their records are a link's: a floating root alone has none)
  if (model_.num_links() == 0)
    throw Error("simulator: the model has no link after the root link '" + model_.root_name +
                "' (a link fixed to it will do)");
  // The steps read the held links' motion from the kinematics (link_state), never the
  // solves' link accelerations: the solves compute those of the links with directions
  // alone, none at first (Data::set_link_outputs; set_of() adds each link).
  for (Data* d : {&data_[0], &data_[1], &limit_data_, &integrator_->stage_data}) d->set_link_outputs({});
  const int n = model_.num_rates();
  q = Case::zeros(model_).q;  // num_positions(): a floating base upright at the origin
  qd = ff_torques = Eigen::VectorXd::Zero(n);
  case_.qd = case_.ff_torques = Eigen::VectorXd::Zero(n);
  case_.f_ext.reserve(model_.num_links());
  case_.coupling_beta = Eigen::VectorXd::Zero(model_.couplings.size());
  case_.loop_beta = Eigen::VectorXd::Zero(model_.num_loop_columns());
  loop_drift_.assign(model_.loops.size(), 0.0);
  // Blocks, impact points and the saved held angles: room for every link, so that no step
  // allocates (the state's held angles grow with the sets, set_of()).
  const int links = model_.num_links();
  case_.constraints.reserve(links);
  impact_points_.resize(links);
  saved_.q = q;
  saved_.qd = qd;
  for (HeldAngles* a : {&saved_.held_angles, &limit_angle_rate_}) a->setZero(links * kNumDirections);
  limit_hits_.reserve(n);
  // Joints resting on a limit stop are prescribed (joint_limits.cpp); none at first.
  case_.qdd_given = Eigen::VectorXd::Zero(n);
  case_.prescribed.assign(n, false);
  limit_stop_.assign(n, 0);
  limit_reached_.assign(n, 0);
  motions_.assign(n, JointMotion{});
  moving_.assign(n, 0);
  impact_case_ = Case::zeros(model_);
  impact_case_.loop_beta = Eigen::VectorXd::Zero(model_.num_loop_columns());
  impact_case_.coupling_beta = Eigen::VectorXd::Zero(model_.couplings.size());
  impact_case_.qdd_given = case_.qdd_given;
  impact_case_.prescribed = case_.prescribed;
  impact_case_.constraints.reserve(links);
  impact_target_ = Eigen::VectorXd::Zero(n);
  X0_.resize(n);
  r_.assign(n, Vector3::Zero());
  v_.assign(n, Vector6::Zero());
  // Mass and centre of mass from the spatial inertia [m 1, -m [c]x; m [c]x, I_o].
  for (const Body& b : model_.bodies) {
    const double m = b.inertia(0, 0);
    const Matrix3 mc = b.inertia.block<3, 3>(3, 0);  // m [c]x
    mass_.push_back(m);
    com_.push_back(m > 0 ? Vector3(Vector3(mc(2, 1), mc(0, 2), mc(1, 0)) / m) : Vector3::Zero());
  }
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

const std::vector<DirectionEvent>& Simulator::events() const { return directions_->events().events(); }
std::int64_t Simulator::events_not_kept() const { return directions_->events().not_kept(); }
std::int64_t Simulator::substeps() const { return integrator_->substeps; }
std::int64_t Simulator::rejected_substeps() const { return integrator_->rejected; }
std::int64_t Simulator::stiff_substeps() const { return integrator_->stiff_substeps; }

void Simulator::reset(const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0) {
  const int n = model_.num_rates();
  check_state(q0, model_.num_positions(), "q0");
  check_orientation(model_, q0, "q0");
  if (qd0.size()) check_state(qd0, n, "qd0");
  q = q0;
  if (qd0.size()) qd = qd0;
  else qd.setZero(n);
  t = 0;
  steps_taken_ = 0;
  integrator_->substeps = integrator_->rejected = integrator_->stiff_substeps = 0;
  integrator_->substep = 0;
  integrator_->clear_stiffness();
  directions_->release_all();  // their driver weights and points stay
  held_angles.setZero();
  update_blocks();
  limit_hits_.clear();
  std::fill(loop_drift_.begin(), loop_drift_.end(), 0.0);
  limit_stop_.assign(n, 0);
  moving_.assign(n, 0);
  case_.prescribed.assign(n, false);
  case_.qdd_given.setZero();
}

void Simulator::step(double dt) {
  check_step(dt);
  const double w_n = options_.stabilisation_frequency, zeta = options_.stabilisation_damping;
  // The state a failed step returns to.
  saved_.q = q;
  saved_.qd = qd;
  const Eigen::Index na = held_angles.size();
  saved_.held_angles.head(na) = held_angles;
  const std::int64_t substeps0 = integrator_->substeps, rejected0 = integrator_->rejected,
                     stiff0 = integrator_->stiff_substeps;
  const auto undo = [&] {
    q = saved_.q;
    qd = saved_.qd;
    held_angles = saved_.held_angles.head(na);
    integrator_->substeps = substeps0;
    integrator_->rejected = rejected0;
    integrator_->stiff_substeps = stiff0;
  };
  Data& first = data_[1 - current_];
  try {
    update_limit_stops(w_n, zeta);
    advance(dt, w_n, zeta, first);
    stop_at_limits();
  } catch (const Error& e) {
    undo();
    throw step_failure(e.what());
  }
  if (!q.allFinite() || !qd.allFinite() || !held_angles.allFinite()) {
    std::string cause = non_finite_joint(model_, q, qd);
    for (Eigen::Index j = 0; j < na && cause.empty(); ++j)
      if (!std::isfinite(held_angles[j]))
        cause = "the held angle of " +
                direction_label(model_, directions_->sets()[j / kNumDirections].link, j % kNumDirections) + " = " +
                message_number(held_angles[j]);
    undo();
    integrator_->stage = -1;
    throw step_failure("the new state is not finite (" + cause + ")");
  }
  finish_step(first);
}

// The caller's state, dt and options (bad input, not a failed step: no undo), the step's
// solve inputs, its clock, and the residuals of the state it starts from.
void Simulator::check_step(double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw Error("step: dt must be positive and finite");
  if (!std::isfinite(t)) throw Error("step: t is not finite");
  check_state(q, model_.num_positions(), "q");
  check_orientation(model_, q, "q");
  check_state(qd, model_.num_rates(), "qd");
  solver_ = options_.solver;
  solver_.effects = options_.effects;
  solver_.convention = Convention::Physical;
  check_simulator_options(options_);
  case_.gravity = options_.gravity;
  case_.ff_torques = ff_torques;
  case_.f_ext = f_ext;
  clock.start(t, dt);
  body_motion(model_, q, qd, X0_, r_, v_);
  directions_->record_residuals(model_, X0_, v_, held_angles);
  // a loop's closure error counts while the loop is enforced (no direction released)
  for (size_t l = 0; l < model_.loops.size(); ++l)
    if (!directions_->events().loop_released(static_cast<int>(l)))
      loop_drift_[l] = std::max(loop_drift_[l], achd::loop_error(model_, model_.loops[l], X0_, v_));
}

// One step of the chosen integrator from this state, its first solve into `first`.
void Simulator::advance(double dt, double w_n, double zeta, Data& first) {
  IntegratorWorkspace& ws = *integrator_;
  auto f = [this, w_n, zeta](const SimulationState& x, Data& out, HeldAngles& rates) {
    evaluate(x, w_n, zeta, out, rates);
  };
  auto rates = [this](const SimulationState& x, HeldAngles& r) { held_angle_rates(x, r); };
  auto implicit = [this, w_n, zeta](const SimulationState& x, double h, Data& out, HeldAngles& r) {
    evaluate_implicit(x, h, w_n, zeta, out, r);
  };
  switch (options_.integrator) {
    case Integrator::ExplicitEuler: explicit_euler(model_, ws, *this, dt, f, first); break;
    case Integrator::SemiImplicitEuler: semi_implicit_euler(model_, ws, *this, dt, f, rates, first); break;
    case Integrator::RK4: rk4(model_, ws, *this, dt, f, first); break;
    case Integrator::DormandPrince:
      dormand_prince(model_, ws, *this, dt, options_.rtol, options_.atol, directions_->integrated_angles(), f,
                     implicit, first);
      break;
    case Integrator::ImplicitEuler: {
      const PassiveTerms passive{solver_.effects, solver_.friction_velocity, control_on_ ? &control_.kd : nullptr};
      // the held directions', loops' and couplings' stabilisation at the step's end too
      const Stabilisation s = implicit_stabilisation(w_n, zeta, dt);
      auto f_end = [this, s](const SimulationState& x, Data& out, HeldAngles& r) { evaluate(x, s.w, s.zeta, out, r); };
      implicit_euler(model_, ws, *this, dt, passive, case_.extra_inertia, f_end, rates, first);
      break;
    }
  }
  if (options_.integrator != Integrator::DormandPrince) ++ws.substeps;
}

// After a good step: its first solve is data(), the direction events, the new t, the
// prescribed joints on their trajectories, the limits, and the re-anchored directions
// (resumed ones, and held ones that yield to a driver, continue from where their point is).
void Simulator::finish_step(const Data& first) {
  current_ = 1 - current_;
  const bool anchor = directions_->update_events(model_, first, t, steps_taken_, options_.stabilisation_frequency);
  ++steps_taken_;
  t = clock.advance();
  follow_trajectories(t);
  apply_limits();
  if (anchor) anchor_directions(directions_->anchored());
}

Error Simulator::step_failure(const std::string& cause) const {
  const std::string held = directions_->held_text(model_), accelerated = directions_->accelerated_text(model_);
  const int stage = integrator_->stage;
  std::string where = integrator_name(options_.integrator);
  if (options_.integrator == Integrator::RK4 && stage >= 0) where += " stage " + std::to_string(stage + 1) + " of 4";
  if (options_.integrator == Integrator::DormandPrince)
    where += (stage >= 0 ? " stage " + std::to_string(stage + 1) + " of 7," : "") +
             (integrator_->stiff ? " stiff: extrapolated implicit Euler" : "") + " substep of " +
             message_number(integrator_->substep) + " s";
  if (!held.empty()) where += "; held: " + held;
  if (!accelerated.empty()) where += "; accelerated: " + accelerated;
  const double t_next = clock.after(1);
  return Error("step " + std::to_string(steps_taken_ + 1) + " from t = " + message_number(t) + " s to " + message_number(t_next) +
               " s (" + where + ") failed: " + cause + "; the state stays at t = " + message_number(t) + " s");
}

void Simulator::run(std::int64_t steps, double dt) {
  if (steps < 0) throw Error("run: steps must be >= 0, got " + std::to_string(steps));
  for (std::int64_t s = 0; s < steps; ++s) step(dt);
}

// Report and Clamp: list the joints at or past a limit (Clamp has put them on it, see
// stop_at_limits).
void Simulator::apply_limits() {
  limit_hits_.clear();
  if (options_.limits == LimitPolicy::Ignore) return;
  for (int i = 0; i < model_.num_rates(); ++i) {
    const JointLimits& l = model_.bodies[i].limits;
    const double x = q[model_.position_index(i)];
    if (x <= l.lower || x >= l.upper) limit_hits_.push_back(i);
  }
}

}  // namespace achd
