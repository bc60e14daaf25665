#pragma once
// Time stepping of a chain under the hybrid solver: state (q, qd, t), integrators, the
// effects a scene enables, and tip directions the user holds or accelerates.
//
// Directions are the base axes at the tip: x, y, z (linear) and rx, ry, rz (angular).
//   Hold, linear e:  keeps e . p_tip at its value when the direction was set.
//   Hold, angular e: keeps the integral of e . w_tip since it was set at zero.
//   Accelerate:      the classical tip acceleration along e equals the setpoint.
// A held direction becomes a row of alpha with a Baumgarte-stabilised beta, including
// the velocity-product term that separates spatial from classical acceleration.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "achd/case.hpp"
#include "achd/data.hpp"
#include "achd/model.hpp"
#include "achd/options.hpp"

namespace achd {

enum class Integrator { ExplicitEuler, SemiImplicitEuler, RK4 };
enum class DirectionMode { Free, Hold, Accelerate };
enum class LimitPolicy { Ignore, Report, Clamp };

constexpr int kNumDirections = 6;
// "x", "y", "z", "rx", "ry", "rz"; index_of_direction returns -1 for anything else.
const char* direction_name(int index);
int index_of_direction(const std::string& name);
const char* integrator_name(Integrator integrator);

struct SimulatorOptions {
  Integrator integrator = Integrator::RK4;
  std::uint32_t effects = kAllEffects;       // achd::Effect bits
  Vector3 gravity = Vector3(0, 0, -9.81);
  LimitPolicy limits = LimitPolicy::Report;
  // Baumgarte stabilisation of held directions: beta = -2 zeta w e_dot - w^2 e.
  double stabilisation_frequency = 0;        // w in rad/s; 0 = chosen from dt
  double stabilisation_damping = 1.0;        // zeta
  Options solver;                            // policy, tolerances (effects are above)
};

class Simulator {
 public:
  Simulator(const Model& model, const SimulatorOptions& options = {});

  // State, root to tip. Setting them directly is allowed; reset() also restarts t,
  // releases every direction and clears the energy and drift records.
  Eigen::VectorXd q, qd;
  double t = 0;
  Eigen::VectorXd ff_torques;   // joint torques applied every step (default 0)
  std::vector<Vector6> f_ext;   // wrench per link after the root (base orientation)

  void reset(const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0);
  void set_direction(int index, DirectionMode mode, double setpoint = 0);
  DirectionMode direction_mode(int index) const;
  void step(double dt);
  void run(int steps, double dt);

  // Held-direction residuals in m or rad (0 for directions that are not held).
  std::array<double, kNumDirections> residuals() const;
  double kinetic_energy() const;
  double potential_energy() const;  // gravity only; 0 when gravity is off
  double energy() const { return kinetic_energy() + potential_energy(); }
  // The solve at the start of the last step (nu, joint torques, ...).
  const Data& data() const { return data_; }
  const Model& model() const { return model_; }
  const SimulatorOptions& options() const { return options_; }
  SimulatorOptions& options() { return options_; }
  // Joints that were at or past a limit in the last step (LimitPolicy Report/Clamp).
  const std::vector<int>& limit_hits() const { return limit_hits_; }

 private:
  Model model_;
  SimulatorOptions options_;
  Data data_;
  Case case_;
  std::array<DirectionMode, kNumDirections> mode_{};
  std::array<double, kNumDirections> setpoint_{}, target_{}, angle_{};
  std::vector<int> limit_hits_;
  // Workspace for the integrators (sized once).
  Eigen::VectorXd k_q_[4], k_qd_[4], q0_, qd0_;
};

}  // namespace achd
