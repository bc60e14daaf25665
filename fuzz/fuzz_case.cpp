// libFuzzer target: the case JSON parser of the CLI (tools/case_json.cpp) against the
// KUKA LWR 4 (7 joints, 7 links). Any outcome but a Case or an achd::Error is a
// finding; a parsed case must solve without error, both policies.
#include <cstddef>
#include <cstdint>
#include <string>

#include "case_json.hpp"

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
  achd::hybrid_dynamics(model, data, c, options);
  options.policy = achd::SingularityPolicy::Damped;
  achd::hybrid_dynamics(model, data, c, options);
  return 0;
}
