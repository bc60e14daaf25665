// The fast path (hybrid_dynamics) on kinematic trees with constraint blocks, against the
// plain reference (pv_reference): equal in every output on seeded random trees (<= 1e-12
// relative, docs/design.md section 4.6). And two ways of saying the same problem, for both
// solvers: a chain's tip alpha equals a block on its tip link; two chains on one fixed root
// solved as one tree equal the two chain solves.
#include <gtest/gtest.h>

#include <cstdio>

#include "random_chain.hpp"
#include "random_tree.hpp"
#include "tree_cases.hpp"

namespace achd::test {
namespace {

// The outputs both solvers have, by the same names.
struct Solution {
  Eigen::VectorXd qdd, nu, joint_torques, prescribed_torques;
  std::vector<Vector6> link_accelerations, constraint_wrenches;
  Vector6 constraint_wrench;
  int rank;
};

Solution fast_path(const Model& m, const Case& c, const Options& o) {
  Data d(m);
  hybrid_dynamics(m, d, c, o);
  return {d.qdd, d.nu, d.joint_torques, d.prescribed_torques, d.link_accelerations,
          d.constraint_wrenches, d.constraint_wrench, d.rank};
}

Solution reference(const Model& m, const Case& c, const Options& o) {
  const ReferenceSolution s = pv_reference(m, c, o);
  return {s.qdd, s.nu, s.joint_torques, s.prescribed_torques, s.link_accelerations,
          s.constraint_wrenches, s.constraint_wrench, s.rank};
}

using Solver = Solution (*)(const Model&, const Case&, const Options&);

// The largest relative error over the outputs, named.
struct Comparison {
  double qdd = 0, nu = 0, joint_torques = 0, prescribed_torques = 0, link_accelerations = 0,
         constraint_wrenches = 0;
  double max() const {
    return std::max({qdd, nu, joint_torques, prescribed_torques, link_accelerations, constraint_wrenches});
  }
  void add(const Comparison& o) {
    qdd = std::max(qdd, o.qdd), nu = std::max(nu, o.nu);
    joint_torques = std::max(joint_torques, o.joint_torques);
    prescribed_torques = std::max(prescribed_torques, o.prescribed_torques);
    link_accelerations = std::max(link_accelerations, o.link_accelerations);
    constraint_wrenches = std::max(constraint_wrenches, o.constraint_wrenches);
  }
  void print(const char* what, int cases) const {
    std::printf("  %s, %d cases: max rel error qdd %.3g, nu %.3g, joint_torques %.3g, prescribed_torques "
                "%.3g, link_accelerations %.3g, constraint_wrenches %.3g\n", what, cases, qdd, nu,
                joint_torques, prescribed_torques, link_accelerations, constraint_wrenches);
  }
};

Comparison compare(const Solution& a, const Solution& b) {
  Comparison e;
  e.qdd = rel_error(a.qdd, b.qdd);
  e.nu = rel_error(a.nu, b.nu);
  e.joint_torques = rel_error(a.joint_torques, b.joint_torques);
  e.prescribed_torques = rel_error(a.prescribed_torques, b.prescribed_torques);
  e.link_accelerations = rel_error(stack(a.link_accelerations), stack(b.link_accelerations));
  e.constraint_wrenches = std::max(rel_error(stack(a.constraint_wrenches), stack(b.constraint_wrenches)),
                                   rel_error(a.constraint_wrench, b.constraint_wrench));
  return e;
}

TEST(FastPathTrees, EqualsPvReference) {
  Comparison worst;
  const Options o = all_effects();
  const int cases = for_tree_cases(1521, [&](const Model& m, const Case& c) {
    const Solution ref = reference(m, c, o);
    Solution fast;
    try {
      fast = fast_path(m, c, o);
    } catch (const Error& e) {
      ADD_FAILURE() << "hybrid_dynamics: " << e.what();
      return;
    }
    const Comparison e = compare(fast, ref);
    EXPECT_LE(e.max(), 1e-12) << "qdd " << e.qdd << " nu " << e.nu << " joint_torques " << e.joint_torques
                              << " prescribed_torques " << e.prescribed_torques << " link_accelerations "
                              << e.link_accelerations << " constraint_wrenches " << e.constraint_wrenches
                              << " (" << c.num_constraints() << " columns, " << c.constraints.size()
                              << " blocks)";
    EXPECT_EQ(fast.rank, ref.rank);
    worst.add(e);
  });
  worst.print("hybrid_dynamics vs pv_reference on trees", cases);
}

// Every effect mask (gravity, velocity products, external wrenches, damping, friction,
// rotor inertia, constraints on or off, drawn at random) in both conventions, and
// absolute tolerances: the fast path still equals pv_reference.
TEST(FastPathTrees, EqualsPvReferenceUnderEveryEffectMaskAndConvention) {
  Comparison worst;
  std::mt19937 draw(1524);
  const int cases = for_tree_cases(1525, [&](const Model& m, const Case& c) {
    Options o;
    o.effects = std::uniform_int_distribution<std::uint32_t>(0, kAllEffects)(draw) & kAllEffects;
    o.convention = draw() % 2 ? Convention::Kdl : Convention::Physical;
    if (draw() % 2) {
      o.absolute_tolerance = true;
      o.tolerance = 1e-14;
    }
    const Solution ref = reference(m, c, o);
    Solution fast;
    try {
      fast = fast_path(m, c, o);
    } catch (const Error& e) {
      ADD_FAILURE() << "hybrid_dynamics: " << e.what();
      return;
    }
    const Comparison e = compare(fast, ref);
    EXPECT_LE(e.max(), 1e-12) << "effects " << o.effects << " qdd " << e.qdd << " nu " << e.nu;
    EXPECT_EQ(fast.rank, ref.rank);
    worst.add(e);
  });
  worst.print("hybrid_dynamics vs pv_reference, random effects and conventions", cases);
}

// Random unit tip columns (nc of them) and beta, redrawn until the coupling condition
// number is below 1e4; false after 200 draws.
bool draw_tip_constraints(std::mt19937& rng, const Model& m, Case& c, int nc) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    c.alpha.resize(6, nc);
    for (int k = 0; k < nc; ++k)
      c.alpha.col(k) = Vector6::NullaryExpr([&] { return uniform(rng, -1, 1); }).normalized();
    c.beta = ConstraintVector::NullaryExpr(nc, [&] { return uniform(rng, -2, 2); });
    if (tree_coupling_condition(m, c) < 1e4) return true;
  }
  return false;
}

