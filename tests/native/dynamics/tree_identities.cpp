// pv_reference (the plain Popov-Vereshchagin solver on trees) on seeded random trees
// (random_tree.hpp) with 0 to 6 constraint blocks at random points, up to 36 columns, and
// prescribed joints, every effect on (damping, friction, random rotor inertias): the
// physics identities against the test references, which share no code with it
// (reference_dynamics.hpp, reference_kinematics.hpp), and the dense KKT solution of
// Gauss's principle. On chains with tip constraints, pv_reference equals hybrid_dynamics.
// Relative errors as docs/design.md section 4.6.
#include <gtest/gtest.h>

#include <cstdio>

#include <Eigen/LU>

#include "random_chain.hpp"
#include "random_tree.hpp"
#include "tree_cases.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"

namespace achd::test {
namespace {

// Joint accelerations with the prescribed ones given and the rest unknown.
bool is_prescribed(const Case& c, int i) { return c.any_prescribed() && c.prescribed[i]; }

// Gauss's principle, densely: with M (reference CRBA, rotor inertia), h = reference
// RNEA(q, qd, 0) (gravity, f_ext, velocity products, damping, friction) and A the stacked
// alpha_k^T J_k at the points, b the points' accelerations at qdd = 0 without gravity,
//   M qdd + h = tau - A^T nu,   A qdd = beta - alpha^T b,
// tau = ff on the free joints; on the prescribed ones qdd is given and tau is unknown.
// Solved for the free qdd and nu by the KKT system, then the prescribed torques.
struct DenseSolution {
  Eigen::VectorXd qdd, nu, prescribed_torques;
};

DenseSolution dense_kkt(const Model& m, const Case& c, std::uint32_t effects) {
  const int n = m.num_rates(), nc = c.num_constraints();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd M = reference_crba(m, c.q, effects & kRotorInertia);
  const Eigen::VectorXd h = reference_rnea(m, c.q, c.qd, zero, c.gravity, c.f_ext, effects, 0.05);
  const Eigen::MatrixXd A = stacked_constraint_jacobian(m, c);
  const std::vector<FrameMotion> bias = reference_motion(m, c.q, c.qd, zero);
  Eigen::VectorXd constraint_rhs(nc);
  int row = 0;
  auto add = [&](int link, const Vector3& point, const ConstraintMatrix& alpha, const ConstraintVector& beta) {
    const Vector6 b = motion_shift(bias[link].spatial_acceleration(), bias[link].R * point);
    constraint_rhs.segment(row, alpha.cols()) = beta - alpha.transpose() * b;
    row += static_cast<int>(alpha.cols());
  };
  if (c.alpha.cols()) add(m.num_links() - 1, Vector3::Zero(), c.alpha, c.beta);
  for (const ConstraintBlock& b : c.constraints) add(b.link, b.point, b.alpha, b.beta);

  std::vector<int> free;
  Eigen::VectorXd qdd_known = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (is_prescribed(c, i)) qdd_known[i] = c.qdd_given[i];
    else free.push_back(i);
  }
  const int nf = static_cast<int>(free.size());
  const Eigen::VectorXd known_force = M * qdd_known, known_acc = A * qdd_known;
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(nf + nc, nf + nc);
  Eigen::VectorXd rhs(nf + nc);
  for (int a = 0; a < nf; ++a) {
    for (int b = 0; b < nf; ++b) kkt(a, b) = M(free[a], free[b]);
    kkt.block(a, nf, 1, nc) = A.col(free[a]).transpose();
    kkt.block(nf, a, nc, 1) = A.col(free[a]);
    rhs[a] = c.ff_torques[free[a]] - h[free[a]] - known_force[free[a]];
  }
  rhs.tail(nc) = constraint_rhs - known_acc;
  const Eigen::VectorXd x = kkt.fullPivLu().solve(rhs);
  DenseSolution s;
  s.qdd = qdd_known;
  for (int a = 0; a < nf; ++a) s.qdd[free[a]] = x[a];
  s.nu = x.tail(nc);
  const Eigen::VectorXd tau = M * s.qdd + h + A.transpose() * s.nu;  // what each joint needs
  s.prescribed_torques = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i)
    if (is_prescribed(c, i)) s.prescribed_torques[i] = tau[i];
  return s;
}

