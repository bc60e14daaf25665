// 1e5 RK4 steps (100 s at dt = 1 ms) of the KUKA LWR 4 released next to its upright,
// fully stretched pose with the tip's height (z) held: at that height the arm must stay
// almost stretched, where vertical tip motion is the direction it loses, so K = sigma
// stays 50..2000 times below its value at a generic pose while the arm topples and
// swings about the vertical (damped policy). No damping or friction: the energy is
// conserved up to the integrator and the Baumgarte correction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "achd/achd.hpp"
#include "achd/simulator.hpp"

namespace achd::test {
namespace {

TEST(HardLongSimulation, KukaPassingNearSingularitiesWithHeldDirectionsStaysBounded) {
  const Model model =
      load_urdf_file(ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  SimulatorOptions o;
  o.integrator = Integrator::RK4;
  o.effects = kAllEffects & ~(kDamping | kFriction);  // conservative: energy is a check
  o.limits = LimitPolicy::Ignore;
  o.solver.policy = SingularityPolicy::Damped;
  Simulator sim(model, o);
  Eigen::VectorXd q0(7);
  q0 << 0.3, 0.02, 0.0, -0.03, 0.0, 0.02, 0.0;
  sim.reset(q0, Eigen::VectorXd::Zero(7));
  sim.set_direction(index_of_direction("z"), DirectionMode::Hold);

  // sigma of K for the same held direction at the index's generic pose
  Case generic = Case::zeros(model);
  generic.q << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  generic.alpha.setZero(6, 1);
  generic.alpha(2, 0) = 1;
  generic.beta.setZero(1);
  Data dg(model);
  hybrid_dynamics(model, dg, generic);
  const double sigma_generic = sigma_min(dg);

  const double dt = 1e-3, E0 = sim.energy();
  // The energy scale: total mass times g times the arm's reach (~1.2 m).
  double mass = 0;
  for (const Body& b : model.bodies) mass += b.inertia(0, 0);
  const double energy_scale = mass * 9.81 * 1.2;
  double max_dE = 0, min_sigma = INFINITY, max_sigma = 0, max_speed = 0;
  for (int step = 0; step < 100000; ++step) {
    sim.step(dt);
    const Data& d = sim.data();
    ASSERT_TRUE(sim.q.allFinite() && sim.qd.allFinite() && d.nu.allFinite()) << "step " << step;
    max_dE = std::max(max_dE, std::abs(sim.energy() - E0));
    min_sigma = std::min(min_sigma, sigma_min(d));
    max_sigma = std::max(max_sigma, sigma_min(d));
    max_speed = std::max(max_speed, sim.qd.cwiseAbs().maxCoeff());
  }
  const auto drift = sim.max_residuals();
  std::printf("energy drift %.3e J (scale %.3e J), held drift z %.3e m, "
              "sigma_min of K in [%.3e, %.3e] (generic pose %.3e), max |qd| %.3e rad/s\n",
              max_dE, energy_scale, drift[2], min_sigma, max_sigma, sigma_generic, max_speed);
  // The whole run is near the singularity, and comes within 1e-3 of it.
  EXPECT_LT(max_sigma, 5e-2 * sigma_generic);
  EXPECT_LT(min_sigma, 1e-3 * sigma_generic);
  EXPECT_LT(max_speed, 5.0);  // the w of the energy bound below
  // Energy: RK4's relative energy error per unit time is ~ (w dt)^4 w for motion of
  // frequency w; with w <= 5 rad/s (max |qd| above), dt = 1e-3 and T = 100 s that is
  // 3e-7 of E, so 1e-6 m g L bounds it with margin for the Baumgarte term (the held
  // drift, below, times |nu| ~ m g).
  EXPECT_LT(max_dE, 1e-6 * energy_scale);
  // Held drift: RK4's local position error (w dt)^5 L ~ 4e-12 m per step, which
  // Baumgarte (w_n = 100 rad/s) keeps from accumulating; 1e-6 m bounds it.
  EXPECT_LT(drift[2], 1e-6);
}

}  // namespace
}  // namespace achd::test
