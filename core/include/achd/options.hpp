#pragma once
// What a solve computes: the acceleration convention, the effects it includes, and the
// policy for a singular constraint coupling matrix.
#include <cstdint>

namespace achd {

// Effects as bits (MuJoCo's disable bits, inverted): a cleared bit means the term is
// not computed at all, and the outputs stay defined.
enum Effect : std::uint32_t {
  kGravity = 1u << 0,           // uniform gravity (as a fictitious base acceleration)
  kVelocityProducts = 1u << 1,  // Coriolis and centrifugal terms; off = approximation
  kExternalWrenches = 1u << 2,  // the case's f_ext
  kDamping = 1u << 3,           // -damping * qd per joint (URDF <dynamics damping>)
  kFriction = 1u << 4,          // smoothed Coulomb friction (URDF <dynamics friction>)
  kRotorInertia = 1u << 5,      // armature added to each joint's D
  kConstraints = 1u << 6,       // the tip acceleration constraints alpha, beta
};
// What a plain solve includes: everything in the case, no joint-level passive terms
// (KDL's solver and RNEA have none; the simulator turns damping and friction on).
constexpr std::uint32_t kDefaultEffects =
    kGravity | kVelocityProducts | kExternalWrenches | kRotorInertia | kConstraints;
constexpr std::uint32_t kAllEffects = kDefaultEffects | kDamping | kFriction;

enum class Convention {
  Physical,  // beta and link accelerations are real accelerations (default)
  Kdl,       // KDL's numbers: beta_kdl = beta - alpha_lin^T g, a_kdl = a - [g; 0]
};

enum class SingularityPolicy {
  Truncate,  // pseudo-inverse dropping singular values below the tolerance (default)
  Damped,    // damped least squares: nu = (K^2 + lambda^2)^-1 K b, lambda = damping * sigma_max
  // Variable-damping least squares: each eigen-direction k of K = V diag(sigma) V^T gets
  // w_k = sigma_k / (sigma_k^2 + lambda_k^2), with lambda_k = 0 outside the singular region
  // (sigma_k > eps, eps = singular_region * sigma_max) and, inside it, lambda_k^2 =
  // lambda_max^2 (1 - (sigma_k / eps)^2), lambda_max = max_damping * sigma_max: the
  // damping grows smoothly as sigma_k falls, acts only on the directions being lost, and
  // nothing changes (the exact solve) while no direction is in the region.
  VariableDamping,
};

struct Options {
  Convention convention = Convention::Physical;
  std::uint32_t effects = kDefaultEffects;
  SingularityPolicy policy = SingularityPolicy::Truncate;
  double tolerance = 1e-12;         // truncate: sigma < tolerance * sigma_max is dropped
  bool absolute_tolerance = false;  // true: sigma < tolerance (KDL: 1e-14, absolute)
  double damping = 1e-6;            // damped policy: lambda relative to sigma_max
  double singular_region = 5e-3;    // variable_damping: eps relative to sigma_max of K scaled by kind (coupling_solve.cpp)
  double max_damping = 2e-2;        // variable_damping: lambda_max, the same way (defaults: docs/guide/hard-cases.md)
  // variable_damping: keep the exact solve in the singular region where the joints' effort
  // limits allow it (hybrid_dynamics.cpp); the simulator keeps it while every
  // direction is held, and turns it off while one is accelerated (pushed)
  bool exact_within_efforts = true;
  // variable_damping, when a direction is damped: the columns that give way to the others
  // (bit j: column j of nu), solved in the Schur complement while the others are solved
  // exactly (coupling_solve.cpp, solve_held_first). 0: the columns the damped
  // eigen-directions point to (each one's largest component), decided from the state.
  // The simulator fixes them for the rest of a step after its first solve that decides,
  // so that a step's right-hand side does not jump where the largest component changes.
  std::uint64_t gives_way = 0;
  double friction_velocity = 0.05;  // friction = F tanh(qd / friction_velocity)
};

// The default options with other effects: rnea(model, q, qd, qdd, g, {}, with_effects(kGravity)).
inline Options with_effects(std::uint32_t effects) {
  Options o;
  o.effects = effects;
  return o;
}

// Throws achd::Error naming the option unless tolerance >= 0, damping > 0,
// singular_region > 0, max_damping > 0 and friction_velocity > 0 are finite
// (hybrid_dynamics calls it).
void validate(const Options& options);

}  // namespace achd
