// Relative constraint blocks: alpha^T (a_P - a_Q) = beta between a point P of one link and
// a point Q of another (ConstraintBlock::link_b), the explicit constraints of a cut loop.
// On seeded random trees of 10 to 40 bodies with 1 to 4 relative blocks between links of
// different branches, some mixed with blocks on one link, every effect on:
// - pv_reference equals the dense KKT solution of Gauss's principle with the rows
//   alpha^T (J_P - J_Q) (1e-8);
// - the motion it returns meets alpha^T (a_P - a_Q) = beta in the test's own kinematics
//   (1e-10), and RNEA at its qdd gives joint_torques = ff - sum (J_P - J_Q)^T alpha nu
//   (1e-10);
// - the fast path (hybrid_dynamics) equals pv_reference (1e-12), on fixed and floating
//   bases (the free joint's 6-DoF step takes the two legs' sum at the root);
// - driver weights pass each driver's share through along a relative column (1e-8);
// - naming the links the other way round with -alpha changes nothing, and a block
//   relative to a link fixed to the base is the block on one link.
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "random_chain.hpp"
#include "random_tree.hpp"
#include "reference_dynamics.hpp"
#include "reference_kinematics.hpp"
#include "tree_cases.hpp"

namespace achd::test {
namespace {

int uniform_int(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

bool is_ancestor(const Model& m, int ancestor, int body) {
  for (int i = body; i >= 0; i = m.bodies[i].parent)
    if (i == ancestor) return true;
  return false;
}

// Two moving links on different branches: neither's body is on the other's path.
bool on_different_branches(const Model& m, int la, int lb) {
  const int a = m.links[la].body, b = m.links[lb].body;
  return a >= 0 && b >= 0 && !is_ancestor(m, a, b) && !is_ancestor(m, b, a);
}

ConstraintBlock random_block(std::mt19937& rng, int link, int link_b, int columns) {
  ConstraintBlock b;
  b.link = link;
  b.point = uniform3(rng, -0.3, 0.3);
  b.link_b = link_b;
  if (link_b >= 0) b.point_b = uniform3(rng, -0.3, 0.3);
  b.alpha.resize(6, columns);
  for (int j = 0; j < columns; ++j)
    b.alpha.col(j) = Vector6::NullaryExpr([&] { return uniform(rng, -1, 1); }).normalized();
  b.beta = ConstraintVector::NullaryExpr(columns, [&] { return uniform(rng, -2, 2); });
  return b;
}

// `c` with 1 to 4 relative blocks between links of different branches (1 to 6 columns
// each) and, every other draw, one block on a single link; redrawn until K's condition
// number is below 1e4 (tree_coupling_condition); nullopt after 200 draws or when the tree
// has no two branches.
std::optional<Case> with_relative_blocks(std::mt19937& rng, const Model& m, Case c) {
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < m.num_links(); ++a)
    for (int b = a + 1; b < m.num_links(); ++b)
      if (on_different_branches(m, a, b)) pairs.emplace_back(a, b);
  if (pairs.empty()) return std::nullopt;
  for (int attempt = 0; attempt < 200; ++attempt) {
    c.constraints.clear();
    const int blocks = uniform_int(rng, 1, 4);
    int columns = 0;
    for (int k = 0; k < blocks && columns < m.num_rates(); ++k) {
      auto [a, b] = pairs[uniform_int(rng, 0, static_cast<int>(pairs.size()) - 1)];
      if (uniform(rng, 0, 1) < 0.5) std::swap(a, b);
      const int nc = uniform_int(rng, 1, std::min(kMaxConstraints, m.num_rates() - columns));
      c.constraints.push_back(random_block(rng, a, b, nc));
      columns += nc;
    }
    if (attempt % 2 == 0 && columns < m.num_rates()) {
      const int link = uniform_int(rng, 0, m.num_links() - 1);
      if (m.links[link].body >= 0) c.constraints.push_back(random_block(rng, link, -1, 1));
    }
    if (tree_coupling_condition(m, c) < 1e4) return c;
  }
  return std::nullopt;
}

// The spatial acceleration of `point` of `link` (the reference sweep's, no gravity).
Vector6 point_acceleration(const std::vector<FrameMotion>& motion, int link, const Vector3& point) {
  return motion_shift(motion[link].spatial_acceleration(), motion[link].R * point);
}

// Each block's alpha^T (a_P - a_Q) (a_Q = 0 without link_b) under the motion.
Eigen::VectorXd constraint_accelerations(const Case& c, const std::vector<FrameMotion>& motion) {
  Eigen::VectorXd out(c.num_constraints());
  int row = 0;
  for (const ConstraintBlock& b : c.constraints) {
    Vector6 a = point_acceleration(motion, b.link, b.point);
    if (b.link_b >= 0) a -= point_acceleration(motion, b.link_b, b.point_b);
    out.segment(row, b.alpha.cols()) = b.alpha.transpose() * a;
    row += static_cast<int>(b.alpha.cols());
  }
  return out;
}

Eigen::VectorXd stacked_beta(const Case& c) {
  Eigen::VectorXd beta(c.num_constraints());
  int row = 0;
  for (const ConstraintBlock& b : c.constraints) {
    beta.segment(row, b.alpha.cols()) = b.beta;
    row += static_cast<int>(b.alpha.cols());
  }
  return beta;
}

// Gauss's principle densely, every joint free:
//   M qdd + h = ff - A^T nu,   A qdd = beta - (alpha^T (a_P - a_Q) at qdd = 0, no gravity),
// M the reference CRBA (rotor inertia), h the reference RNEA at qdd = 0, A the stacked
// alpha^T (J_P - J_Q).
void dense_kkt(const Model& m, const Case& c, std::uint32_t effects, Eigen::VectorXd& qdd, Eigen::VectorXd& nu) {
  const int n = m.num_rates(), nc = c.num_constraints();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd M = reference_crba(m, c.q, effects & kRotorInertia);
  const Eigen::VectorXd h = reference_rnea(m, c.q, c.qd, zero, c.gravity, c.f_ext, effects, 0.05);
  const Eigen::MatrixXd A = stacked_constraint_jacobian(m, c);
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + nc, n + nc);
  kkt.topLeftCorner(n, n) = M;
  kkt.topRightCorner(n, nc) = A.transpose();
  kkt.bottomLeftCorner(nc, n) = A;
  Eigen::VectorXd rhs(n + nc);
  rhs.head(n) = c.ff_torques - h;
  rhs.tail(nc) = stacked_beta(c) - constraint_accelerations(c, reference_motion(m, c.q, c.qd, zero));
  const Eigen::VectorXd x = kkt.fullPivLu().solve(rhs);
  qdd = x.head(n);
  nu = x.tail(nc);
}

// Calls f(model, case) on random fixed-base trees of 10 to 40 bodies (random rotor
// inertias) with relative blocks; returns how many cases ran.
template <class F>
int for_relative_cases(unsigned seed, int trees, F f) {
  std::mt19937 rng(seed);
  int cases = 0;
  for (int k = 0; k < trees; ++k) {
    const RandomTree t = random_tree(rng, uniform_int(rng, 10, 40));
    Model m = t.model;
    for (int i = 0; i < m.num_rates(); ++i) m.set_rotor_inertia(i, uniform(rng, 0, 0.1));
    const std::optional<Case> c = with_relative_blocks(rng, m, random_tree_inputs(rng, m));
    if (!c) continue;
    SCOPED_TRACE(tree_urdf(t.links));
    f(m, *c);
    ++cases;
  }
  return cases;
}

constexpr int kRelativeTrees = 40;

TEST(RelativeBlocks, TextbookSolveIsTheDenseKktSolution) {
  double worst_qdd = 0, worst_nu = 0;
  const Options o = all_effects();
  const int cases = for_relative_cases(2701, kRelativeTrees, [&](const Model& m, const Case& c) {
    const ReferenceSolution s = pv_reference(m, c, o);
    Eigen::VectorXd qdd, nu;
    dense_kkt(m, c, o.effects, qdd, nu);
    const double e_qdd = rel_error(s.qdd, qdd), e_nu = rel_error(s.nu, nu);
    EXPECT_LE(e_qdd, 1e-8);
    EXPECT_LE(e_nu, 1e-8);
    EXPECT_EQ(s.rank, c.num_constraints());
    worst_qdd = std::max(worst_qdd, e_qdd);
    worst_nu = std::max(worst_nu, e_nu);
  });
  std::printf("  %d trees: pv_reference vs dense KKT: qdd %.3g, nu %.3g\n", cases, worst_qdd, worst_nu);
  EXPECT_GE(cases, kRelativeTrees * 3 / 4);
}

TEST(RelativeBlocks, MotionMeetsBetaAndRneaGivesTheJointTorques) {
  double worst_beta = 0, worst_rnea = 0, worst_jt = 0;
  const Options o = all_effects();
  const int cases = for_relative_cases(2702, kRelativeTrees, [&](const Model& m, const Case& c) {
    const ReferenceSolution s = pv_reference(m, c, o);
    const double e_beta =
        rel_error(constraint_accelerations(c, reference_motion(m, c.q, c.qd, s.qdd)), stacked_beta(c));
    const double e_rnea =
        rel_error(s.joint_torques, reference_rnea(m, c.q, c.qd, s.qdd, c.gravity, c.f_ext, o.effects, 0.05));
    const Eigen::VectorXd expected = c.ff_torques - stacked_constraint_jacobian(m, c).transpose() * s.nu;
    const double e_jt = rel_error(s.joint_torques, expected);
    EXPECT_LE(e_beta, 1e-10);
    EXPECT_LE(e_rnea, 1e-10);
    EXPECT_LE(e_jt, 1e-10);
    worst_beta = std::max(worst_beta, e_beta);
    worst_rnea = std::max(worst_rnea, e_rnea);
    worst_jt = std::max(worst_jt, e_jt);
  });
  std::printf("  %d trees: alpha^T (a_P - a_Q) vs beta %.3g; joint_torques vs RNEA(qdd) %.3g, vs ff - "
              "sum (J_P - J_Q)^T alpha nu %.3g\n", cases, worst_beta, worst_rnea, worst_jt);
  EXPECT_GE(cases, kRelativeTrees * 3 / 4);
}

// qdd, nu, joint_torques and constraint_wrenches of two solutions.
double solution_error(const ReferenceSolution& r, const Data& d) {
  double e = std::max({rel_error(r.qdd, d.qdd), rel_error(r.nu, Eigen::VectorXd(d.nu)),
                       rel_error(r.joint_torques, d.joint_torques)});
  EXPECT_EQ(r.constraint_wrenches.size(), d.constraint_wrenches.size());
  for (size_t k = 0; k < r.constraint_wrenches.size() && k < d.constraint_wrenches.size(); ++k)
    e = std::max(e, rel_error(r.constraint_wrenches[k], d.constraint_wrenches[k]));
  return e;
}

TEST(RelativeBlocks, FastPathIsTheTextbookSolve) {
  double worst = 0, worst_kdl = 0;
  const Options o = all_effects();
  Options kdl = o;
  kdl.convention = Convention::Kdl;
  const int cases = for_relative_cases(2703, kRelativeTrees, [&](const Model& m, const Case& c) {
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    const double e = solution_error(pv_reference(m, c, o), d);
    // the KDL convention: a_P - a_Q is the same in both (the base's -g cancels); a block on
    // one link has beta_kdl = beta - alpha_lin^T g
    Case k = c;
    for (ConstraintBlock& b : k.constraints)
      if (b.link_b < 0) b.beta -= b.alpha.topRows<3>().transpose() * c.gravity;
    hybrid_dynamics(m, d, k, kdl);
    const double e_kdl = solution_error(pv_reference(m, c, o), d);
    EXPECT_LE(e, 1e-12);
    EXPECT_LE(e_kdl, 1e-12);
    worst = std::max(worst, e);
    worst_kdl = std::max(worst_kdl, e_kdl);
  });
  std::printf("  %d trees: hybrid_dynamics vs pv_reference %.3g (kdl convention %.3g)\n", cases, worst, worst_kdl);
  EXPECT_GE(cases, kRelativeTrees * 3 / 4);
}

TEST(RelativeBlocks, NamingTheLinksTheOtherWayRoundChangesNothing) {
  double worst = 0;
  const Options o = all_effects();
  const int cases = for_relative_cases(2704, kRelativeTrees, [&](const Model& m, const Case& c) {
    Case swapped = c;
    for (ConstraintBlock& b : swapped.constraints) {
      if (b.link_b < 0) continue;
      std::swap(b.link, b.link_b);
      std::swap(b.point, b.point_b);
      b.alpha = -b.alpha;
    }
    Data d(m), ds(m);
    hybrid_dynamics(m, d, c, o);
    hybrid_dynamics(m, ds, swapped, o);
    const double e = std::max({rel_error(d.qdd, ds.qdd), rel_error(Eigen::VectorXd(d.nu), Eigen::VectorXd(ds.nu)),
                               rel_error(d.joint_torques, ds.joint_torques)});
    EXPECT_LE(e, 1e-12);
    worst = std::max(worst, e);
  });
  std::printf("  %d trees: (P, Q, alpha) vs (Q, P, -alpha) %.3g\n", cases, worst);
  EXPECT_GE(cases, kRelativeTrees * 3 / 4);
}

// Driver priorities on relative blocks: with weights w in [0, 1] on every column,
//   alpha_k^T (a_P - a_Q) = beta_k + (1 - w_fext,k) (A M^-1 J^T f_ext)_k + (1 - w_ff,k) (A M^-1 ff)_k,
// A the stacked alpha^T (J_P - J_Q), M the public CRBA, J^T f_ext from link_jacobian.
TEST(RelativeBlocks, DriverWeightsPassTheirShareThrough) {
  std::mt19937 rng(2708);
  double worst = 0;
  const Options o = all_effects();
  const int cases = for_relative_cases(2708, kRelativeTrees, [&](const Model& m, const Case& given) {
    Case c = given;
    Eigen::VectorXd wf(c.num_constraints()), wff(c.num_constraints());
    int row = 0;
    for (ConstraintBlock& b : c.constraints) {
      b.w_fext = ConstraintVector::NullaryExpr(b.alpha.cols(), [&] { return uniform(rng, 0, 1); });
      b.w_ff = ConstraintVector::NullaryExpr(b.alpha.cols(), [&] { return uniform(rng, 0, 1); });
      wf.segment(row, b.alpha.cols()) = b.w_fext;
      wff.segment(row, b.alpha.cols()) = b.w_ff;
      row += static_cast<int>(b.alpha.cols());
    }
    Data d(m);
    hybrid_dynamics(m, d, c, o);
    const Eigen::MatrixXd A = stacked_constraint_jacobian(m, c);
    const Eigen::LDLT<Eigen::MatrixXd> M(crba(m, c.q, o));
    Eigen::VectorXd JTf = Eigen::VectorXd::Zero(m.num_rates());
    for (int l = 0; l < m.num_links(); ++l) JTf += link_jacobian(m, c.q, l, Vector3::Zero()).transpose() * c.f_ext[l];
    const Eigen::VectorXd yf = A * M.solve(JTf), yff = A * M.solve(c.ff_torques);
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(wf.size());
    const Eigen::VectorXd expected =
        stacked_beta(c) + (ones - wf).cwiseProduct(yf) + (ones - wff).cwiseProduct(yff);
    const Eigen::VectorXd got = constraint_accelerations(c, reference_motion(m, c.q, c.qd, d.qdd));
    const double scale = std::max({1.0, expected.cwiseAbs().maxCoeff(), yf.cwiseAbs().maxCoeff(),
                                   yff.cwiseAbs().maxCoeff()});
    const double e = (got - expected).cwiseAbs().maxCoeff() / scale;
    EXPECT_LE(e, 1e-8);
    worst = std::max(worst, e);
  });
  std::printf("  %d trees: alpha^T (a_P - a_Q) vs beta + the drivers' shares %.3g\n", cases, worst);
  EXPECT_GE(cases, kRelativeTrees * 3 / 4);
}

// A block relative to a link fixed to the base (a_Q = 0) is the same block on one link.
TEST(RelativeBlocks, RelativeToTheBaseIsTheBlockOnOneLink) {
  std::mt19937 rng(2705);
  const Options o = all_effects();
  int cases = 0;
  double worst = 0;
  for (int k = 0; k < 200 && cases < 20; ++k) {
    const RandomTree t = random_tree(rng, uniform_int(rng, 3, 30));
    const Model& m = t.model;
    int fixed = -1;
    for (int l = 0; l < m.num_links() && fixed < 0; ++l)
      if (m.links[l].body < 0) fixed = l;
    if (fixed < 0) continue;
    std::optional<Case> one = with_random_blocks(rng, m, random_tree_inputs(rng, m), 3);
    if (!one || one->constraints.empty()) continue;
    Case relative = *one;
    for (ConstraintBlock& b : relative.constraints) {
      b.link_b = fixed;
      b.point_b = uniform3(rng, -0.5, 0.5);
    }
    Data d1(m), dr(m);
    hybrid_dynamics(m, d1, *one, o);
    hybrid_dynamics(m, dr, relative, o);
    const double e = std::max({rel_error(d1.qdd, dr.qdd), rel_error(Eigen::VectorXd(d1.nu), Eigen::VectorXd(dr.nu)),
                               rel_error(d1.joint_torques, dr.joint_torques),
                               solution_error(pv_reference(m, relative, o), dr)});
    EXPECT_LE(e, 1e-12);
    worst = std::max(worst, e);
    ++cases;
  }
  std::printf("  %d trees: relative to a link fixed to the base vs on one link %.3g\n", cases, worst);
  EXPECT_GE(cases, 10);
}

// Floating bases: the free joint's 6-DoF step takes the two legs' sum at the root.
TEST(RelativeBlocks, FloatingBaseFastPathIsTheTextbookSolve) {
  std::mt19937 rng(2706);
  const Options o = all_effects();
  int cases = 0;
  double worst = 0, worst_beta = 0;
  for (int k = 0; k < 60 && cases < 20; ++k) {
    const RandomTree t = random_tree(rng, uniform_int(rng, 10, 40));
    std::string urdf = tree_urdf(t.links);
    const std::string root = "<link name=\"l0\"/>";
    urdf.replace(urdf.find(root), root.size(),
                 "<link name=\"l0\"><inertial><mass value=\"3\"/><inertia ixx=\"0.05\" iyy=\"0.06\" izz=\"0.07\" "
                 "ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>");
    UrdfOptions options;
    options.floating = true;
    const Model m = load_urdf_string(urdf, "", "", options);
    Case c;
    c.q = Eigen::VectorXd::NullaryExpr(m.num_positions(), [&] { return uniform(rng, -1, 1); });
    c.q.segment<4>(3).normalize();
    c.qd = Eigen::VectorXd::NullaryExpr(m.num_rates(), [&] { return uniform(rng, -1, 1); });
    c.ff_torques = Eigen::VectorXd::NullaryExpr(m.num_rates(), [&] { return uniform(rng, -3, 3); });
    c.ff_torques.head<6>().setZero();
    c.gravity = Vector3(0, 0, -9.81);
    std::vector<std::pair<int, int>> pairs;
    for (int a = 0; a < m.num_links(); ++a)
      for (int b = a + 1; b < m.num_links(); ++b)
        if (m.links[a].body != m.links[b].body) pairs.emplace_back(a, b);
    if (pairs.empty()) continue;
    for (int b = 0; b < uniform_int(rng, 1, 3); ++b) {
      auto [la, lb] = pairs[uniform_int(rng, 0, static_cast<int>(pairs.size()) - 1)];
      c.constraints.push_back(random_block(rng, la, lb, uniform_int(rng, 1, 3)));
    }
    Data d(m);
    ReferenceSolution r;
    try {
      r = pv_reference(m, c, o);
    } catch (const Error&) {
      continue;  // (a draw the textbook solve finds singular)
    }
    if (r.rank != c.num_constraints()) continue;
    hybrid_dynamics(m, d, c, o);
    const double e = solution_error(r, d);
    // alpha^T (a_P - a_Q) = beta from the public link accelerations and poses
    const std::vector<Transform> X = forward_kinematics(m, c.q);
    double e_beta = 0;
    for (const ConstraintBlock& b : c.constraints) {
      const Vector6 aP = motion_shift(d.link_accelerations[b.link + 1], X[b.link].R * b.point);
      const Vector6 aQ = motion_shift(d.link_accelerations[b.link_b + 1], X[b.link_b].R * b.point_b);
      e_beta = std::max(e_beta, rel_error(b.alpha.transpose() * (aP - aQ), b.beta));
    }
    EXPECT_LE(e, 1e-12);
    EXPECT_LE(e_beta, 1e-10);
    worst = std::max(worst, e);
    worst_beta = std::max(worst_beta, e_beta);
    ++cases;
  }
  std::printf("  %d floating trees: hybrid_dynamics vs pv_reference %.3g, alpha^T (a_P - a_Q) vs beta %.3g\n", cases,
              worst, worst_beta);
  EXPECT_GE(cases, 15);
}

TEST(RelativeBlocks, BadSecondLinkIsNamed) {
  std::mt19937 rng(2707);
  const RandomTree t = random_tree(rng, 5);
  const Model& m = t.model;
  Case c = random_tree_inputs(rng, m);
  c.constraints.push_back(random_block(rng, 1, 2, 1));
  Data d(m);
  auto message = [&](const Case& bad) {
    try {
      hybrid_dynamics(m, d, bad, Options{});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  Case self = c;
  self.constraints[0].link_b = 1;
  EXPECT_NE(message(self).find("constraints[0].link_b: the block would hold link 'l2' relative to itself"),
            std::string::npos)
      << message(self);
  Case outside = c;
  outside.constraints[0].link_b = m.num_links();
  EXPECT_NE(message(outside).find("constraints[0].link_b: " + std::to_string(m.num_links()) + " is not a link index"),
            std::string::npos)
      << message(outside);
  Case not_finite = c;
  not_finite.constraints[0].point_b[1] = NAN;
  EXPECT_NE(message(not_finite).find("constraints[0].point_b[1] (link 'l3') is not finite"), std::string::npos)
      << message(not_finite);
  Case ignored = c;  // point_b without link_b is not read
  ignored.constraints[0].link_b = -1;
  ignored.constraints[0].point_b[1] = NAN;
  EXPECT_EQ(message(ignored), "(no error)");
}

}  // namespace
}  // namespace achd::test
