// The simulator: state, held directions, and one step of the chosen integrator. Every
// state derivative is one hybrid_dynamics solve with the held set as alpha, beta.
#include "achd/simulator.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

#include "achd/error.hpp"
#include "achd/hybrid_dynamics.hpp"
#include "achd/kinematics.hpp"
#include "direction_events.hpp"
#include "held_directions.hpp"
#include "joint_couplings.hpp"
#include "message_number.hpp"
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

// A floating base's orientation in q (q[3..6]) must not be the zero quaternion, which is
// no orientation (any other length is normalised).
void check_orientation(const Model& model, const Eigen::VectorXd& q, const char* field) {
  if (model.floating && !(q.segment<4>(3).lpNorm<Eigen::Infinity>() > 0))
    throw Error(std::string(field) + "[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
}

// The first joint whose q or qd is not finite, as "joint 'elbow': qd = inf"; "" if none
// (a floating base's free joint: its seven positions and six rates).
std::string non_finite_joint(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (model.floating)
    for (int k = 0; k < 7; ++k)
      if (!std::isfinite(q[k]) || (k < 6 && !std::isfinite(qd[k])))
        return "joint '" + model.root_name + "' (the floating base): " + (std::isfinite(q[k]) ? "qd[" : "q[") +
               std::to_string(k) + "] = " + message_number(std::isfinite(q[k]) ? qd[k] : q[k]);
  for (int i = model.floating ? 6 : 0; i < model.num_joints(); ++i) {
    const double x = q[model.position_index(i)];
    for (const auto& [name, v] : {std::pair<const char*, double>{"q", x}, {"qd", qd[i]}})
      if (!std::isfinite(v))
        return "joint '" + model.bodies[i].joint_name + "': " + name + " = " + message_number(v);
  }
  return "";
}

// The options step() reads, each a positive finite number (rtol, atol: >= 0, one > 0).
void check_simulator_options(const SimulatorOptions& o) {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw Error(std::string(name) + " must be positive and finite, got " + message_number(v));
  };
  positive(o.stabilisation_frequency, "stabilisation_frequency");
  positive(o.stabilisation_damping, "stabilisation_damping");
  for (const auto& [v, name] : {std::pair<double, const char*>{o.rtol, "rtol"}, {o.atol, "atol"}})
    if (!(v >= 0) || !std::isfinite(v)) throw Error(std::string(name) + " must be finite and >= 0, got " + message_number(v));
  if (o.rtol == 0 && o.atol == 0) throw Error("rtol and atol are both 0: at least one must be positive");
}

}  // namespace

std::int64_t steps_for_duration(double duration, double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw Error("dt must be positive and finite, got " + message_number(dt));
  if (!(duration >= 0) || !std::isfinite(duration))
    throw Error("duration must be finite and >= 0, got " + message_number(duration));
  const std::string what = "duration " + message_number(duration) + " s at dt " + message_number(dt) + " s";
  const double exact = duration / dt;  // inf when dt is far below duration
  if (!(exact <= static_cast<double>(kMaxSteps)))
    throw Error(what + " is " + message_number(exact) + " steps, more than 2^53 = " + std::to_string(kMaxSteps) +
                " (the largest step count a double holds exactly)");
  const std::int64_t n = std::llround(exact);
  if (std::abs(static_cast<double>(n) * dt - duration) > 1e-9 * duration)
    throw Error(what + " is " + message_number(exact) + " steps, not a whole number (within 1e-9 relative): " +
                "make the duration a multiple of dt");
  // t = k dt (Simulator::t) advances at every step when dt is at least the spacing of
  // doubles at the end time; always so below 2^52 steps.
  const double end = static_cast<double>(n) * dt;
  if (n > 0 && dt < std::nextafter(end, INFINITY) - end)
    throw Error(what + " is " + std::to_string(n) + " steps, but dt is below the spacing of doubles at t = " +
                message_number(end) + " s (" + message_number(std::nextafter(end, INFINITY) - end) + " s): t + dt == t");
  return n;
}

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
    case Integrator::DormandPrince: return "dormand_prince";
    case Integrator::ImplicitEuler: return "implicit_euler";
  }
  return "?";
}

