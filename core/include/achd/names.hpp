#pragma once
// The one spelling of each option value across scene files, the CLI, the JS API, the
// page and its URL hash: snake_case words, listed in the order of the C++ enums so that a
// name's index is the enum's value (the static_asserts below keep the two in step).
// JS option keys are the same words in camelCase (velocity_products -> velocityProducts).
// Integrator and direction names are integrator_name() (simulator_options.hpp) and
// direction_name() (directions.hpp).
#include <cstdint>

#include "achd/joint_motion.hpp"
#include "achd/options.hpp"
#include "achd/directions.hpp"
#include "achd/simulator_options.hpp"

namespace achd {

struct EffectName {
  const char* name;
  Effect bit;
};
// Every achd::Effect bit, in bit order.
inline constexpr EffectName kEffectNames[] = {
    {"gravity", kGravity},
    {"velocity_products", kVelocityProducts},
    {"external_wrenches", kExternalWrenches},
    {"damping", kDamping},
    {"friction", kFriction},
    {"rotor_inertia", kRotorInertia},
    {"constraints", kConstraints},
};
constexpr bool effect_names_in_bit_order() {
  std::uint32_t all = 0;
  for (std::size_t k = 0; k < sizeof kEffectNames / sizeof kEffectNames[0]; ++k) {
    if (kEffectNames[k].bit != (1u << k)) return false;
    all |= kEffectNames[k].bit;
  }
  return all == kAllEffects;
}
static_assert(effect_names_in_bit_order(), "kEffectNames: one entry per Effect bit, in bit order");

// Convention, SingularityPolicy: index = enum value.
inline constexpr const char* kConventionNames[] = {"physical", "kdl"};
static_assert(static_cast<int>(Convention::Physical) == 0 && static_cast<int>(Convention::Kdl) == 1,
              "kConventionNames follows Convention");
inline constexpr const char* kSingularityPolicyNames[] = {"truncate", "damped", "variable_damping"};
static_assert(static_cast<int>(SingularityPolicy::Truncate) == 0 &&
                  static_cast<int>(SingularityPolicy::Damped) == 1 &&
                  static_cast<int>(SingularityPolicy::VariableDamping) == 2,
              "kSingularityPolicyNames follows SingularityPolicy");

// LimitPolicy, DirectionMode: index = enum value. Scene files and JS give an accelerated
// direction as its setpoint (a number), not by this name.
inline constexpr const char* kLimitPolicyNames[] = {"ignore", "report", "clamp"};
static_assert(static_cast<int>(LimitPolicy::Ignore) == 0 && static_cast<int>(LimitPolicy::Report) == 1 &&
                  static_cast<int>(LimitPolicy::Clamp) == 2,
              "kLimitPolicyNames follows LimitPolicy");
inline constexpr const char* kDirectionModeNames[] = {"free", "hold", "accelerate"};
static_assert(static_cast<int>(DirectionMode::Free) == 0 && static_cast<int>(DirectionMode::Hold) == 1 &&
                  static_cast<int>(DirectionMode::Accelerate) == 2,
              "kDirectionModeNames follows DirectionMode");
// DirectionEventKind: index = enum value.
inline constexpr const char* kDirectionEventKindNames[] = {"limited", "released", "resumed"};
static_assert(static_cast<int>(DirectionEventKind::Limited) == 0 &&
                  static_cast<int>(DirectionEventKind::Released) == 1 &&
                  static_cast<int>(DirectionEventKind::Resumed) == 2,
              "kDirectionEventKindNames follows DirectionEventKind");
// MotionKind (prescribed joint motion): index = enum value.
inline constexpr const char* kMotionKindNames[] = {"constant", "ramp", "sine"};
static_assert(static_cast<int>(MotionKind::Constant) == 0 && static_cast<int>(MotionKind::Ramp) == 1 &&
                  static_cast<int>(MotionKind::Sine) == 2,
              "kMotionKindNames follows MotionKind");
// Every Integrator, in enum order (names: integrator_name()).
inline constexpr Integrator kIntegrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler,
                                              Integrator::RK4, Integrator::DormandPrince,
                                              Integrator::ImplicitEuler};
// Whether an integrator controls its own error (takes SimulatorOptions::rtol and atol,
// steps in substeps of its own choosing) rather than taking fixed steps of dt.
constexpr bool integrator_is_adaptive(Integrator integrator) { return integrator == Integrator::DormandPrince; }

}  // namespace achd