// The chain's tip constraints as a block on the tip link's origin.
Case as_tip_block(const Model& m, Case c) {
  ConstraintBlock b;
  b.link = m.num_links() - 1;
  b.alpha = c.alpha;
  b.beta = c.beta;
  c.constraints = {b};
  c.alpha.resize(6, 0);
  c.beta.resize(0);
  return c;
}

void tip_alpha_equals_a_tip_block(Solver solve, const char* what) {
  std::mt19937 rng(1522);
  Comparison worst;
  int cases = 0;
  for (int k = 0; k < 30; ++k) {
    const RandomTree chain = random_tree(rng, k == 0 ? 1 : std::uniform_int_distribution<int>(1, 40)(rng), true);
    Model m = chain.model;
    for (int i = 0; i < m.num_rates(); ++i) m.set_rotor_inertia(i, uniform(rng, 0, 0.1));
    for (int nc = 1; nc <= std::min(kMaxConstraints, m.num_rates()); ++nc) {
      Case c = random_tree_inputs(rng, m);
      if (nc % 2) prescribe_random_joints(rng, m, c, 0.2);
      if (!draw_tip_constraints(rng, m, c, nc)) continue;
      SCOPED_TRACE(tree_urdf(chain.links));
      const Options o = all_effects();
      Solution tip, block;
      try {
        tip = solve(m, c, o);
        block = solve(m, as_tip_block(m, c), o);
      } catch (const Error& e) {
        ADD_FAILURE() << what << ": " << e.what();
        continue;
      }
      // The tip's wrench is the block's.
      block.constraint_wrench = block.constraint_wrenches.at(0);
      tip.constraint_wrenches = block.constraint_wrenches;
      const Comparison e = compare(block, tip);
      EXPECT_LE(e.max(), 1e-12) << what << ": nc " << nc << " qdd " << e.qdd << " nu " << e.nu;
      EXPECT_EQ(block.rank, tip.rank);
      worst.add(e);
      ++cases;
    }
  }
  worst.print(what, cases);
  EXPECT_GE(cases, 60);
}

TEST(FastPathChains, TipAlphaEqualsABlockOnTheTipLink) {
  tip_alpha_equals_a_tip_block(fast_path, "hybrid_dynamics: tip alpha vs a block on the tip");
}

TEST(PvReferenceChains, TipAlphaEqualsABlockOnTheTipLink) {
  tip_alpha_equals_a_tip_block(reference, "pv_reference: tip alpha vs a block on the tip");
}

