#pragma once
// Random serial chains and random cases for the physics-identity suites: URDF text built
// in code from a fixed seed (revolute, continuous, prismatic and fixed joints, random
// axes, origins with rpy, masses, COM offsets and physical inertias), loaded through
// achd::load_urdf_string so that fixed-joint merging is exercised.
#include <algorithm>
#include <optional>
#include <random>
#include <string>

#include "achd/achd.hpp"

namespace achd::test {

// Drawing helpers shared with random_tree.cpp: a uniform number, a vector of three, a
// uniformly random rotation, and a physical inertia about the COM (principal moments
// obeying the triangle inequality, randomly rotated) for `mass`.
double uniform(std::mt19937& rng, double lo, double hi);
Vector3 uniform3(std::mt19937& rng, double lo, double hi);
Matrix3 random_rotation(std::mt19937& rng);
Matrix3 random_inertia(std::mt19937& rng, double mass);

struct RandomChain {
  std::string urdf;
  std::string root = "l0", tip;  // links l0 (root) .. lN
  Model model;
};

// A chain of `num_links` links after the root. allow_fixed = false gives only movable
// joints (KDL's solver needs one joint per segment). At least one joint is movable.
RandomChain random_chain(std::mt19937& rng, int num_links, bool allow_fixed);

// Random q, qd, ff_torques, f_ext (one per link), gravity (|g| in [5, 15]) and
// `num_constraints` random alpha columns with random beta.
Case random_case(std::mt19937& rng, const Model& model, int num_constraints);

// Condition number sigma_max / sigma_min of the constraint coupling matrix
// K = A M^-1 A^T, A = alpha^T J, computed densely (CRBA, tip Jacobian). 1 when nc = 0,
// infinity when K is singular.
double coupling_condition(const Model& model, const Case& c);

// A random case whose coupling matrix has condition number below `max_condition`
// (redraws the whole case until it does; throws std::runtime_error after 100 tries).
Case well_conditioned_case(std::mt19937& rng, const Model& model, int num_constraints,
                           double max_condition = 1e4);

// A random case at q (gravity -9.81 z when standard_gravity, else random) whose coupling
// matrix has condition number below 1e4, redrawing the rest; nullopt after 100 draws.
std::optional<Case> case_at(std::mt19937& rng, const Model& model, const Eigen::VectorXd& q,
                            int num_constraints, bool standard_gravity);

// Rank of the tip Jacobian (at most kMaxConstraints) at q, or at a random configuration.
int tip_jacobian_rank(const Model& model, const Eigen::VectorXd& q);
int tip_jacobian_rank(std::mt19937& rng, const Model& model);

// The relative error (docs/design.md section 4.6): max|a - b| / max(1, max|b|).
double rel_error(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

// Calls f(chain, case) for `num_chains` random chains drawn from `seed` (the first has
// 1 link, the second 50, the rest 1..50) and, on each, one well-conditioned random case
// per constraint count nc = 0 .. rank of the tip Jacobian (<= min(joints, 6); an
// all-prismatic chain, for instance, can hold at most 3 directions).
template <class F>
void for_random_cases(unsigned seed, int num_chains, bool allow_fixed, F f) {
  std::mt19937 rng(seed);
  for (int k = 0; k < num_chains; ++k) {
    const int links = k == 0 ? 1 : k == 1 ? 50 : std::uniform_int_distribution<int>(1, 50)(rng);
    const RandomChain chain = random_chain(rng, links, allow_fixed);
    const int max_nc = tip_jacobian_rank(rng, chain.model);
    for (int nc = 0; nc <= max_nc; ++nc) f(chain, well_conditioned_case(rng, chain.model, nc));
  }
}

}  // namespace achd::test