// Each block's (and the tip's) constraint accelerations alpha^T a_P - beta, a_P the point's
// spatial acceleration from the reference sweep driven by qdd, in the physical convention.
Eigen::VectorXd constraint_residuals(const Model& m, const Case& c, const Eigen::VectorXd& qdd,
                                     Eigen::VectorXd& beta) {
  const std::vector<FrameMotion> motion = reference_motion(m, c.q, c.qd, qdd);
  Eigen::VectorXd lhs(c.num_constraints());
  beta.resize(c.num_constraints());
  int row = 0;
  auto add = [&](int link, const Vector3& point, const ConstraintMatrix& alpha, const ConstraintVector& b) {
    // the reference sweep has no gravity: the physical acceleration of the point
    const Vector6 a = motion_shift(motion[link].spatial_acceleration(), motion[link].R * point);
    lhs.segment(row, alpha.cols()) = alpha.transpose() * a;
    beta.segment(row, alpha.cols()) = b;
    row += static_cast<int>(alpha.cols());
  };
  if (c.alpha.cols()) add(m.num_links() - 1, Vector3::Zero(), c.alpha, c.beta);
  for (const ConstraintBlock& b : c.constraints) add(b.link, b.point, b.alpha, b.beta);
  return lhs;
}

// RNEA(q, qd, qdd) reproduces the applied torques and wrenches: joint_torques, which are
// ff - sum_k J_k^T alpha_k nu_k (link_jacobian at the points; prescribed joints: their
// torques), and which drive the unconstrained tree, free everywhere, to the same qdd.
TEST(PvReferenceTrees, RneaReproducesTheAppliedTorquesAndWrenches) {
  double worst_rnea = 0, worst_jt = 0, worst_free = 0, worst_wrench = 0;
  const Options o = all_effects();
  const int cases = for_tree_cases(1511, [&](const Model& m, const Case& c) {
    const ReferenceSolution s = pv_reference(m, c, o);
    const double e_rnea = rel_error(s.joint_torques,
                                    reference_rnea(m, c.q, c.qd, s.qdd, c.gravity, c.f_ext, o.effects, 0.05));
    Eigen::VectorXd expected = c.ff_torques;
    for (int i = 0; i < m.num_rates(); ++i)
      if (is_prescribed(c, i)) expected[i] = s.prescribed_torques[i];
    int row = 0;
    double e_wrench = 0;
    for (size_t k = 0; k < c.constraints.size(); ++k) {
      const ConstraintBlock& b = c.constraints[k];
      const Eigen::VectorXd nu = s.nu.segment(row, b.alpha.cols());
      expected -= link_jacobian(m, c.q, b.link, b.point).transpose() * (b.alpha * nu);
      e_wrench = std::max(e_wrench, rel_error(s.constraint_wrenches[k], b.alpha * nu));
      row += static_cast<int>(b.alpha.cols());
    }
    const double e_jt = rel_error(s.joint_torques, expected);
    Case free = c;
    free.constraints.clear();
    free.prescribed.clear();
    free.qdd_given.resize(0);
    free.ff_torques = s.joint_torques;
    const double e_free = rel_error(pv_reference(m, free, o).qdd, s.qdd);
    EXPECT_LE(e_rnea, 1e-10);
    EXPECT_LE(e_jt, 1e-10);
    EXPECT_LE(e_free, 1e-10);
    EXPECT_LE(e_wrench, 1e-12);
    EXPECT_EQ(s.constraint_wrenches.size(), c.constraints.size());
    worst_rnea = std::max(worst_rnea, e_rnea);
    worst_jt = std::max(worst_jt, e_jt);
    worst_free = std::max(worst_free, e_free);
    worst_wrench = std::max(worst_wrench, e_wrench);
  });
  std::printf("  %d cases: max rel error joint_torques vs reference RNEA(qdd) %.3g, vs ff - J^T alpha nu "
              "%.3g; qdd(free, joint_torques) vs qdd %.3g; constraint_wrenches vs alpha nu %.3g\n",
              cases, worst_rnea, worst_jt, worst_free, worst_wrench);
  EXPECT_GE(cases, 2 * kTrees);
}

// alpha^T a_P = beta for every block at its point; in the kdl convention, with
// beta_kdl = beta - alpha_lin^T g, the same motion, and link accelerations less [g; 0].
// Every link's acceleration equals the reference sweep's.
TEST(PvReferenceTrees, BlocksMeetBetaAtTheirPointsInBothConventions) {
  double worst_beta = 0, worst_kdl = 0, worst_acc = 0;
  const Options o = all_effects();
  Options kdl = o;
  kdl.convention = Convention::Kdl;
  const int cases = for_tree_cases(1512, [&](const Model& m, const Case& c) {
    const ReferenceSolution s = pv_reference(m, c, o);
    Eigen::VectorXd beta;
    const double e_beta = rel_error(constraint_residuals(m, c, s.qdd, beta), beta);
    Case k = c;
    for (ConstraintBlock& b : k.constraints) b.beta -= b.alpha.topRows<3>().transpose() * c.gravity;
    const ReferenceSolution sk = pv_reference(m, k, kdl);
    const double e_kdl = std::max(rel_error(sk.qdd, s.qdd), rel_error(sk.nu, s.nu));
    const std::vector<FrameMotion> motion = reference_motion(m, c.q, c.qd, s.qdd);
    std::vector<Vector6> expected(1, Vector6::Zero()), expected_kdl, got_kdl;
    for (const FrameMotion& f : motion) expected.push_back(f.spatial_acceleration());
    for (size_t l = 0; l < expected.size(); ++l) {
      expected_kdl.push_back(expected[l]);
      expected_kdl.back().head<3>() -= c.gravity;
    }
    const double e_acc = std::max(rel_error(stack(s.link_accelerations), stack(expected)),
                                  rel_error(stack(sk.link_accelerations), stack(expected_kdl)));
    EXPECT_LE(e_beta, 1e-10);
    EXPECT_LE(e_kdl, 1e-10);
    EXPECT_LE(e_acc, 1e-10);
    worst_beta = std::max(worst_beta, e_beta);
    worst_kdl = std::max(worst_kdl, e_kdl);
    worst_acc = std::max(worst_acc, e_acc);
  });
  std::printf("  %d cases: max rel error alpha^T a_P vs beta %.3g, kdl vs physical %.3g, link "
              "accelerations vs reference sweep %.3g\n", cases, worst_beta, worst_kdl, worst_acc);
  EXPECT_GE(cases, 2 * kTrees);
}

