// libFuzzer target: the URDF loader on arbitrary text. The first line names the root
// and the tip ("root tip\n"), the rest is the XML. Any outcome but a model or an
// achd::Error (a crash, a sanitizer report, another exception type) is a finding; a
// loaded model must also solve its zero case without error and with finite results.
#include <cstddef>
#include <cstdint>
#include <string>

#include "achd/achd.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(bytes), size);
  const std::size_t eol = text.find('\n');
  if (eol == std::string::npos) return 0;
  const std::string names = text.substr(0, eol);
  const std::size_t space = names.find(' ');
  if (space == std::string::npos) return 0;
  achd::Model model;
  try {
    model = achd::load_urdf_string(text.substr(eol + 1), names.substr(0, space),
                                   names.substr(space + 1));
  } catch (const achd::Error&) {
    return 0;
  }
  achd::Data data(model);
  achd::hybrid_dynamics(model, data, achd::Case::zeros(model));
  if (!data.qdd.allFinite()) __builtin_trap();
  return 0;
}
