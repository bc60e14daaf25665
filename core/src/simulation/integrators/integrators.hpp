#pragma once
// The Simulator's integrators, free functions that advance a state x = (q, qd, held
// angles) (SimulationState) by one step of dt from its time x.t, given f: x' = f(x).
// `evaluate(x, out, rates)` solves at state x (at time x.t) into `out` (its qdd is
// qd') and writes the held angles' rates; `angle_rates(x, rates)` writes those rates
// alone (from the kinematics: no solve). q' is configuration_rate(q, qd). Each writes its
// first evaluation (at the step's start) into `first`. x.t is the step's start throughout
// (the Simulator's clock advances t); a stage that throws leaves x partly advanced, and
// the Simulator restores the state it started from.
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "achd/data.hpp"
#include "achd/model.hpp"
#include "achd/simulator.hpp"

namespace achd {

// A reference to a callable for the length of a call: no allocation, one indirect call.
template <class Signature>
class FunctionRef;
template <class R, class... A>
class FunctionRef<R(A...)> {
 public:
  template <class C, class = std::enable_if_t<!std::is_same_v<C, FunctionRef>>>
  FunctionRef(C& callable)  // NOLINT: implicit, as a function parameter
      : object_(&callable), call_([](void* o, A... a) -> R { return (*static_cast<C*>(o))(std::forward<A>(a)...); }) {}
  R operator()(A... a) const { return call_(object_, std::forward<A>(a)...); }

 private:
  void* object_;
  R (*call_)(void*, A...);
};

using Evaluate = FunctionRef<void(const SimulationState&, Data&, HeldAngles&)>;
using AngleRates = FunctionRef<void(const SimulationState&, HeldAngles&)>;
// `implicit_evaluate(x, h, out, rates)`: the solve of a linearly implicit step of h from x
// (extrapolated_implicit_euler.cpp): evaluate's, with h c_i + h^2 kp_i added to joint i's
// axial inertia and the PD torque taken at q + h qd (Simulator::evaluate_implicit).
using ImplicitEvaluate = FunctionRef<void(const SimulationState&, double, Data&, HeldAngles&)>;

// The most rows of the extrapolated implicit Euler method's tableau: its highest order
// (extrapolated_implicit_euler.cpp).
constexpr int kMaxImplicitRows = 6;

// Storage of the integrators, sized once for the model and held angles for every link.
struct IntegratorWorkspace {
  IntegratorWorkspace(const Model& model, Eigen::Index max_held_angles);

