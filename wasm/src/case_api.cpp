// Cases from JS, parsed by the CLI's case parser (tools/case_json.cpp): robot.solve(case),
// the case-shaped inputs of the other calls (q by joint name, f_ext by link name), and
// the words of its messages. JS hands each input over as JSON text written by its bridge
// (wasm/js/json_text.mjs), which marks the values JSON cannot hold (foreign_values.hpp);
// everything about a case's fields, their forms and their messages is decided here.
#include <nlohmann/json.hpp>

#include "achd/achd.hpp"
#include "boundary.hpp"
#include "c_api.hpp"
#include "case_json.hpp"
#include "foreign_values.hpp"

namespace achd::wasm {
namespace {

// The bridge's JSON text as a JSON value, foreign values marked. (A JS object has no two
// equal keys: the check of parse_json_text, which costs a set of keys per object, is not
// needed here.)
nlohmann::json from_bridge(const char* text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // (a lone UTF-16 surrogate in a string)
    throw Error(std::string("invalid JSON: ") + e.what());
  }
  cli::mark_foreign(j);
  return j;
}

}  // namespace

nlohmann::json json_from_bridge(const char* text) { return from_bridge(text); }

}  // namespace achd::wasm

using achd::wasm::Robot;

// robot.solve(case, options): the case parsed and checked (achd::cli::case_from_json, its
// messages without a file name), solved with the options as achd_solver_set_options takes
// them, the result as the CLI writes it (achd::cli::result_json). Returns the result text,
// valid until the next call on this robot, or null with the reason in achd_last_error().
ACHD_EXPORT const char* achd_robot_solve(Robot* r, const char* case_text, int convention, int policy,
                                         double tolerance, int absolute_tolerance, double damping, unsigned effects,
                                         double friction_velocity) {
  const char* out = nullptr;
  achd::wasm::guarded([&] {
    const achd::Model& model = *r->model;
    const achd::Case c = achd::cli::case_from_json(achd::wasm::from_bridge(case_text), model, "");
    achd::Options o;
    o.convention = static_cast<achd::Convention>(convention);
    o.policy = static_cast<achd::SingularityPolicy>(policy);
    o.tolerance = tolerance;
    o.absolute_tolerance = absolute_tolerance != 0;
    o.damping = damping;
    o.effects = effects;
    o.friction_velocity = friction_velocity;
    if (!r->data) r->data = std::make_unique<achd::Data>(model);
    achd::hybrid_dynamics(model, *r->data, c, o);
    r->result = achd::cli::result_json(model, *r->data, c, achd::cli::Digits::Shortest);
    out = r->result.c_str();
  });
  return out;
}

// One case-shaped input of a JS call (the bridge's JSON text) into `out`, by
// achd::wasm::InputKind: joint positions (q, by name or in model order: num_positions()
// numbers), joint rates (qd, qdd: num_rates()), link wrenches (f_ext: 6 per link after
// the root), a 3-vector (gravity); `field` names it in the messages.
ACHD_EXPORT int achd_robot_read_input(const Robot* r, const char* text, const char* field, int kind, double* out) {
  return achd::wasm::guarded([&] {
    const achd::Model& model = *r->model;
    const nlohmann::json j = achd::wasm::from_bridge(text);
    Eigen::VectorXd v;
    switch (kind) {
      case achd::wasm::kInputJointPositions: v = achd::cli::joint_vector(j, field, model, true); break;
      case achd::wasm::kInputJointRates: v = achd::cli::joint_vector(j, field, model, false); break;
      case achd::wasm::kInputVector3: v = achd::cli::numbers(j, field, 3); break;
      case achd::wasm::kInputLinkWrenches: {
        std::vector<achd::Vector6> wrenches;
        achd::cli::link_wrenches(j, model, field, wrenches);
        for (const achd::Vector6& w : wrenches)
          for (int k = 0; k < 6; ++k) *out++ = w[k];
        return;
      }
      default: throw achd::Error("achd_robot_read_input: no input kind " + std::to_string(kind));
    }
    Eigen::Map<Eigen::VectorXd>(out, v.size()) = v;
  });
}
