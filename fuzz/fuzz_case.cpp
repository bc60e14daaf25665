// libFuzzer target: the case JSON parser of the CLI (tools/case_json.cpp) against the
// KUKA LWR 4 (7 joints, 7 links), then a solve under both policies and the result JSON.
// Any outcome but a Case or an achd::Error is a finding, and so is a solve that returns
// a number that is not finite (every result, sigma_min included) or a result JSON that
// is not strict JSON.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "case_json.hpp"

namespace {

bool finite_results(const achd::Model& model, const achd::Data& d) {
  bool ok = d.qdd.allFinite() && d.joint_torques.allFinite() && d.constraint_torques.allFinite() &&
            d.total_torques.allFinite() && d.prescribed_torques.allFinite() && d.virtual_torques.allFinite() &&
            d.nu.allFinite() && d.constraint_wrench.allFinite() && d.dropped.allFinite();
  for (int l = 0; l <= model.num_links(); ++l) ok = ok && d.link_accelerations[l].allFinite();
  for (const achd::Vector6& w : d.constraint_wrenches) ok = ok && w.allFinite();
  return ok;
}

// Finite results and a strict result JSON, or an achd::Error; anything else aborts.
void solve_and_check(const achd::Model& model, achd::Data& data, const achd::Case& c,
                     const achd::Options& options) {
  try {
    achd::hybrid_dynamics(model, data, c, options);
    if (!finite_results(model, data) || !std::isfinite(achd::sigma_min(data))) std::abort();
    (void)nlohmann::json::parse(achd::cli::result_json(model, data, c));  // throws on nan, inf
  } catch (const achd::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  static const achd::Model model = achd::load_urdf_file(
      ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  static achd::Data data(model);
  achd::Case c;
  try {
    c = achd::cli::parse_case(std::string(reinterpret_cast<const char*>(bytes), size), model,
                              "fuzz.json");
  } catch (const achd::Error&) {
    return 0;
  }
  achd::Options options;
  solve_and_check(model, data, c, options);
  options.policy = achd::SingularityPolicy::Damped;
  solve_and_check(model, data, c, options);
  options.policy = achd::SingularityPolicy::VariableDamping;
  solve_and_check(model, data, c, options);
  return 0;
}