// qdd, nu and the prescribed torques equal the dense KKT solution of Gauss's principle.
TEST(PvReferenceTrees, MatchesTheDenseKktSolution) {
  double worst_qdd = 0, worst_nu = 0, worst_tau = 0;
  int columns = 0;
  const Options o = all_effects();
  const int cases = for_tree_cases(1513, [&](const Model& m, const Case& c) {
    const ReferenceSolution s = pv_reference(m, c, o);
    const DenseSolution d = dense_kkt(m, c, o.effects);
    const double e_qdd = rel_error(s.qdd, d.qdd), e_nu = rel_error(s.nu, d.nu);
    const double e_tau = rel_error(s.prescribed_torques, d.prescribed_torques);
    EXPECT_LE(e_qdd, 1e-8);
    EXPECT_LE(e_nu, 1e-8);
    EXPECT_LE(e_tau, 1e-8);
    EXPECT_EQ(s.rank, c.num_constraints());
    worst_qdd = std::max(worst_qdd, e_qdd);
    worst_nu = std::max(worst_nu, e_nu);
    worst_tau = std::max(worst_tau, e_tau);
    columns = std::max(columns, c.num_constraints());
  });
  std::printf("  %d cases (up to %d columns): max rel error vs KKT qdd %.3g, nu %.3g, prescribed "
              "torques %.3g\n", cases, columns, worst_qdd, worst_nu, worst_tau);
  EXPECT_GE(cases, 2 * kTrees);
}

// On chains with the tip's alpha (random_chain.hpp's cases), pv_reference equals the fast
// path in every output, with every effect and in both conventions, with and without
// prescribed joints.
TEST(PvReferenceChains, EqualsHybridDynamics) {
  double worst = 0;
  int cases = 0;
  std::mt19937 rng(1514);
  for_random_cases(1515, 30, true, [&](const RandomChain& ch, const Case& c0) {
    SCOPED_TRACE(ch.urdf);
    Model m = ch.model;
    for (int i = 0; i < m.num_rates(); ++i) m.set_rotor_inertia(i, uniform(rng, 0, 0.1));
    for (int variant = 0; variant < 3; ++variant) {
      Case c = c0;
      Options o;
      if (variant >= 1) o.effects = kAllEffects;
      if (variant == 2) {
        o.convention = Convention::Kdl;
        prescribe_random_joints(rng, m, c, 0.3);
        if (!(tree_coupling_condition(m, c) < 1e4)) continue;
      }
      const ReferenceSolution s = pv_reference(m, c, o);
      Data d(m);
      hybrid_dynamics(m, d, c, o);
      const double e = std::max({rel_error(s.qdd, d.qdd), rel_error(s.nu, d.nu),
                                 rel_error(s.joint_torques, d.joint_torques),
                                 rel_error(s.prescribed_torques, d.prescribed_torques),
                                 rel_error(stack(s.link_accelerations), stack(d.link_accelerations)),
                                 rel_error(s.constraint_wrench, d.constraint_wrench)});
      EXPECT_LE(e, 1e-12) << "variant " << variant;
      EXPECT_EQ(s.rank, d.rank);
      worst = std::max(worst, e);
      ++cases;
    }
  });
  std::printf("  %d chain cases: max rel error pv_reference vs hybrid_dynamics %.3g\n", cases, worst);
}

TEST(PvReference, RefusesPoliciesOtherThanTruncate) {
  std::mt19937 rng(1516);
  const RandomTree t = random_tree(rng, 4);
  Options o;
  o.policy = SingularityPolicy::Damped;
  EXPECT_THROW(pv_reference(t.model, Case::zeros(t.model), o), Error);
}

}  // namespace
}  // namespace achd::test
