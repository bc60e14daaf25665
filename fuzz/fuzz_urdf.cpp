// libFuzzer target: the URDF loader on arbitrary text. The first line names the root
// and the tip ("root tip\n"), the rest is the XML; mimic joints load as independent
// joints, as with --mimic independent. Any outcome but a model or an achd::Error (a
// crash, a sanitizer report, another exception type) is a finding; so is a loaded model
// whose solves (with gravity, at the zero configuration and at one off zero) return a number
// that is not finite instead of an achd::Error.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "achd/achd.hpp"

namespace {

bool finite(const achd::Data& d) {
  bool ok = d.qdd.allFinite() && d.constraint_torques.allFinite() && d.total_torques.allFinite() &&
            d.joint_torques.allFinite() && d.nu.allFinite() && d.constraint_wrench.allFinite();
  for (const achd::Vector6& a : d.link_accelerations) ok = ok && a.allFinite();
  return ok;
}

// Solves c; traps on a non-finite result, returns quietly on an achd::Error.
void solve(const achd::Model& model, achd::Data& data, const achd::Case& c) {
  try {
    achd::hybrid_dynamics(model, data, c);
  } catch (const achd::Error&) {
    return;
  }
  if (!finite(data)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(bytes), size);
  const std::size_t eol = text.find('\n');
  if (eol == std::string::npos) return 0;
  const std::string names = text.substr(0, eol);
  const std::size_t space = names.find(' ');
  if (space == std::string::npos) return 0;
  achd::UrdfOptions options;
  options.mimic = achd::MimicJoints::Independent;
  achd::Model model;
  try {
    model = achd::load_urdf_string(text.substr(eol + 1), names.substr(0, space), names.substr(space + 1),
                                   options);
  } catch (const achd::Error&) {
    return 0;
  }
  achd::Data data(model);
  achd::Case c = achd::Case::zeros(model);
  solve(model, data, c);
  for (int i = 0; i < model.num_rates(); ++i) {
    const achd::JointLimits& l = model.bodies[i].limits;
    c.q[i] = std::max(l.lower, std::min(l.upper, 0.5));
  }
  c.gravity = achd::Vector3(0, 0, -9.81);
  solve(model, data, c);
  return 0;
}
