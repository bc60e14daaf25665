// Events of loop joints: the two-link planar arm (robots/planar2.urdf, 1 m links) with its
// tip pinned by a spherical loop joint to a point of the base 2.2 m away, beyond its 2 m
// reach. The loop cannot close: the stabilisation pulls the arm straight towards the point,
// and at the stretched pose the loop's directions are lost. The simulator runs on, each
// lost direction is an event naming the loop (not a link), with the acceleration the solve
// left undelivered, and loop_released_seconds() says how long it was not followed. A loop
// the arm can close (the point at 1.5 m), started closed, has no event and stays closed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "achd/achd.hpp"
#include "achd/names.hpp"
#include "achd/simulator.hpp"

namespace {

achd::Model pinned_arm(double distance, const achd::Vector3& axis = achd::Vector3(0, 0, -1)) {
  achd::LoopJointSpec pin;
  pin.name = "pin";
  pin.link_a = "link2";
  pin.origin_a.p = achd::Vector3(1, 0, 0);  // the tip: link2's frame sits on the elbow
  pin.link_b = "base_link";
  pin.origin_b.p = distance * axis;
  pin.type = achd::LoopType::Spherical;
  achd::UrdfOptions o;
  o.loops = {pin};
  return achd::load_urdf_file(std::string(ACHD_SOURCE_DIR) + "/robots/planar2.urdf", "", "", o);
}

// A bent pose with the tip away from the pin: the stabilisation pulls it there (within
// reach it closes the loop in about 0.2 s).
Eigen::VectorXd start() { return Eigen::Vector2d(0.3, -0.6); }

}  // namespace

TEST(LoopEvents, ALoopBeyondReachIsReleasedWithAnEventNamingTheLoop) {
  const achd::Model m = pinned_arm(2.2);
  ASSERT_EQ(m.loops.size(), 1u);
  achd::Simulator sim(m);
  sim.reset(start(), Eigen::Vector2d::Zero());
  ASSERT_NO_THROW(sim.run(5000, 1e-3));
  EXPECT_EQ(sim.t, 5.0);
  ASSERT_TRUE(sim.q.allFinite() && sim.qd.allFinite());
  bool released = false;
  for (const achd::DirectionEvent& e : sim.events()) {
    EXPECT_EQ(e.link, -1);
    EXPECT_EQ(e.loop, 0);
    EXPECT_TRUE(m.loops[0].directions >> e.direction & 1u) << achd::direction_name(e.direction);
    if (e.kind == achd::DirectionEventKind::Released) {
      released = true;
      // far more than the w^2 1e-9 = 1e-5 m/s^2 of a followed direction
      EXPECT_GT(e.unmet, 1.0);
    }
    std::printf("  t = %.3f s: loop direction %s %s, sigma_min %.3g, unmet %.3g\n", e.t,
                achd::direction_name(e.direction), achd::kDirectionEventKindNames[static_cast<int>(e.kind)],
                e.sigma_min, e.unmet);
  }
  EXPECT_TRUE(released);
  const auto seconds = sim.loop_released_seconds(0);
  double total = 0;
  for (int k = 0; k < achd::kNumDirections; ++k) {
    EXPECT_GE(seconds[k], 0);
    EXPECT_LE(seconds[k], 5.0);
    if (!(m.loops[0].directions >> k & 1u)) EXPECT_EQ(seconds[k], 0);
    total += seconds[k];
  }
  EXPECT_GT(total, 1.0);
  // the tip ends as near the pin as the arm reaches: 0.2 m short
  EXPECT_NEAR(sim.loop_error(0), 0.2, 1e-3);
  EXPECT_THROW(sim.loop_released_seconds(1), achd::Error);
}

// loop_drift counts the closure error only while the loop is enforced: the largest
// loop_error at the start of the steps (and now) when none of its directions was released,
// the released ones told by the events so far.
// The pin 2.05 m out along x, the arm started stretched towards it (error 0.05 m): the loop
// is released, and the arm, no longer held up, falls away from the pin under gravity.
TEST(LoopEvents, TheDriftLeavesOutTheTimeTheLoopWasReleased) {
  const achd::Model m = pinned_arm(2.05, achd::Vector3(1, 0, 0));
  achd::Simulator sim(m);
  sim.reset(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());  // along x
  bool released[achd::kNumDirections] = {false};
  double enforced = 0, largest = 0;
  std::size_t seen = 0;
  for (int k = 0; k < 5000; ++k) {
    bool any = false;
    for (bool r : released) any = any || r;
    if (!any) enforced = std::max(enforced, sim.loop_error(0));
    largest = std::max(largest, sim.loop_error(0));
    sim.step(1e-3);
    for (; seen < sim.events().size(); ++seen) {
      const achd::DirectionEvent& e = sim.events()[seen];
      released[e.direction] = e.kind == achd::DirectionEventKind::Released ||
                              (released[e.direction] && e.kind != achd::DirectionEventKind::Resumed);
    }
  }
  bool any = false;
  for (bool r : released) any = any || r;
  ASSERT_TRUE(any);  // released at the end: the error now does not count
  EXPECT_EQ(sim.loop_drift(0), enforced);
  EXPECT_GT(largest, enforced);  // while released the arm fell further from the pin
}

TEST(LoopEvents, ALoopWithinReachHasNoEvent) {
  const double d = 1.5;
  const achd::Model m = pinned_arm(d);
  achd::Simulator sim(m);
  // closed: the elbow bent so the tip is d from the shoulder (2 cos(q2 / 2) = d), the arm
  // turned to point it straight down
  const double q2 = 2 * std::acos(d / 2);
  sim.reset(Eigen::Vector2d(M_PI / 2 - q2 / 2, q2), Eigen::Vector2d::Zero());
  ASSERT_LT(sim.loop_error(0), 1e-12);
  ASSERT_NO_THROW(sim.run(5000, 1e-3));
  EXPECT_TRUE(sim.events().empty());
  EXPECT_LT(sim.loop_error(0), 1e-9);
  for (double s : sim.loop_released_seconds(0)) EXPECT_EQ(s, 0);
}
