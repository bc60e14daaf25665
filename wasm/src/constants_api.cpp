// achd_constants(): the effect bits, enum names, defaults and buffer names the JS wrapper
// needs, as one JSON object read once by wasm/js/constants.mjs. Everything in it comes from the C++
// declarations (options.hpp, simulator.hpp, achd/names.hpp, boundary.hpp), so JS has no
// hand-kept copy. achd_solver_options / achd_sim_options describe what a solver or
// simulator was actually given, in the same form, so that tests/node/constants.test.mjs
// can compare the wrapper's choices with the C++ defaults.
#include <cstdio>
#include <string>

#include "achd/achd.hpp"
#include "achd/names.hpp"
#include "boundary.hpp"
#include "c_api.hpp"

namespace achd::wasm {
namespace {

std::string quoted(const char* s) { return std::string("\"") + s + "\""; }

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

template <std::size_t N>
std::string names(const char* const (&list)[N]) {
  std::string s = "[";
  for (std::size_t k = 0; k < N; ++k) s += (k ? "," : "") + quoted(list[k]);
  return s + "]";
}

std::string vector3(const Vector3& v) {
  return "[" + number(v[0]) + "," + number(v[1]) + "," + number(v[2]) + "]";
}

std::string constants() {
  std::string s = "{\"effects\":{";
  bool first = true;
  for (const EffectName& e : kEffectNames) {
    s += (first ? "" : ",") + quoted(e.name) + ":" + std::to_string(e.bit);
    first = false;
  }
  s += "},\"default_effects\":" + std::to_string(kDefaultEffects) +
       ",\"all_effects\":" + std::to_string(kAllEffects) +
       ",\"max_constraints\":" + std::to_string(kMaxConstraints) +
       ",\"max_constraint_columns\":" + std::to_string(kMaxConstraintColumns);
  s += ",\"integrators\":[";
  first = true;
  for (Integrator i : kIntegrators) {
    s += (first ? "" : ",") + quoted(integrator_name(i));
    first = false;
  }
  s += "],\"adaptive_integrators\":[";
  first = true;
  for (Integrator i : kIntegrators) {
    if (!integrator_is_adaptive(i)) continue;
    s += (first ? "" : ",") + quoted(integrator_name(i));
    first = false;
  }
  s += "],\"directions\":[";
  for (int k = 0; k < kNumDirections; ++k) s += (k ? "," : "") + quoted(direction_name(k));
  s += "],\"direction_modes\":" + names(kDirectionModeNames) +
       ",\"limit_policies\":" + names(kLimitPolicyNames) + ",\"conventions\":" + names(kConventionNames) +
       ",\"singularity_policies\":" + names(kSingularityPolicyNames) +
       ",\"direction_event_kinds\":" + names(kDirectionEventKindNames) +
       ",\"motion_kinds\":" + names(kMotionKindNames);
  s += ",\"case_gravity\":" + vector3(Case().gravity);
  s += ",\"options\":" + describe(Options()) + ",\"simulator_options\":" + describe(SimulatorOptions());
  s += ",\"solver_buffers\":" + names(kSolverBufferNames) +
       ",\"simulator_buffers\":" + names(kSimulatorBufferNames) +
       ",\"simulator_results\":" + names(kSimulatorResultNames) + ",\"input_kinds\":" + names(kInputKindNames) + "}";
  return s;
}

}  // namespace

std::string describe(const Options& o) {
  return "{\"convention\":" + quoted(kConventionNames[static_cast<int>(o.convention)]) +
         ",\"effects\":" + std::to_string(o.effects) +
         ",\"policy\":" + quoted(kSingularityPolicyNames[static_cast<int>(o.policy)]) +
         ",\"tolerance\":" + number(o.tolerance) +
         ",\"absolute_tolerance\":" + (o.absolute_tolerance ? "true" : "false") +
         ",\"damping\":" + number(o.damping) + ",\"singular_region\":" + number(o.singular_region) +
         ",\"max_damping\":" + number(o.max_damping) + ",\"friction_velocity\":" + number(o.friction_velocity) + "}";
}

std::string describe(const SimulatorOptions& o) {
  return "{\"integrator\":" + quoted(integrator_name(o.integrator)) +
         ",\"effects\":" + std::to_string(o.effects) + ",\"gravity\":" + vector3(o.gravity) +
         ",\"limits\":" + quoted(kLimitPolicyNames[static_cast<int>(o.limits)]) +
         ",\"stabilisation_frequency\":" + number(o.stabilisation_frequency) +
         ",\"stabilisation_damping\":" + number(o.stabilisation_damping) +
         ",\"rtol\":" + number(o.rtol) + ",\"atol\":" + number(o.atol) +
         ",\"solver\":" + describe(o.solver) + "}";
}

}  // namespace achd::wasm

ACHD_EXPORT const char* achd_constants() {
  static const std::string json = achd::wasm::constants();
  return json.c_str();
}
