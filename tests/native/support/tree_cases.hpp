#pragma once
// The random tree cases shared by the tree suites (tree_identities.cpp,
// tree_fast_path.cpp): random trees with random blocks and prescribed joints, six-armed
// trees with 36 columns, every effect on.
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <vector>

#include "random_chain.hpp"
#include "random_tree.hpp"

namespace achd::test {

constexpr int kTrees = 30;

inline Eigen::VectorXd stack(const std::vector<Vector6>& v) {
  Eigen::VectorXd r(6 * v.size());
  for (size_t i = 0; i < v.size(); ++i) r.segment<6>(6 * i) = v[i];
  return r;
}

// The options of the tree suites: every effect, the physical convention.
inline Options all_effects() {
  Options o;
  o.effects = kAllEffects;
  return o;
}

// Calls f(model, case) on kTrees random trees from `seed` (random rotor inertias), three
// cases each: blocks, blocks with about a third of the joints prescribed, no blocks; then
// on kStars trees of six arms (6 to 10 bodies each) with six columns on every arm's tip
// (36 in all). Counts the cases run; a tree where no well-conditioned blocks were drawn
// skips that case.
constexpr int kStars = 5;
template <class F>
int for_tree_cases(unsigned seed, F f) {
  int cases = 0;
  auto run = [&](const RandomTree& t, std::mt19937& rng, const std::vector<int>& arm_tips) {
    Model m = t.model;
    for (int i = 0; i < m.num_rates(); ++i) m.set_rotor_inertia(i, uniform(rng, 0, 0.1));
    for (int variant = 0; variant < 3; ++variant) {
      std::optional<Case> blocks;
      if (variant == 0 && arm_tips.empty()) {
        blocks = random_tree_case(rng, m);
      } else {
        Case c = random_tree_inputs(rng, m);
        if (variant == 1) prescribe_random_joints(rng, m, c, arm_tips.empty() ? 0.3 : 0.05);
        blocks = variant == 2 ? std::optional<Case>(c)
                 : arm_tips.empty() ? with_random_blocks(rng, m, c)
                                    : with_blocks_on(rng, m, c, arm_tips, kMaxConstraints);
      }
      if (!blocks) continue;
      SCOPED_TRACE(tree_urdf(t.links));
      f(m, *blocks);
      ++cases;
    }
  };
  for_random_trees(seed, kTrees, [&](const RandomTree& t, std::mt19937& rng) { run(t, rng, {}); });
  std::mt19937 rng(seed + 1000);
  for (int k = 0; k < kStars; ++k) {
    std::vector<int> arm_tips;
    const RandomTree t = random_star(rng, 6, 6, 10, arm_tips);
    run(t, rng, arm_tips);
  }
  return cases;
}

}  // namespace achd::test
