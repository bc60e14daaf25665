// The Simulator's checks of its inputs, the step count of a duration, and the integrators' names.
#include "simulator_checks.hpp"

#include <cmath>
#include <utility>

#include "achd/error.hpp"
#include "message_number.hpp"

namespace achd {

void check_state(const Eigen::VectorXd& v, int n, const char* field) {
  if (v.size() != n)
    throw Error(std::string(field) + ": expected " + std::to_string(n) + " values, got " +
                std::to_string(v.size()));
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) throw Error(std::string(field) + "[" + std::to_string(i) + "] is not finite");
}

void check_orientation(const Model& model, const Eigen::VectorXd& q, const char* field) {
  if (model.floating && !(q.segment<4>(3).lpNorm<Eigen::Infinity>() > 0))
    throw Error(std::string(field) + "[3..6]: the floating base's orientation quaternion (qx, qy, qz, qw) is zero");
}

std::string non_finite_joint(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  if (model.floating)
    for (int k = 0; k < 7; ++k)
      if (!std::isfinite(q[k]) || (k < 6 && !std::isfinite(qd[k])))
        return "joint '" + model.root_name + "' (the floating base): " + (std::isfinite(q[k]) ? "qd[" : "q[") +
               std::to_string(k) + "] = " + message_number(std::isfinite(q[k]) ? qd[k] : q[k]);
  for (int i = model.free_joint_rates(); i < model.num_rates(); ++i) {
    const double x = q[model.position_index(i)];
    for (const auto& [name, v] : {std::pair<const char*, double>{"q", x}, {"qd", qd[i]}})
      if (!std::isfinite(v))
        return "joint '" + model.bodies[i].joint_name + "': " + name + " = " + message_number(v);
  }
  return "";
}

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

void check_loop(const Model& model, int loop, const char* what) {
  if (loop < 0 || loop >= static_cast<int>(model.loops.size()))
    throw Error(std::string(what) + ": loop index " + std::to_string(loop) +
                (model.loops.empty() ? " but the model has no loop joints"
                                     : " is not in 0.." + std::to_string(model.loops.size() - 1)));
}

std::string loop_beta_not_finite(const Model& model, int column, double beta) {
  for (const LoopJoint& loop : model.loops)
    for (int k = 0; k < kNumDirections; ++k) {
      if (!((loop.directions >> k) & 1u)) continue;
      if (column-- == 0)
        return std::string("the acceleration to enforce along direction ") + direction_name(k) + " of loop '" +
               loop.name + "' is not finite (beta = " + message_number(beta) + ")";
    }
  return "a loop's acceleration to enforce is not finite";
}

}  // namespace achd
