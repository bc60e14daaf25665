// Badly scaled and large chains: mass and inertia ratios from 1e-6 to 1e6 along the
// chain, millimetre links, 200 and 1000 links, joint velocities of 100 rad/s. The
// physics identities must hold to bounds that follow from the conditioning:
//   RNEA(q, qd, qdd) == joint_torques:  |r| <= c n eps (|M| |qdd| + |tau| + |h|)
//     (a backward-error bound: the sweeps sum n terms of those sizes, h = RNEA(q, qd, 0);
//     the forward error of qdd may grow with cond(M), printed, up to 7e12 here, but the
//     residual does not: the articulated-body factorisation is backward stable in these
//     cases, and a bound scaled with cond(M) would be vacuous, 1e15 N m);
//   alpha^T a_tip == beta:              |r| <= c n eps cond(K) |rhs|
//     (K nu = rhs solved with K and rhs from O(n) sweeps, |nu| <= |rhs| / sigma_min).
// c = 10 covers the constant factors of the spatial products (6x6, a few terms each).
// The measured residuals and bounds are printed.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>

#include "achd/achd.hpp"
#include "hard_chain_urdf.hpp"
#include "reference_dynamics.hpp"

namespace achd::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// n links of length length(i) and mass mass(i); axes cycle z, y, x and each joint
// frame is twisted by 0.3 rad so that no two consecutive axes are parallel. The tip is
// a massless frame 0.5 link lengths beyond the last joint.
template <typename Length, typename Mass>
std::string scaled_chain(int n, Length length, Mass mass) {
  std::vector<LinkSpec> links(n + 1);
  const Eigen::Vector3d axes[3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  for (int i = 0; i < n; ++i) {
    LinkSpec& l = links[i];
    const double len = length(i), m = mass(i);
    l.axis = axes[i % 3];
    l.joint_xyz = {i == 0 ? 0.0 : length(i - 1), 0, 0};
    l.joint_rpy = {0.3, 0, 0};
    l.mass = m;
    l.com = {len / 2, 0.1 * len, 0};
    // a rod of radius len/10: I_axial = m r^2 / 2, I_transverse = m (3 r^2 + len^2) / 12
    const double r = len / 10, t = m * (3 * r * r + len * len) / 12;
    l.inertia_diag = {m * r * r / 2, t, t};
  }
  links[n].joint_type = "fixed";
  links[n].joint_xyz = {0.5 * length(n - 1), 0, 0};
  links[n].has_inertial = false;
  links[n].name = "tip";
  return chain_urdf(links);
}

struct Report {
  double rnea_residual, rnea_bound, constraint_residual, constraint_bound, cond_M, cond_K;
};

// Solves with the tip's linear x, y, z accelerations constrained (beta = 0.5, -0.3,
// 0.2) and checks both identities against their bounds.
Report check(const std::string& name, const Model& model, const Eigen::VectorXd& q,
             const Eigen::VectorXd& qd) {
  const int n = model.num_rates();
  Case c = Case::zeros(model);
  c.q = q;
  c.qd = qd;
  c.alpha.setZero(6, 3);
  c.alpha.topRows<3>().setIdentity();
  c.beta.resize(3);
  c.beta << 0.5, -0.3, 0.2;
  Data d(model);
  hybrid_dynamics(model, d, c);
  EXPECT_TRUE(d.qdd.allFinite() && d.nu.allFinite() && d.joint_torques.allFinite()) << name;

  const Eigen::MatrixXd M = reference_crba(model, q);
  const Eigen::VectorXd h = reference_rnea(model, q, qd, Eigen::VectorXd::Zero(n), c.gravity);
  const Eigen::VectorXd m_eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(
                                    M, Eigen::EigenvaluesOnly).eigenvalues();
  const Eigen::VectorXd k_eig = Eigen::SelfAdjointEigenSolver<CouplingMatrix>(
                                    d.K, Eigen::EigenvaluesOnly).eigenvalues();
  Report r;
  r.cond_M = m_eig.maxCoeff() / m_eig.minCoeff();
  r.cond_K = k_eig.maxCoeff() / k_eig.minCoeff();
  const double c_n_eps = 10 * n * kEps;
  const double M_norm = m_eig.maxCoeff(), qdd_norm = d.qdd.norm();
  r.rnea_residual = (reference_rnea(model, q, qd, d.qdd, c.gravity) - d.joint_torques).norm();
  r.rnea_bound = c_n_eps * (M_norm * qdd_norm + d.joint_torques.norm() + h.norm());
  r.constraint_residual = (c.alpha.transpose() * d.link_accelerations.back() - c.beta).norm();
  r.constraint_bound = c_n_eps * r.cond_K * d.workspace.rhs.norm();
  EXPECT_EQ(d.rank, 3) << name;
  EXPECT_LE(r.rnea_residual, r.rnea_bound) << name;
  EXPECT_LE(r.constraint_residual, r.constraint_bound) << name;
  std::printf("%-28s n=%4d cond(M)=%.1e cond(K)=%.1e |RNEA-tau|=%.1e (bound %.1e) "
              "|alpha^T a-beta|=%.1e (bound %.1e)\n",
              name.c_str(), n, r.cond_M, r.cond_K, r.rnea_residual, r.rnea_bound,
              r.constraint_residual, r.constraint_bound);
  return r;
}

Eigen::VectorXd wavy(int n, double amplitude) {
  Eigen::VectorXd q(n);
  for (int i = 0; i < n; ++i) q[i] = amplitude * std::sin(1.7 * i + 0.4);
  return q;
}

// Masses from 1e-6 kg at the root to 1e6 kg at the tip (a factor 10 per link), and the
// reverse; the inertias follow the masses, so the inertia ratio is 1e12 too.
TEST(HardConditioning, MassAndInertiaRatiosOf1e12AlongTheChain) {
  const int n = 13;
  const auto length = [](int) { return 0.3; };
  const Model up = load_urdf_string(
      scaled_chain(n, length, [](int i) { return std::pow(10.0, -6 + i); }), "link0", "tip");
  const Model down = load_urdf_string(
      scaled_chain(n, length, [](int i) { return std::pow(10.0, 6 - i); }), "link0", "tip");
  check("light root, heavy tip", up, wavy(n, 0.8), wavy(n, 0.5));
  check("heavy root, light tip", down, wavy(n, 0.8), wavy(n, 0.5));
}

// Millimetre and tenth-of-a-millimetre links with gram masses: D and K are tiny (down
// to 1e-14), the relative thresholds and bounds must still hold.
TEST(HardConditioning, VerySmallLinks) {
  const int n = 7;
  const Model mm = load_urdf_string(
      scaled_chain(n, [](int) { return 1e-3; }, [](int) { return 1e-3; }), "link0", "tip");
  const Model tenth = load_urdf_string(
      scaled_chain(n, [](int) { return 1e-4; }, [](int) { return 1e-5; }), "link0", "tip");
  check("1 mm links, 1 g", mm, wavy(n, 0.8), wavy(n, 0.5));
  check("0.1 mm links, 10 mg", tenth, wavy(n, 0.8), wavy(n, 0.5));
}

// 100 rad/s on every joint: velocity products of 1e4 rad^2/s^2 per link dominate
// gravity; the identities still hold relative to those torques.
TEST(HardConditioning, JointVelocitiesOf100RadPerSecond) {
  const int n = 7;
  const Model m = load_urdf_string(
      scaled_chain(n, [](int) { return 0.3; }, [](int i) { return 3.0 - 0.3 * i; }), "link0", "tip");
  check("qd = 100 rad/s", m, wavy(n, 0.8), Eigen::VectorXd::Constant(n, 100.0));
  check("qd = +-100 rad/s", m, wavy(n, 0.8), 100.0 * wavy(n, 1.0).cwiseSign());
}

// Long chains: 200 and 1000 links of 5 cm, masses varying by 10x along the chain.
TEST(HardConditioning, TwoHundredAndOneThousandLinkChains) {
  for (int n : {200, 1000}) {
    const Model m = load_urdf_string(
        scaled_chain(n, [](int) { return 0.05; },
                     [n](int i) { return 0.1 + 0.9 * (n - i) / n; }),
        "link0", "tip");
    ASSERT_EQ(m.num_rates(), n);
    check(std::to_string(n) + " links", m, wavy(n, 0.2), wavy(n, 1.0));
  }
}

}  // namespace
}  // namespace achd::test