// Two random chains A and B, each with random tip constraints, and the tree of both on one
// root (A's bodies and links first): the tree's case is the two cases side by side, its
// blocks the two tips' constraints.
void two_chains_equal_one_tree(Solver solve, const char* what) {
  std::mt19937 rng(1523);
  Comparison worst;
  int cases = 0;
  for (int k = 0; k < 40; ++k) {
    const RandomTree a = random_tree(rng, std::uniform_int_distribution<int>(1, 30)(rng), true);
    const RandomTree b = random_tree(rng, std::uniform_int_distribution<int>(1, 30)(rng), true);
    const std::vector<TreeLink> joined = join_on_root(a.links, b.links);
    const Model tree = tree_model(joined);
    const Model& ma = a.model;
    const Model& mb = b.model;
    const int na = ma.num_rates(), nb = mb.num_rates();
    Case ca = random_tree_inputs(rng, ma), cb = random_tree_inputs(rng, mb);
    cb.gravity = ca.gravity;
    if (k % 3 == 1) {
      prescribe_random_joints(rng, ma, ca, 0.2);
      prescribe_random_joints(rng, mb, cb, 0.2);
    }
    const int nca = std::uniform_int_distribution<int>(0, std::min(kMaxConstraints, na))(rng);
    const int ncb = std::uniform_int_distribution<int>(0, std::min(kMaxConstraints, nb))(rng);
    if (!draw_tip_constraints(rng, ma, ca, nca) || !draw_tip_constraints(rng, mb, cb, ncb)) continue;
    SCOPED_TRACE(tree_urdf(joined));

    Case ct = Case::zeros(tree);
    ct.gravity = ca.gravity;
    ct.q << ca.q, cb.q;
    ct.qd.resize(na + nb);
    ct.qd << ca.qd, cb.qd;
    ct.ff_torques.resize(na + nb);
    ct.ff_torques << ca.ff_torques, cb.ff_torques;
    ct.f_ext = ca.f_ext;
    ct.f_ext.insert(ct.f_ext.end(), cb.f_ext.begin(), cb.f_ext.end());
    if (ca.any_prescribed() || cb.any_prescribed()) {
      ct.qdd_given.resize(na + nb);
      ct.qdd_given << ca.qdd_given, cb.qdd_given;
      ct.prescribed = ca.prescribed;
      ct.prescribed.insert(ct.prescribed.end(), cb.prescribed.begin(), cb.prescribed.end());
    }
    const Case block_a = as_tip_block(ma, ca), block_b = as_tip_block(mb, cb);
    ct.constraints = {block_a.constraints[0], block_b.constraints[0]};
    ct.constraints[1].link += ma.num_links();

    const Options o = all_effects();
    Solution sa, sb, st;
    try {
      sa = solve(ma, ca, o);
      sb = solve(mb, cb, o);
      st = solve(tree, ct, o);
    } catch (const Error& e) {
      ADD_FAILURE() << what << ": " << e.what();
      continue;
    }
    // The two chain solves side by side, in the tree's order (B's root link is the tree's).
    Solution both;
    both.qdd.resize(na + nb);
    both.qdd << sa.qdd, sb.qdd;
    both.nu.resize(nca + ncb);
    both.nu << sa.nu, sb.nu;
    both.joint_torques.resize(na + nb);
    both.joint_torques << sa.joint_torques, sb.joint_torques;
    both.prescribed_torques.resize(na + nb);
    both.prescribed_torques << sa.prescribed_torques, sb.prescribed_torques;
    both.link_accelerations = sa.link_accelerations;
    both.link_accelerations.insert(both.link_accelerations.end(), sb.link_accelerations.begin() + 1,
                                   sb.link_accelerations.end());
    both.constraint_wrenches = {sa.constraint_wrench, sb.constraint_wrench};
    both.constraint_wrench = st.constraint_wrench;
    both.rank = sa.rank + sb.rank;
    const Comparison e = compare(st, both);
    EXPECT_LE(e.max(), 1e-12) << what << ": qdd " << e.qdd << " nu " << e.nu << " joint_torques "
                              << e.joint_torques << " link_accelerations " << e.link_accelerations;
    EXPECT_EQ(st.rank, both.rank);
    worst.add(e);
    ++cases;
  }
  worst.print(what, cases);
  EXPECT_GE(cases, 30);
}

TEST(FastPathTrees, TwoChainsOnOneRootEqualTheTwoChainSolves) {
  two_chains_equal_one_tree(fast_path, "hybrid_dynamics: two chains vs one tree");
}

TEST(PvReferenceTrees, TwoChainsOnOneRootEqualTheTwoChainSolves) {
  two_chains_equal_one_tree(reference, "pv_reference: two chains vs one tree");
}

}  // namespace
}  // namespace achd::test
