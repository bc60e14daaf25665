// Columns that give way to the joints' efforts (ConstraintBlock::yields): the UR5 (its
// URDF's effort limits, 150 and 28 N m) with its tip's z column marked yielding and rx
// held, at its default pose and at poses near its stretched elbow, under variable_damping
// as the simulator runs it with a push (exact_within_efforts off), beta_z swept so that
// the torques the followed solve takes, r = max |tau_i| / effort_i, fall below 1, between
// 1 and 2, and above 2. Each yielding solve is checked against two independent solves of
// the same case: the one following z (yields 0) and the one without the z column at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "achd/achd.hpp"

namespace achd::test {
namespace {

const std::string kRepo = ACHD_SOURCE_DIR;

struct Ur5 {
  Model model = load_urdf_file(kRepo + "/robots/ur5.urdf", "base_link", "wrist_3_link");
  int tip = model.link_index("wrist_3_link");
};

// A block on the tip with z (pushed at beta_z) then rx (held), or rx alone.
Case tip_case(const Model& m, int tip, const Eigen::VectorXd& q, double beta_z, bool with_z, std::uint8_t yields) {
  Case c = Case::zeros(m);
  c.q = q;
  c.qd = Eigen::VectorXd::LinSpaced(m.num_rates(), 0.4, -0.3);
  ConstraintBlock& b = c.constraints.emplace_back();
  b.link = tip;
  const int n = with_z ? 2 : 1;
  b.alpha = ConstraintMatrix::Zero(6, n);
  b.beta = ConstraintVector::Zero(n);
  if (with_z) {
    b.alpha(2, 0) = 1;
    b.beta[0] = beta_z;
  }
  b.alpha(3, n - 1) = 1;
  b.yields = yields;
  return c;
}

// variable_damping as the simulator runs it with a push (exact_within_efforts off).
Options pushing() {
  Options o;
  o.policy = SingularityPolicy::VariableDamping;
  o.exact_within_efforts = false;
  return o;
}

// The UR5 with its elbow bent, away from the stretched pose.
Eigen::VectorXd bent_pose() {
  Eigen::VectorXd q(6);
  q << 0.2, -1.0, 1.2, -1.5, -1.4, 0.3;
  return q;
}

// r of a solve (ff_torques 0: its joint_torques are the constraint forces' alone)
double effort_ratio(const Model& m, const Data& d) {
  double r = 0;
  for (int i = 0; i < m.num_rates(); ++i) r = std::max(r, std::abs(d.joint_torques[i]) / m.bodies[i].limits.effort);
  return r;
}

TEST(YieldToEfforts, FollowsWithinTheEffortsAndGivesWayBeyondThem) {
  const Ur5 u;
  const Model& m = u.model;
  Eigen::VectorXd q(6);
  const Options vd = pushing();
  int below = 0, between = 0, beyond = 0;
  for (const double elbow : {1.2, 0.3, 0.05}) {
    q << 0.2, -1.0, elbow, -1.5, -1.4, 0.3;
    for (double beta_z = 0.05; beta_z < 1e5; beta_z *= 1.7) {
      SCOPED_TRACE("elbow " + std::to_string(elbow) + ", beta_z " + std::to_string(beta_z));
      Data followed(m), without(m), yielding(m), truncated(m);
      hybrid_dynamics(m, followed, tip_case(m, u.tip, q, beta_z, true, 0), vd);
      hybrid_dynamics(m, without, tip_case(m, u.tip, q, beta_z, false, 0), vd);
      hybrid_dynamics(m, yielding, tip_case(m, u.tip, q, beta_z, true, 1), vd);
      // truncate solves every column as asked
      hybrid_dynamics(m, truncated, tip_case(m, u.tip, q, beta_z, true, 1), {});
      EXPECT_EQ(truncated.yielded, 0);
      const double r = effort_ratio(m, followed);
      EXPECT_NEAR(yielding.effort_ratio, r, 1e-12 * r);
      ASSERT_TRUE(yielding.qdd.allFinite() && yielding.nu.allFinite());
      if (r <= 1) {  // followed: the same solve to the bit
        ++below;
        EXPECT_EQ(yielding.yielded, 0);
        EXPECT_EQ(yielding.qdd, followed.qdd);
        EXPECT_EQ(yielding.nu, followed.nu);
        continue;
      }
      const double x = std::min(r - 1, 1.0), s = x * x * (3 - 2 * x);
      (r < 2 ? between : beyond) += 1;
      EXPECT_NEAR(yielding.yielded, s, 1e-12);
      // nu = nu_followed + s (nu_without - nu_followed), nu_without's z being 0
      const double scale = std::max(std::abs(followed.nu[0]), std::abs(followed.nu[1]));
      EXPECT_NEAR(yielding.nu[0], (1 - s) * followed.nu[0], 1e-10 * scale);
      EXPECT_NEAR(yielding.nu[1], followed.nu[1] + s * (without.nu[0] - followed.nu[1]), 1e-10 * scale);
      if (r >= 2) {  // given up: the solve without the z column
        EXPECT_EQ(yielding.nu[0], 0);
        for (int i = 0; i < m.num_rates(); ++i)
          EXPECT_NEAR(yielding.qdd[i], without.qdd[i], 1e-9 * (1 + without.qdd.cwiseAbs().maxCoeff())) << i;
      }
    }
  }
  // every regime was met
  EXPECT_GT(below, 0);
  EXPECT_GT(between, 0);
  EXPECT_GT(beyond, 0);
}

// On a robot with coupled joints (the Panda arm with its <mimic> fingers), whose solve
// superposes several, nothing yields: the marked column is followed as asked, to the bit,
// even where its torques are far past the efforts.
TEST(YieldToEfforts, NothingYieldsOnARobotWithCoupledJoints) {
  const Model m = load_urdf_file(kRepo + "/robots/panda_fingers.urdf", "", "");
  ASSERT_FALSE(m.couplings.empty());
  Case c = Case::zeros(m);
  ASSERT_EQ(m.num_positions(), 9);
  c.q << 0.1, -0.785, 0.1, -2.356, 0.1, 1.571, 0.785, 0.02, 0.02;  // its robots/index.json pose
  ConstraintBlock& b = c.constraints.emplace_back();
  b.link = m.link_index("panda_hand");
  b.alpha = ConstraintMatrix::Zero(6, 1);
  b.alpha(2, 0) = 1;
  b.beta = ConstraintVector::Constant(1, 1e4);  // 10^4 m/s^2: far past any effort
  const Options vd = pushing();
  Data followed(m), marked(m);
  hybrid_dynamics(m, followed, c, vd);
  b.yields = 1;
  hybrid_dynamics(m, marked, c, vd);
  EXPECT_GT(effort_ratio(m, followed), 2);
  EXPECT_EQ(marked.yielded, 0);
  EXPECT_EQ(marked.qdd, followed.qdd);
  EXPECT_EQ(marked.nu, followed.nu);
}

// Hostile effort limits: denormal ones (any torque exceeds them, the ratio overflows)
// give the push up wholly with a finite ratio; 1e308 ones never give it up.
TEST(YieldToEfforts, DenormalAndHugeEffortLimits) {
  const Options vd = pushing();
  const Eigen::VectorXd q = bent_pose();
  for (const double effort : {5e-324, 1e-310, 1e308}) {
    Ur5 u;
    for (Body& b : u.model.bodies) b.limits.effort = effort;
    Data d(u.model);
    hybrid_dynamics(u.model, d, tip_case(u.model, u.tip, q, 0.45, true, 1), vd);
    EXPECT_TRUE(std::isfinite(d.effort_ratio)) << effort;
    EXPECT_TRUE(d.nu.allFinite() && d.qdd.allFinite()) << effort;
    EXPECT_EQ(d.yielded, effort < 1 ? 1.0 : 0.0) << effort;
  }
}

// A push whose followed solve leaves a double's range (beta_z = +-1e308: nu and the
// torques overflow to inf and NaN) is given up wholly: the result is the solve without z,
// finite, with the largest double as its ratio.
TEST(YieldToEfforts, APushBeyondTheRangeOfADoubleIsGivenUp) {
  const Options vd = pushing();
  const Eigen::VectorXd q = bent_pose();
  const Ur5 u;
  Data without(u.model);
  hybrid_dynamics(u.model, without, tip_case(u.model, u.tip, q, 0, false, 0), vd);
  for (const double beta_z : {1e308, -1e308}) {
    Data d(u.model);
    hybrid_dynamics(u.model, d, tip_case(u.model, u.tip, q, beta_z, true, 1), vd);  // throws if not finite
    EXPECT_EQ(d.yielded, 1.0) << beta_z;
    EXPECT_EQ(d.effort_ratio, std::numeric_limits<double>::max()) << beta_z;
    EXPECT_EQ(d.nu[0], 0.0) << beta_z;
    EXPECT_TRUE(d.qdd.allFinite() && d.joint_torques.allFinite()) << beta_z;
    for (int i = 0; i < 6; ++i)
      EXPECT_NEAR(d.qdd[i], without.qdd[i], 1e-9 * (1 + without.qdd.cwiseAbs().maxCoeff())) << i;
  }
}

// A bit naming a column the block does not have is refused with the field's name.
TEST(YieldToEfforts, RefusesABitBeyondTheBlocksColumns) {
  const Ur5 u;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  Data d(u.model);
  try {
    hybrid_dynamics(u.model, d, tip_case(u.model, u.tip, q, 1.0, true, 1u << 2), {});
    FAIL() << "a yields bit beyond the block's two columns was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("constraints[0].yields: bit 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace achd::test
