#include "achd/joint_motion.hpp"

#include <cmath>
#include <utility>

#include "achd/error.hpp"
#include "achd/names.hpp"

namespace achd {

JointSample sample(const JointMotion& m, double t) {
  switch (m.kind) {
    case MotionKind::Constant: return {m.position, 0, 0};
    case MotionKind::Ramp: return {m.position + m.velocity * t, m.velocity, 0};
    case MotionKind::Sine: {
      // q = c + A sin(w t + phi), qd = A w cos(w t + phi), qdd = -A w^2 sin(w t + phi)
      const double w = 2 * M_PI * m.frequency, angle = w * t + m.phase;
      const double s = std::sin(angle), c = std::cos(angle);
      return {m.position + m.amplitude * s, m.amplitude * w * c, -m.amplitude * w * w * s};
    }
  }
  return {};
}

void validate(const JointMotion& m, const std::string& where) {
  const std::pair<const char*, double> fields[] = {{"position", m.position},   {"velocity", m.velocity},
                                                   {"amplitude", m.amplitude}, {"frequency", m.frequency},
                                                   {"phase", m.phase}};
  for (const auto& [name, value] : fields)
    if (!std::isfinite(value)) throw Error(where + name + " is not finite");
  if (m.frequency < 0) throw Error(where + "frequency must be >= 0 (Hz)");
  const bool ramp = m.kind == MotionKind::Ramp, sine = m.kind == MotionKind::Sine;
  const char* kind = kMotionKindNames[static_cast<int>(m.kind)];
  for (const auto& [name, value] : fields) {
    const std::string n = name;
    const bool read = n == "position" || (ramp && n == "velocity") || (sine && n != "velocity");
    if (!read && value != 0) throw Error(where + n + " is not a parameter of a '" + kind + "' motion");
  }
}

}  // namespace achd
