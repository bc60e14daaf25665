// The variable_damping policy on its own (solver level): bounded where truncate's
// constraint forces grow without bound, the exact solve where nothing is near singular,
// and near a singularity where the joints' efforts allow the exact solve.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>

#include "achd/achd.hpp"
#include "coupling_solve.hpp"

#include "hard_stretched_arm.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

Options policy(SingularityPolicy p) {
  Options o;
  o.policy = p;
  return o;
}

double largest_eigenvalue(const CouplingMatrix& K) {
  return Eigen::SelfAdjointEigenSolver<CouplingMatrix>(K, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}

// The stretched arm (hard_stretched_arm.hpp) pushed radially (x) while z is held: both
// columns are positions, so K is scaled by one number and the gain of every direction is
// at most 1 / eps = 1 / (singular_region sigma_max): |nu| <= |rhs| / (singular_region
// sigma_max) at every theta, while truncate's nu grows like 1/theta^2 until its
// tolerance (1e-12 sigma_max) drops the direction near theta = 1e-6.
TEST(VariableDamping, ConstraintForcesStayBoundedWhereTruncatesGrow) {
  const Model model = stretched_arm();
  const Options vd = policy(SingularityPolicy::VariableDamping), tr = policy(SingularityPolicy::Truncate);
  for (double theta : sweep_angles()) {
    const Case c = stretched_arm_case(model, theta);
    Data d(model);
    hybrid_dynamics(model, d, c, vd);
    ASSERT_TRUE(d.nu.allFinite() && d.qdd.allFinite()) << theta;
    const double bound = d.workspace.rhs.norm() / (vd.singular_region * largest_eigenvalue(d.K));
    EXPECT_LE(d.nu.norm(), bound * (1 + 1e-12)) << "theta " << theta;
    if (theta <= 1e-3) {
      EXPECT_GE(d.damped.cols(), 1) << theta;  // the radial direction is in the region
      Data t(model);
      hybrid_dynamics(model, t, c, tr);
      if (theta == 1e-4) EXPECT_GT(t.nu.norm(), 100 * bound) << "truncate's nu at theta 1e-4";
    }
  }
}

// Away from the region variable_damping is truncate's exact solve: every robot of
// robots/index.json at its q0 holding z and rx, and x y z, with nonzero velocities
// (where the robot can move in every held direction: not the planar arm): nu and qdd
// agree to 1e-15 (relative), and no direction is reported damped.
TEST(VariableDamping, EqualsTruncateAwayFromTheRegion) {
  for (const IndexedRobot& r : load_robot_index(ACHD_SOURCE_DIR)) {
    const Model& m = r.model;
    for (const std::vector<int>& held : {std::vector<int>{2, 3}, std::vector<int>{0, 1, 2}}) {
      Case c = Case::zeros(m);
      c.q = r.q0;
      c.qd = Eigen::VectorXd::Constant(m.num_rates(), 0.3);
      c.alpha.setZero(6, static_cast<int>(held.size()));
      c.beta.resize(static_cast<int>(held.size()));
      for (std::size_t j = 0; j < held.size(); ++j) {
        c.alpha(held[j], static_cast<int>(j)) = 1;
        c.beta[static_cast<int>(j)] = 0.1 * (j + 1);
      }
      Data a(m), b(m);
      hybrid_dynamics(m, a, c, policy(SingularityPolicy::Truncate));
      hybrid_dynamics(m, b, c, policy(SingularityPolicy::VariableDamping));
      if (a.rank < static_cast<int>(held.size())) continue;  // a held direction the robot cannot move in
      EXPECT_EQ(b.damped.cols(), 0) << r.name;
      EXPECT_LE((a.nu - b.nu).norm(), 1e-15 * a.nu.norm()) << r.name << " nu " << a.nu.transpose() << " / "
                                                            << b.nu.transpose();
      EXPECT_LE((a.qdd - b.qdd).norm(), 1e-15 * a.qdd.norm()) << r.name;
    }
  }
}

// Next to a singularity but not at it, the exact solve is kept where the joints' efforts
// allow it. The LWR at rest holding its tip in 6D beside its stretched pose has an
// eigenvalue of K (scaled by kind) in the singular region, 5.3e-3 of the largest, but
// holding it needs a few N m of its joints, far below their URDF efforts: variable_damping
// gives truncate's exact solve and damps nothing. With no effort limits (0: not given) the
// same case is damped; with every effort set so that the exact solve needs r = 3/4 of it,
// the solve lies halfway (s = 1/2) between the exact and the damped one; from r = 1 it is
// the damped one.
TEST(VariableDamping, KeepsTheExactSolveWhereTheJointEffortsAllowIt) {
  const Model lwr = load_urdf_file(ACHD_SOURCE_DIR "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  Case c = Case::zeros(lwr);
  c.q << 0.3, 0.15, -0.2, -0.15, 0.4, 0.1, 0.1;
  c.alpha = ConstraintMatrix::Identity(6, 6);
  c.beta = ConstraintVector::Zero(6);
  const Options vd = policy(SingularityPolicy::VariableDamping);
  auto with_efforts = [&](double effort) {
    Model m = lwr;
    for (Body& b : m.bodies) b.limits.effort = effort;
    return m;
  };
  Data exact(lwr), kept(lwr), damped(lwr);
  hybrid_dynamics(lwr, exact, c, policy(SingularityPolicy::Truncate));
  hybrid_dynamics(lwr, kept, c, vd);
  const Model unbounded = with_efforts(0);
  hybrid_dynamics(unbounded, damped, c, vd);
  ASSERT_GE(damped.damped.cols(), 1) << "the case is meant to be in the singular region";
  EXPECT_GT((damped.nu - exact.nu).norm(), 1e-3 * exact.nu.norm());
  EXPECT_EQ(kept.damped.cols(), 0);
  EXPECT_EQ(kept.rank, 6);
  EXPECT_LE((kept.nu - exact.nu).norm(), 1e-12 * exact.nu.norm()) << kept.nu.transpose() << " / " << exact.nu.transpose();
  EXPECT_LE((kept.qdd - exact.qdd).norm(), 1e-9);
  // ff = 0: the exact solve's joint torques are those its constraint forces take.
  const double largest = exact.joint_torques.cwiseAbs().maxCoeff();
  for (int i = 0; i < lwr.num_rates(); ++i) EXPECT_LT(std::abs(exact.joint_torques[i]), lwr.bodies[i].limits.effort / 2);
  const Model halfway = with_efforts(largest / 0.75), beyond = with_efforts(largest / 1.5);
  Data h(halfway), b(beyond);
  hybrid_dynamics(halfway, h, c, vd);
  hybrid_dynamics(beyond, b, c, vd);
  EXPECT_LE((h.nu - (exact.nu + damped.nu) / 2).norm(), 1e-9 * exact.nu.norm());
  EXPECT_GE(h.damped.cols(), 1);
  EXPECT_EQ((b.nu - damped.nu).norm(), 0.0);
}

// The singular region's edge, at the solve of K itself (solve_coupling): K = V diag(sigma)
// V^T of 6 and 12 position columns (one kind: the scaling keeps the eigenvalue ratios),
// sigma_max = 1, the others spread over [0.05, 1], the smallest at ratio * singular_region.
// Just inside the region (ratio 1 - 1e-6) exactly one direction is damped: the
// eigen-decomposition-free proof that K is outside the region must fail there. Just
// outside it and beyond (1 + 1e-6, 1.5, 3, 10: where a region taken at trace(K) >= sigma_max
// needs the eigen-decomposition) nothing is damped and nu = K^-1 rhs to round-off.
TEST(VariableDamping, SingularRegionEdgeAtTheCouplingSolve) {
  const Model m = load_urdf_file(std::string(ACHD_SOURCE_DIR) + "/robots/kuka_lwr4.urdf", "lwr_base_link", "lwr_link_7");
  Data d(m);
  Options o = policy(SingularityPolicy::VariableDamping);
  o.exact_within_efforts = false;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1), spread(0.05, 1);
  for (int n : {6, 12}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::MatrixXd V = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return U(rng); }).householderQr().householderQ();
      for (double ratio : {1 - 1e-6, 1 + 1e-6, 1.5, 3.0, 10.0}) {
        Eigen::VectorXd sigma = Eigen::VectorXd::NullaryExpr(n, [&] { return spread(rng); });
        sigma[0] = 1;
        sigma[n - 1] = ratio * o.singular_region;
        const Eigen::MatrixXd K = V * sigma.asDiagonal() * V.transpose();
        d.K = (K + K.transpose()) / 2;
        d.workspace.rhs = ConstraintVector::NullaryExpr(n, [&] { return U(rng); });
        for (int i = 0; i < n; ++i) d.workspace.has_force[i] = true;
        const Eigen::VectorXd exact = Eigen::MatrixXd(d.K).llt().solve(Eigen::VectorXd(d.workspace.rhs));
        solve_coupling(d, o);
        if (ratio < 1) {
          EXPECT_EQ(d.damped.cols(), 1) << "n " << n << " trial " << trial;
          continue;
        }
        EXPECT_EQ(d.damped.cols(), 0) << "n " << n << " trial " << trial << " ratio " << ratio;
        EXPECT_EQ(d.rank, n);
        EXPECT_LE((Eigen::VectorXd(d.nu) - exact).norm(), 1e-11 * exact.norm()) << "n " << n << " ratio " << ratio;
      }
    }
  }
}