  // Stage derivatives k_s of (q, qd, held angles): RK4 uses 4, Dormand-Prince 7.
  static constexpr int kMaxStages = 7;
  Eigen::VectorXd k_q[kMaxStages], k_qd[kMaxStages];
  HeldAngles k_angle[kMaxStages];
  SimulationState stage_state;  // the state a stage is evaluated at
  SimulationState next_state;   // Dormand-Prince: the 5th-order solution of a substep
  // The extrapolated implicit Euler method: its tableau's row and a scratch state.
  SimulationState extrapolation[kMaxImplicitRows + 1];
  HeldAngles rates;       // semi-implicit Euler: the held angles' rates at the new velocity
  Data stage_data;        // the solves after the first
  Eigen::VectorXd extra_inertia;  // implicit Euler: dt c_i per joint
  int stage = 0;          // the stage being evaluated (RK4: 0..3; -1: none), for messages
  double substep = 0;     // Dormand-Prince: the substep proposed for the next one (0: none yet)
  std::int64_t substeps = 0, rejected = 0;  // accepted and rejected substeps
  // Dormand-Prince's stiffness detection (dormand_prince.cpp): the accepted substeps whose
  // h lambda exceeded kStiffHLambda since the count was last cleared, the substeps in a row
  // below it, whether the substeps are the extrapolated implicit Euler's (stiff), the
  // spectral radius lambda last estimated (1/s), and the stiff substeps accepted.
  int stiff_count = 0, nonstiff_count = 0;
  bool stiff = false;
  double stiff_lambda = 0;
  std::int64_t stiff_substeps = 0;
  // Clears the stiffness detection (reset(), a new controller): Dormand-Prince again.
  void clear_stiffness() {
    stiff_count = nonstiff_count = 0;
    stiff = false;
    stiff_lambda = 0;
  }
};

// x_{k+1} = x_k + dt f(x_k)
void explicit_euler(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt, Evaluate evaluate,
                    Data& first);
// qd_{k+1} = qd_k + dt qdd(q_k, qd_k);  q_{k+1} = q_k + dt qd_{k+1}; the held angles
// (positions too) advance with the new velocity: dt e . w(q_k, qd_{k+1}).
void semi_implicit_euler(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt,
                         Evaluate evaluate, AngleRates angle_rates, Data& first);
// Classical Runge-Kutta, order 4 (rk4.cpp).
void rk4(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt, Evaluate evaluate, Data& first);
// The adaptive Dormand-Prince 5(4) pair (dormand_prince.cpp): substeps to x.t + dt under
// rtol, atol, the error norm over q, qd and the held angles marked in `integrated_angles`.
// Where it detects stiffness its substeps are the extrapolated implicit Euler's below,
// until the stiffness estimate falls again.
void dormand_prince(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt, double rtol,
                    double atol, const std::vector<char>& integrated_angles, Evaluate evaluate,
                    ImplicitEvaluate implicit_evaluate, Data& first);
// One substep of h from x (at time t) of the extrapolated linearly implicit Euler method
// (extrapolated_implicit_euler.cpp): rows added until the error norm (as Dormand-Prince's:
// RMS of err_i / (atol + rtol max(|x_i|, |x'_i|)), the error O(h^rows)) is <= 1, its
// result (order `rows`) then in ws.next_state; else the error with kMaxImplicitRows (inf
// when a state is not finite). ws.stage_state is overwritten.
struct ImplicitSubstep {
  double err;
  int rows;
};
ImplicitSubstep extrapolated_implicit_euler(const Model& model, IntegratorWorkspace& ws, const SimulationState& x,
                                            double t, double h, double rtol, double atol,
                                            const std::vector<char>& integrated_angles,
                                            ImplicitEvaluate implicit_evaluate);

// Implicit Euler (implicit_euler.cpp): semi-implicit Euler whose solves see, in
// `solve_extra_inertia` (the Case::extra_inertia that `evaluate` solves with), dt times
// each joint's passive-torque derivative: damping and friction per `effects`, and the PD
// controller's kd (nullptr: none). Empty again afterwards, also when a stage throws.
struct PassiveTerms {
  std::uint32_t effects;
  double friction_velocity;
  const Eigen::VectorXd* kd;
  const Eigen::VectorXd* kp = nullptr;  // the PD controller's kp (extrapolated implicit Euler)
};
// out_i = h c_i + h^2 kp_i: c_i = b_i + F_i / (v_f cosh^2(qd_i / v_f)) + kd_i, the
// derivative of joint i's passive and PD torque in -qd_i (per `passive`: damping and
// friction by its effects, kd and kp when given), kp_i its derivative in -q_i.
void implicit_inertia(const Model& model, const PassiveTerms& passive, const Eigen::VectorXd& qd, double h,
                      Eigen::VectorXd& out);
// The held directions', loops' and couplings' stabilisation e'' = -2 zeta w e' - w^2 e
// (e a constraint's error) taken at the step's end (implicit_euler.cpp): the w and zeta
// whose beta at the step's start enforces it.
struct Stabilisation {
  double w, zeta;
};
Stabilisation implicit_stabilisation(double w, double zeta, double dt);
void implicit_euler(const Model& model, IntegratorWorkspace& ws, SimulationState& x, double dt,
                    const PassiveTerms& passive, Eigen::VectorXd& solve_extra_inertia, Evaluate evaluate,
                    AngleRates angle_rates, Data& first);

}  // namespace achd