Simulator::Simulator(const Model& model, const SimulatorOptions& options)
    : model_(model),
      options_(options),
      data_{{Data(model_, kMaxConstraintColumns), Data(model_, kMaxConstraintColumns)}},
      stage_data_(model_, kMaxConstraintColumns),
      case_(Case::zeros(model_)),
      events_(std::make_unique<DirectionEventLog>(kMaxDirectionEvents, model_.num_links())),
      implicit_model_(model_),
      limit_data_(model_, kMaxConstraintColumns) {
  // (the directions and their records are a link's: a floating root alone has none)
  if (model_.num_links() == 0)
    throw Error("simulator: the model has no link after the root link '" + model_.root_name +
                "' (a link fixed to it will do)");
  const int n = model_.num_joints();
  q = Case::zeros(model_).q;  // num_positions(): a floating base upright at the origin
  qd = ff_torques = Eigen::VectorXd::Zero(n);
  case_.qd = case_.ff_torques = Eigen::VectorXd::Zero(n);
  case_.f_ext.reserve(model_.num_links());
  case_.coupling_beta = Eigen::VectorXd::Zero(model_.couplings.size());
  // Direction sets, their blocks and held angles: room for every link, so that setting a
  // direction never moves them and no step allocates.
  const int links = model_.num_links();
  sets_.reserve(links);
  block_set_.reserve(links);
  case_.constraints.reserve(links);
  impact_points_.resize(links);
  anchored_.assign(links, 0);
  for (HeldAngles* a : {&angles_, &angle0_, &angle_stage_, &angle_next_, &limit_angle_rate_})
    a->setZero(links * kNumDirections);
  for (HeldAngles& a : k_angle_) a.setZero(links * kNumDirections);
  limit_hits_.reserve(n);
  // Joints resting on a limit stop are prescribed (joint_limits.cpp); none at first.
  case_.qdd_given = Eigen::VectorXd::Zero(n);
  case_.prescribed.assign(n, false);
  limit_stop_.assign(n, 0);
  limit_reached_.assign(n, 0);
  motions_.assign(n, JointMotion{});
  moving_.assign(n, 0);
  impact_case_ = Case::zeros(model_);
  impact_case_.qdd_given = case_.qdd_given;
  impact_case_.prescribed = case_.prescribed;
  impact_case_.constraints.reserve(links);
  X0_.resize(n);
  r_.assign(n, Vector3::Zero());
  v_.assign(n, Vector6::Zero());
  q0_ = q_stage_ = q_next_ = q;
  qd0_ = qd_stage_ = qd_next_ = Eigen::VectorXd::Zero(n);
  for (auto& k : k_q_) k = Eigen::VectorXd::Zero(q.size());  // dq/dt: configuration_rate
  for (auto& k : k_qd_) k = Eigen::VectorXd::Zero(n);
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

const std::vector<DirectionEvent>& Simulator::events() const { return events_->events(); }
std::int64_t Simulator::events_not_kept() const { return events_->not_kept(); }

void Simulator::reset(const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0) {
  const int n = model_.num_joints();
  check_state(q0, model_.num_positions(), "q0");
  check_orientation(model_, q0, "q0");
  if (qd0.size()) check_state(qd0, n, "qd0");
  q = q0;
  if (qd0.size()) qd = qd0;
  else qd.setZero(n);
  t = 0;
  steps_taken_ = 0;
  substeps_ = rejected_substeps_ = 0;
  substep_ = 0;
  // a reset releases every direction; their driver weights and points stay
  for (LinkDirections& set : sets_) {
    HeldDirections freed;
    freed.w_fext = set.held.w_fext;
    freed.w_ff = set.held.w_ff;
    set.held = freed;
    set.max_residual.fill(0);
  }
  angles_.setZero();
  update_blocks();
  limit_hits_.clear();
  limit_stop_.assign(n, 0);
  moving_.assign(n, 0);
  case_.prescribed.assign(n, false);
  case_.qdd_given.setZero();
  events_->clear();
}

void Simulator::check_joint(int joint, const char* what) const {
  if (joint < 0 || joint >= model_.num_joints())
    throw Error(std::string(what) + ": joint index " + std::to_string(joint) + " is not in 0.." +
                std::to_string(model_.num_joints() - 1));
}

void Simulator::prescribe(int joint, const JointMotion& motion) {
  check_joint(joint, "prescribe");
  if (model_.floating && joint < 6)
    throw Error("prescribe: joint '" + model_.root_name + "' is the floating base's free joint; only its joints "
                "after it take a motion");
  validate(motion, "joint '" + model_.bodies[joint].joint_name + "': ");
  if (!std::isfinite(t)) throw Error("prescribe: t is not finite");
  motions_[joint] = motion;
  moving_[joint] = 1;
  case_.prescribed[joint] = true;
  limit_stop_[joint] = 0;  // its motion is given: no stop holds it
  const JointSample at = sample(motion, t);
  q[model_.position_index(joint)] = at.q;
  qd[joint] = at.qd;
  case_.qdd_given[joint] = at.qdd;
}

void Simulator::release(int joint) {
  check_joint(joint, "release");
  moving_[joint] = 0;
  case_.prescribed[joint] = false;
  case_.qdd_given[joint] = 0;  // a limit stop prescribes 0
}

bool Simulator::prescribed(int joint) const {
  check_joint(joint, "prescribed");
  return moving_[joint] != 0;
}

const JointMotion& Simulator::motion(int joint) const {
  check_joint(joint, "motion");
  if (!moving_[joint]) throw Error("motion: joint '" + model_.bodies[joint].joint_name + "' is not prescribed");
  return motions_[joint];
}

void Simulator::follow_trajectories(double t_at) {
  for (int i = 0; i < model_.num_joints(); ++i) {
    if (!moving_[i]) continue;
    const JointSample at = sample(motions_[i], t_at);
    q[model_.position_index(i)] = at.q;
    qd[i] = at.qd;
  }
}

// x' = f(x) at x = (q, qd, held angles): each link's block (alpha set with its
// directions) gets its beta at this state, one solve, and the held angles' rates e . w_link.
void Simulator::evaluate(const Eigen::VectorXd& q_at, const Eigen::VectorXd& qd_at, const HeldAngles& angles,
                         double t_at, double w_n, Data& out, HeldAngles& angle_rates) {
  if (!q_at.allFinite() || !qd_at.allFinite())
    throw Error("the stage's state is not finite (" + non_finite_joint(model_, q_at, qd_at) + ")");
  body_motion(model_, q_at, qd_at, X0_, r_, v_);
  angle_rates.head(held_angle_count()).setZero();  // sets with no active direction have none
  for (size_t b = 0; b < case_.constraints.size(); ++b) {
    const int s = block_set_[b];
    const LinkDirections& set = sets_[s];
    const TipState at = link_state(model_, X0_, v_, set.link, set.point);
    const double* angle = angles.data() + s * kNumDirections;
    ConstraintVector& beta = case_.constraints[b].beta;
    direction_targets(set.held, at, angle, w_n, options_.stabilisation_damping,
                      options_.effects & kVelocityProducts, beta);
    // beta is the acceleration the solver enforces along each held or accelerated
    // direction, in index order (direction_columns).
    for (int k = 0, column = 0; k < kNumDirections; ++k) {
      if (!set.held.active(k)) continue;
      if (!std::isfinite(beta[column++]))
        throw Error("the acceleration to enforce along " + direction_label(model_, set.link, k) +
                    " is not finite (beta = " + message_number(beta[column - 1]) + "; " +
                    (model_.has_tip() && set.link == model_.num_links() - 1 ? "tip" : "point") + " speed " +
                    message_number(at.v.norm()) + " m/s, " + message_number(at.w.norm()) + " rad/s)");
    }
    for (int k = 0; k < kNumDirections; ++k)
      angle_rates[s * kNumDirections + k] = set.held.mode[k] == DirectionMode::Hold && !is_linear_direction(k)
                                                ? direction_axis(k).dot(at.w) : 0.0;
  }
  for (int i = 0; i < model_.num_joints(); ++i)
    if (moving_[i]) case_.qdd_given[i] = sample(motions_[i], t_at).qdd;
  // Coupled joints: e = q_f - k q_l - c decays as the held directions' errors do,
  //   e'' = -2 zeta w e' - w^2 e.
  for (size_t j = 0; j < model_.couplings.size(); ++j) {
    const JointCoupling& cj = model_.couplings[j];
    case_.coupling_beta[j] = -2 * options_.stabilisation_damping * w_n * coupling_rate_error(model_, cj, qd_at) -
                             w_n * w_n * coupling_position_error(model_, cj, q_at);
  }
  apply_joint_control(q_at, qd_at);
  case_.q = q_at;
  case_.qd = qd_at;
  hybrid_dynamics(implicit_solve_ ? implicit_model_ : model_, out, case_, solver_);
}

void Simulator::step(double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw Error("step: dt must be positive and finite");
  if (!std::isfinite(t)) throw Error("step: t is not finite");
  // The state the caller set (the fields q and qd: bad input, not a failed step).
  check_state(q, model_.num_positions(), "q");
  check_orientation(model_, q, "q");
  check_state(qd, model_.num_joints(), "qd");
  solver_ = options_.solver;
  solver_.effects = options_.effects;
  solver_.convention = Convention::Physical;
  check_simulator_options(options_);
  case_.gravity = options_.gravity;
  case_.ff_torques = ff_torques;
  case_.f_ext = f_ext;
  // t restarts its count from the caller's t or at a new dt (see t in the header).
  if (t != t_written_ || dt != t_dt_) {
    t_origin_ = t;
    t_dt_ = dt;
    t_steps_ = 0;
  }
  // Record the residuals of the state this step starts from.
  body_motion(model_, q, qd, X0_, r_, v_);
  for (size_t s = 0; s < sets_.size(); ++s) {
    LinkDirections& set = sets_[s];
    if (!set.held.count()) continue;
    const TipState at = link_state(model_, X0_, v_, set.link, set.point);
    for (int k = 0; k < kNumDirections; ++k)
      set.max_residual[k] = std::max(set.max_residual[k],
                                     std::abs(direction_error(set.held, k, at, angles_.data() + s * kNumDirections)));
  }

  const double w_n = options_.stabilisation_frequency;
  // The state a failed step returns to.
  q0_ = q;
  qd0_ = qd;
  angle0_.head(held_angle_count()) = angles_.head(held_angle_count());
  const std::int64_t substeps0 = substeps_, rejected0 = rejected_substeps_;
  Data& first = data_[1 - current_];
  const auto undo = [&] {
    q = q0_;
    qd = qd0_;
    angles_.head(held_angle_count()) = angle0_.head(held_angle_count());
    substeps_ = substeps0;
    rejected_substeps_ = rejected0;
    implicit_solve_ = false;
  };
  try {
    update_limit_stops(w_n);
    switch (options_.integrator) {
      case Integrator::ExplicitEuler: step_explicit_euler(dt, w_n, first); break;
      case Integrator::SemiImplicitEuler: step_semi_implicit_euler(dt, w_n, first); break;
      case Integrator::RK4: step_rk4(dt, w_n, first); break;
      case Integrator::DormandPrince: step_dormand_prince(dt, w_n, first); break;
      case Integrator::ImplicitEuler: step_implicit_euler(dt, w_n, first); break;
    }
    if (options_.integrator != Integrator::DormandPrince) ++substeps_;
    stop_at_limits();
  } catch (const Error& e) {
    undo();
    throw step_failure(dt, e.what());
  }
  bool finite = q.allFinite() && qd.allFinite();
  finite = finite && angles_.head(held_angle_count()).allFinite();
  if (!finite) {
    std::string cause = non_finite_joint(model_, q, qd);
    for (int j = 0; j < static_cast<int>(sets_.size() * kNumDirections) && cause.empty(); ++j)
      if (!std::isfinite(angles_[j]))
        cause = "the held angle of " + direction_label(model_, sets_[j / kNumDirections].link, j % kNumDirections) +
                " = " + message_number(angles_[j]);
    undo();
    stage_ = -1;
    throw step_failure(dt, "the new state is not finite (" + cause + ")");
  }
  current_ = 1 - current_;
  events_->update(sets_, first, t, steps_taken_, anchored_);
  ++t_steps_;
  ++steps_taken_;
  t = t_origin_ + static_cast<double>(t_steps_) * dt;
  t_written_ = t;
  follow_trajectories(t);
  apply_limits();
  // resumed directions, and held ones that yield to a driver, continue from where their point is
  bool anchor = false;
  for (size_t s = 0; s < sets_.size(); ++s) {
    anchored_[s] |= yielding_directions(sets_[s].held);
    anchor = anchor || anchored_[s];
  }
  if (anchor) anchor_directions(anchored_);
}

Error Simulator::step_failure(double dt, const std::string& cause) const {
  // "held: z, rx" on a chain's tip; "held: x, y, z of link 'lf_foot', z of link 'rf_foot'"
  std::string held, accelerated;
  for (const LinkDirections& set : sets_) {
    std::string h;
    for (int k = 0; k < kNumDirections; ++k) {
      if (set.held.mode[k] == DirectionMode::Hold) h += (h.empty() ? "" : ", ") + std::string(direction_name(k));
      if (set.held.mode[k] == DirectionMode::Accelerate)
        accelerated += (accelerated.empty() ? "" : ", ") + direction_label(model_, set.link, k).substr(10) + " = " +
                       message_number(set.held.setpoint[k]) + (is_linear_direction(k) ? " m/s^2" : " rad/s^2");
    }
    if (h.empty()) continue;
    const std::string label = direction_label(model_, set.link, 0);  // "direction x[ of link '...']"
    held += (held.empty() ? "" : ", ") + h + label.substr(11);
  }
  std::string where = integrator_name(options_.integrator);
  if (options_.integrator == Integrator::RK4 && stage_ >= 0) where += " stage " + std::to_string(stage_ + 1) + " of 4";
  if (options_.integrator == Integrator::DormandPrince)
    where += (stage_ >= 0 ? " stage " + std::to_string(stage_ + 1) + " of 7," : "") + " substep of " +
             message_number(substep_) + " s";
  if (!held.empty()) where += "; held: " + held;
  if (!accelerated.empty()) where += "; accelerated: " + accelerated;
  const double t_next = t_origin_ + static_cast<double>(t_steps_ + 1) * dt;
  return Error("step " + std::to_string(steps_taken_ + 1) + " from t = " + message_number(t) + " s to " + message_number(t_next) +
               " s (" + where + ") failed: " + cause + "; the state stays at t = " + message_number(t) + " s");
}

void Simulator::run(std::int64_t steps, double dt) {
  if (steps < 0) throw Error("run: steps must be >= 0, got " + std::to_string(steps));
  for (std::int64_t s = 0; s < steps; ++s) step(dt);
}

// x_{k+1} = x_k + dt f(x_k)
void Simulator::step_explicit_euler(double dt, double w_n, Data& first) {
  stage_ = 0;
  evaluate(q, qd, angles_, t, w_n, first, k_angle_[0]);
  integrate(model_, q, qd, dt, q);
  qd += dt * first.qdd;
  const Eigen::Index na = held_angle_count();
  angles_.head(na) += dt * k_angle_[0].head(na);
}

// qd_{k+1} = qd_k + dt qdd(q_k, qd_k);  q_{k+1} = q_k + dt qd_{k+1}; the held angles
// (positions too) advance with the new velocity: dt e . w(q_k, qd_{k+1}).
void Simulator::step_semi_implicit_euler(double dt, double w_n, Data& first) {
  stage_ = 0;
  evaluate(q, qd, angles_, t, w_n, first, k_angle_[0]);
  qd += dt * first.qdd;
  body_motion(model_, q, qd, X0_, r_, v_);
  for (size_t s = 0; s < sets_.size(); ++s) {
    const LinkDirections& set = sets_[s];
    const Vector3 w = link_state(model_, X0_, v_, set.link, set.point).w;
    for (int k = 0; k < kNumDirections; ++k)
      if (set.held.mode[k] == DirectionMode::Hold && !is_linear_direction(k))
        angles_[s * kNumDirections + k] += dt * direction_axis(k).dot(w);
  }
  integrate(model_, q, qd, dt, q);
}

// Classical Runge-Kutta: k1 = f(x), k2 = f(x + dt/2 k1), k3 = f(x + dt/2 k2),
// k4 = f(x + dt k3);  x_{k+1} = x + dt/6 (k1 + 2 k2 + 2 k3 + k4).
// x = (q0_, qd0_, angle0_), set by step().
void Simulator::step_rk4(double dt, double w_n, Data& first) {
  static constexpr double kStageStep[4] = {0, 0.5, 0.5, 1.0};
  const Eigen::Index na = held_angle_count();  // the held angles in use
  for (int s = 0; s < 4; ++s) {
    stage_ = s;
    Data& out = s == 0 ? first : stage_data_;
    if (s == 0) {
      evaluate(q0_, qd0_, angle0_, t, w_n, out, k_angle_[0]);
    } else {
      const double h = kStageStep[s] * dt;
      q_stage_ = q0_ + h * k_q_[s - 1];
      qd_stage_ = qd0_ + h * k_qd_[s - 1];
      angle_stage_.head(na) = angle0_.head(na) + h * k_angle_[s - 1].head(na);
      evaluate(q_stage_, qd_stage_, angle_stage_, t + h, w_n, out, k_angle_[s]);
    }
    configuration_rate(model_, s == 0 ? q0_ : q_stage_, s == 0 ? qd0_ : qd_stage_, k_q_[s]);
    k_qd_[s] = out.qdd;
  }
  const double w = dt / 6;
  q = q0_ + w * (k_q_[0] + 2 * k_q_[1] + 2 * k_q_[2] + k_q_[3]);
  normalise_configuration(model_, q);  // a floating base's quaternion back to unit length
  qd = qd0_ + w * (k_qd_[0] + 2 * k_qd_[1] + 2 * k_qd_[2] + k_qd_[3]);
  angles_.head(na) =
      angle0_.head(na) + w * (k_angle_[0].head(na) + 2 * k_angle_[1].head(na) + 2 * k_angle_[2].head(na) + k_angle_[3].head(na));
}

// Report and Clamp: list the joints at or past a limit (Clamp has put them on it, see
// stop_at_limits).
void Simulator::apply_limits() {
  limit_hits_.clear();
  if (options_.limits == LimitPolicy::Ignore) return;
  for (int i = 0; i < model_.num_joints(); ++i) {
    const JointLimits& l = model_.bodies[i].limits;
    const double x = q[model_.position_index(i)];
    if (x <= l.lower || x >= l.upper) limit_hits_.push_back(i);
  }
}

}  // namespace achd