// variable_damping alone, without the exact solve the joints' efforts could keep.
Options variable_damping_alone() {
  Options o;
  o.policy = SingularityPolicy::VariableDamping;
  o.exact_within_efforts = false;
  return o;
}

// A 6 x 6 coupling V diag(sigma) V^T along random orthonormal directions V, its largest
// eigenvalue 1, the others drawn from [0.05, 1] but for the last lowest.size(), which are
// `lowest` in order; symmetric to the bit.
CouplingMatrix random_coupling(std::mt19937& rng, const std::vector<double>& lowest) {
  std::uniform_real_distribution<double> U(-1, 1), spread(0.05, 1);
  const int n = 6;
  const Eigen::MatrixXd V = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return U(rng); }).householderQr().householderQ();
  Eigen::VectorXd sigma = Eigen::VectorXd::NullaryExpr(n, [&] { return spread(rng); });
  sigma[0] = 1;
  for (std::size_t i = 0; i < lowest.size(); ++i) sigma[n - static_cast<int>(lowest.size() - i)] = lowest[i];
  const Eigen::MatrixXd K = V * sigma.asDiagonal() * V.transpose();
  return (K + K.transpose()) / 2;
}

// The columns that give way (Options::gives_way): a solve with one direction in the
// singular region reports the column its damped eigen-direction points to
// (Data::workspace.gave_way, one bit), and the same solve told those columns gives the
// same nu to the bit; told another column, that one gives way, and every result is finite.
TEST(VariableDamping, TheColumnsThatGiveWayCanBeFixed) {
  Data d(Model{});
  Options o = variable_damping_alone();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  int decided = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 6;
    d.K = random_coupling(rng, {0.3 * o.singular_region});
    const CouplingMatrix K0 = d.K;
    const ConstraintVector rhs = ConstraintVector::NullaryExpr(n, [&] { return U(rng); });
    for (int i = 0; i < n; ++i) d.workspace.has_force[i] = true;
    d.workspace.rhs = rhs;
    o.gives_way = 0;
    solve_coupling(d, o);
    ASSERT_EQ(d.damped.cols(), 1);
    const std::uint64_t gave = d.workspace.gave_way;
    ASSERT_NE(gave, 0u) << "trial " << trial;
    EXPECT_EQ(gave & (gave - 1), 0u) << "one column gives way";
    Eigen::Index column = 0;
    d.damped.col(0).cwiseAbs().maxCoeff(&column);
    EXPECT_EQ(gave, std::uint64_t{1} << column);
    const ConstraintVector nu = d.nu;
    ++decided;
    d.K = K0;
    d.workspace.rhs = rhs;
    o.gives_way = gave;
    solve_coupling(d, o);
    EXPECT_EQ(d.nu, nu) << "trial " << trial;
    EXPECT_EQ(d.workspace.gave_way, gave);
    const std::uint64_t other = std::uint64_t{1} << ((column + 1) % n);
    d.K = K0;
    d.workspace.rhs = rhs;
    o.gives_way = other;
    solve_coupling(d, o);
    EXPECT_EQ(d.workspace.gave_way, other);
    EXPECT_TRUE(d.nu.allFinite());
  }
  EXPECT_EQ(decided, 20);
}

