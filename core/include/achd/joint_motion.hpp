#pragma once
// Prescribed joint motion in the simulator: a joint's position as a function of the
// simulated time t, with its velocity and acceleration derived analytically (the
// Simulator prescribes the acceleration in every solve, Case::prescribed / qdd_given).
//   constant: q(t) = position                                   qd = 0, qdd = 0
//   ramp:     q(t) = position + velocity t                      qd = velocity, qdd = 0
//   sine:     q(t) = position + amplitude sin(2 pi frequency t + phase)
//             qd = amplitude w cos(w t + phase), qdd = -amplitude w^2 sin(w t + phase),
//             w = 2 pi frequency
// Units: rad (rad/s) for revolute joints, m (m/s) for prismatic ones; frequency in Hz.
#include <string>

namespace achd {

// New values go at the end: the enum value is the index of the name (names.hpp).
enum class MotionKind { Constant, Ramp, Sine };

struct JointMotion {
  MotionKind kind = MotionKind::Constant;
  double position = 0;   // constant: the position; ramp: q at t = 0; sine: the centre
  double velocity = 0;   // ramp
  double amplitude = 0;  // sine
  double frequency = 0;  // sine, Hz (>= 0)
  double phase = 0;      // sine, rad
};

// The position, velocity and acceleration of a motion at time t.
struct JointSample {
  double q = 0, qd = 0, qdd = 0;
};
JointSample sample(const JointMotion& motion, double t);

// Throws achd::Error, prefixed with `where`, on a parameter that is not finite or a
// negative frequency; a parameter its kind does not read must be 0 (a sine's velocity
// would otherwise be silently ignored).
void validate(const JointMotion& motion, const std::string& where);

}  // namespace achd
