#pragma once
// The directions a Simulator holds or accelerates on its links, and the events the
// variable_damping policy records on them.
//
// Directions are the base axes at a point of a link (its origin unless set otherwise):
// x, y, z (linear) and rx, ry, rz (angular). Each link has its own set.
//   Hold, linear e:  keeps e . p_point at its value when the direction was set.
//   Hold, angular e: keeps the integral of e . w_link since it was set at zero (its held
//                    angle, SimulationState::held_angles).
//   Accelerate:      the classical acceleration of the point along e equals the setpoint.
// The directions of a link become one constraint block (Case::constraints) whose columns
// are the active directions, with a Baumgarte-stabilised beta including the
// velocity-product term that separates spatial from classical acceleration.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "achd/spatial.hpp"

namespace achd {

enum class DirectionMode { Free, Hold, Accelerate };

// kNumDirections, direction_name and index_of_direction: spatial.hpp.

// Held angles of the direction sets, kNumDirections per set (Simulator::step integrates them).
using HeldAngles = Eigen::VectorXd;

// The held set of one link: one mode per direction, with what each mode needs (the held
// angles are part of the simulated state: SimulationState::held_angles).
struct HeldDirections {
  std::array<DirectionMode, kNumDirections> mode{};
  std::array<double, kNumDirections> setpoint{};  // Accelerate: classical acceleration
  std::array<double, kNumDirections> target{};    // Hold, linear: e . p_point when set
  // Driver priorities of each direction's column (Case::w_fext, w_ff): 1 = the direction
  // resists f_ext / ff_torques fully; below 1 that share of the driver passes through.
  std::array<double, kNumDirections> w_fext{1, 1, 1, 1, 1, 1}, w_ff{1, 1, 1, 1, 1, 1};

  bool active(int k) const { return mode[k] != DirectionMode::Free; }
  int count() const;
};

// The directions of one link: where they act and their held set.
struct LinkDirections {
  int link = 0;                     // Model::links index
  Vector3 point = Vector3::Zero();  // where the directions act, in the link's frame
  HeldDirections held;
  std::array<double, kNumDirections> max_residual{};  // since each direction was set, while followed
};

// What became of an active direction (a link's, or a loop joint's column), from the solve at
// the start of a step under the variable_damping policy (direction_events.cpp has the
// thresholds). A direction is lost while the damping acts on it and the solve leaves more
// than w^2 1e-9 of its acceleration undelivered (w the stabilisation frequency: a constant
// unmet acceleration u settles, under the stabilisation, as a position error u / w^2);
// damping whose effect stays below that is no event. An accelerated (pushed) direction is
// also lost while the solve gives it up because following it would take a joint past its
// effort limit (effort_ratio > 1), and released once it is wholly given up (ratio >= 2).
//   Limited:  lost, with the damping below the singular value it acts on;
//   Released: lost, with the damping dominating (lambda >= sigma): not followed;
//   Resumed:  not lost for 0.05 s. A released Hold direction resumes from where the
//             tip is: its target (linear: e . p_tip) or held angle (0) is reset then, so
//             the stabilisation does not pull the tip back to the old target.
enum class DirectionEventKind { Limited, Released, Resumed };
struct DirectionEvent {
  double t;            // time of the state whose solve showed the change (s)
  std::int64_t step;   // steps completed at that state (t = t0 + step dt)
  int link;            // index in Model::links of the link whose direction it is; -1: a loop's
  int loop;            // index in Model::loops of the loop joint whose direction it is; -1: a link's
  int direction;       // 0..5: x y z rx ry rz (a loop's: of its loop frame)
  DirectionEventKind kind;
  double sigma_min;    // the coupling matrix's smallest singular value in that solve
  double unmet;        // |acceleration asked - delivered| along the direction (m/s^2 or rad/s^2)
  // max_i |tau_i| / effort_i the pushed directions' solve would take from the joints
  // (Data::effort_ratio): above 1 a push gives way (yield_to_efforts.hpp); 0 without pushes
  double effort_ratio;
};
// The events a Simulator keeps (reserved at construction; later ones are counted in
// Simulator::events_not_kept()).
constexpr std::size_t kMaxDirectionEvents = 10000;

}  // namespace achd