// Two eigenvalues near the region, the lowest in it (0.3 eps) and the next just above it
// (1.5 eps), along random directions: no single column's release leaves the rest clear
// of the region, so more columns give way (the lowest eigen-direction of the rest's
// coupling, until its smallest eigenvalue clears 4 eps) and the rest is solved exactly:
// K nu = rhs in every held column. (With one column given way the solve blended into the
// plain variable damping, which leaves part of the lost motion in every column.) A
// yielding column (a pushed direction) whose component in the damped direction is at
// least kPushShare of the largest gives way in place of the largest, and the held columns
// left are still solved exactly.
TEST(VariableDamping, HeldColumnsAreSolvedExactlyAndAPushGivesWayFirst) {
  Data d(Model{});
  Options o = variable_damping_alone();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  int more_than_one = 0, pushes = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 6;
    const CouplingMatrix K0 = random_coupling(rng, {1.5 * o.singular_region, 0.3 * o.singular_region});
    const ConstraintVector rhs = ConstraintVector::NullaryExpr(n, [&] { return U(rng); });
    for (int i = 0; i < n; ++i) d.workspace.has_force[i] = true;
    const auto solve = [&](std::uint64_t yielding) {
      d.K = K0;
      d.workspace.rhs = rhs;
      d.workspace.yielding = yielding;
      o.gives_way = 0;
      solve_coupling(d, o);
      return d.workspace.gave_way;
    };
    // K nu = rhs in every column that did not give way
    const auto expect_held_exact = [&](std::uint64_t gave) {
      const ConstraintVector r = K0 * d.nu - rhs;
      for (int i = 0; i < n; ++i)
        if (!(gave >> i & 1u))
          EXPECT_LE(std::abs(r[i]), 1e-12 * d.nu.cwiseAbs().maxCoeff()) << "trial " << trial << ": held column " << i;
    };
    const std::uint64_t gave = solve(0);
    ASSERT_EQ(d.damped.cols(), 1) << "trial " << trial;
    expect_held_exact(gave);
    int h[kMaxConstraintColumns], nh = 0;
    for (int i = 0; i < n; ++i)
      if (!(gave >> i & 1u)) h[nh++] = i;
    ASSERT_GT(nh, 0);
    CouplingMatrix Khh(nh, nh);
    for (int i = 0; i < nh; ++i)
      for (int j = 0; j < nh; ++j) Khh(i, j) = K0(h[i], h[j]);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<CouplingMatrix>(Khh).eigenvalues().minCoeff(), 4 * o.singular_region);
    more_than_one += (gave & (gave - 1)) != 0;
    // The damped direction's largest component and the largest of the others.
    Eigen::Index first = 0;
    const Eigen::VectorXd v = d.damped.col(0).cwiseAbs();
    v.maxCoeff(&first);
    Eigen::Index second = first == 0 ? 1 : 0;
    for (int i = 0; i < n; ++i)
      if (i != first && v[i] > v[second]) second = i;
    const std::uint64_t pushed = std::uint64_t{1} << second;
    const std::uint64_t gave_pushed = solve(pushed);
    if (v[second] >= kPushShare * v[first]) {
      ++pushes;
      EXPECT_NE(gave_pushed & pushed, 0u) << "trial " << trial << ": the pushed column gives way";
      expect_held_exact(gave_pushed);
    } else {
      EXPECT_EQ(gave_pushed, gave) << "trial " << trial << ": a push with a small share changes nothing";
    }
  }
  EXPECT_GT(more_than_one, 20);  // the case this test is about
  EXPECT_GT(pushes, 5);
}

}  // namespace
}  // namespace achd::test
