// The solver's qdd is the minimiser of Gauss's function
//   Z(qdd) = 1/2 (qdd - qdd_free)^T M (qdd - qdd_free)  subject to  A qdd = beta - alpha^T b,
// computed densely: M from the reference CRBA, bias h = the reference
// RNEA(q, qd, 0; g, f_ext) (reference_dynamics.hpp), A = alpha^T J and the tip's
// acceleration at qdd = 0, b, from the separate reference kinematics sweep. Its
// stationarity conditions are the KKT system
//   [ M  A^T ] [ qdd ]   [ ff - h             ]
//   [ A  0   ] [ nu  ] = [ beta - alpha^T b   ],
// where nu is the solver's constraint magnitudes (the robot receives -alpha nu, so
// M qdd + h = ff - J^T alpha nu).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cstdio>

#include "random_chain.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"
#include "robot_index.hpp"

namespace achd::test {
namespace {

struct Worst {
  double qdd = 0, nu = 0, sigma = 0, cond = 0;
  int cases = 0;
  void print(const char* what) const {
    std::printf("  %s: %d cases, max rel error qdd vs KKT %.3g, nu vs KKT %.3g, sigma_min vs "
                "dense K %.3g (relative to sigma_max), worst condition number %.3g\n",
                what, cases, qdd, nu, sigma, cond);
  }
};

void check_against_kkt(const Model& m, const Case& c, Worst& w) {
  const int n = m.num_rates(), nc = c.num_constraints();
  const Eigen::MatrixXd M = reference_crba(m, c.q);
  const Eigen::VectorXd h = reference_rnea(m, c.q, c.qd, Eigen::VectorXd::Zero(n), c.gravity, c.f_ext);
  const Eigen::MatrixXd A = c.alpha.transpose() * reference_link_jacobian(m, c.q, m.num_links() - 1);
  const Vector6 b =
      reference_motion(m, c.q, c.qd, Eigen::VectorXd::Zero(n)).back().spatial_acceleration();
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + nc, n + nc);
  kkt.topLeftCorner(n, n) = M;
  kkt.topRightCorner(n, nc) = A.transpose();
  kkt.bottomLeftCorner(nc, n) = A;
  Eigen::VectorXd rhs(n + nc);
  rhs << c.ff_torques - h, c.beta - c.alpha.transpose() * b;
  const Eigen::VectorXd x = kkt.fullPivLu().solve(rhs);

  Data d(m);
  hybrid_dynamics(m, d, c);
  const double e_qdd = rel_error(d.qdd, x.head(n));
  const double e_nu = rel_error(d.nu, x.tail(nc));
  EXPECT_LE(e_qdd, 1e-8) << "nc " << nc;
  EXPECT_LE(e_nu, 1e-8) << "nc " << nc;
  // The coupling matrix at the base is K = A M^-1 A^T: same smallest singular value.
  if (nc) {
    const Eigen::MatrixXd K = A * M.ldlt().solve(A.transpose());
    const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(K).singularValues();
    const double e_sigma = std::abs(sigma_min(d) - s[nc - 1]) / s[0];
    EXPECT_LE(e_sigma, 1e-10) << "nc " << nc;
    EXPECT_EQ(d.rank, nc);
    w.sigma = std::max(w.sigma, e_sigma);
    w.cond = std::max(w.cond, s[0] / s[nc - 1]);
  }
  w.qdd = std::max(w.qdd, e_qdd);
  w.nu = std::max(w.nu, e_nu);
  ++w.cases;
}

TEST(GaussPrinciple, RandomChainsMatchDenseKkt) {
  Worst w;
  for_random_cases(505, 40, true, [&](const RandomChain& ch, const Case& c) {
    SCOPED_TRACE(ch.urdf);
    check_against_kkt(ch.model, c, w);
  });
  w.print("random chains");
}

TEST(GaussPrinciple, IndexRobotsMatchDenseKkt) {
  std::mt19937 rng(515);
  for (const IndexedRobot& r : load_robot_index(ACHD_SOURCE_DIR)) {
    SCOPED_TRACE(r.name);
    Worst w;
    for (int nc = 0; nc <= tip_jacobian_rank(r.model, r.q0); ++nc)
      for (const bool standard_gravity : {true, false})
        if (const std::optional<Case> c = case_at(rng, r.model, r.q0, nc, standard_gravity))
          check_against_kkt(r.model, *c, w);
    w.print(r.name.c_str());
    EXPECT_GT(w.cases, 0);
  }
}

}  // namespace
}  // namespace achd::test
