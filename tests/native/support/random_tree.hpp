#pragma once
// Random kinematic trees and random cases on them, from a fixed seed, for the tree suites
// (pv_reference, the fast path on trees) and, through their URDF text, for the Node tests.
// A tree is drawn as URDF links (each on a random earlier link: random branching; revolute,
// continuous, prismatic and fixed joints; random origins, axes, masses, COM offsets and
// physical inertias), then turned into a Model in code, as the loader would: each movable
// joint's child link becomes a body whose frame is the link frame turned so that z is the
// joint axis, and links on fixed joints ride rigidly on the body they hang from, their
// inertias merged into it (links fixed to the root belong to the base).
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "achd/achd.hpp"

namespace achd::test {

// One URDF link after the root and the joint above it.
struct TreeLink {
  std::string name, joint;  // link "l<k>", joint "j<k>"
  int parent = 0;           // URDF link index, 0 = the root link "l0"
  std::string type;         // "revolute", "continuous", "prismatic" or "fixed"
  Transform origin;         // parent link frame -> this link frame (the joint's <origin>)
  Vector3 axis = Vector3::UnitZ();  // unit, in this link's frame (movable joints)
  double mass = 0;          // 0: a massless link (no <inertial>)
  Vector3 com = Vector3::Zero();    // in this link's frame
  Matrix3 inertia = Matrix3::Zero();  // about the COM, this link's axes
  double damping = 0, friction = 0;   // URDF <dynamics>
};

struct RandomTree {
  std::vector<TreeLink> links;  // URDF links 1.. (index k - 1 holds link "l<k>")
  Model model;                  // links[k - 1] is model.links[k - 1]: the same order
};

// A tree with `num_bodies` movable joints (>= 1) and fixed links among them. chain = true:
// each link hangs from the one before and the last link is movable and is the tip
// (Model::tip_name set); else a tree (no tip) branching at random. Every joint moves
// something (validate(Model) passes).
RandomTree random_tree(std::mt19937& rng, int num_bodies, bool chain = false);

// The Model of a set of URDF links (link k's parent < k), built as described above;
// tip: the tip link's name, empty for a tree.
Model tree_model(const std::vector<TreeLink>& links, const std::string& tip = "");

// Two trees on one root: b's links after a's, renamed (l<k> -> l<k + a's count>, j<k>
// likewise), its links on the root staying on the root.
std::vector<TreeLink> join_on_root(const std::vector<TreeLink>& a, const std::vector<TreeLink>& b);

// `arms` random chains of min_bodies .. max_bodies bodies each, joined on one root
// (join_on_root): a tree whose arm tips can hold 6 columns each. arm_tips: the Model::links
// index of each arm's tip.
RandomTree random_star(std::mt19937& rng, int arms, int min_bodies, int max_bodies,
                       std::vector<int>& arm_tips);

// `c` with a block of `columns` random unit columns at a random point on each of `links`
// (random beta), redrawn until the coupling condition number is below max_condition;
// nullopt after 200 draws.
std::optional<Case> with_blocks_on(std::mt19937& rng, const Model& model, Case c,
                                   const std::vector<int>& links, int columns,
                                   double max_condition = 1e4);

// The tree as URDF text (root link "l0"), every number written with 17 digits, so that a
// loader builds the same physical tree. Rotor inertia is not a URDF field: set it in code.
std::string tree_urdf(const std::vector<TreeLink>& links);

// Random q, qd, ff_torques, f_ext (one per link) and gravity (|g| in [5, 15]); no
// constraints, no prescribed joints.
Case random_tree_inputs(std::mt19937& rng, const Model& model);

// Random constraint blocks on 0 .. max_blocks distinct links (not fixed to the root), each
// at a random point with 1 .. 6 random unit alpha columns (at most the joints on the
// link's path) and random beta, max_columns in all; redrawn (blocks only) until the
// coupling condition number is below max_condition; nullopt after 200 draws.
std::optional<Case> with_random_blocks(std::mt19937& rng, const Model& model, Case c,
                                       int max_blocks = 6, int max_columns = kMaxConstraintColumns,
                                       double max_condition = 1e4);

// random_tree_inputs with random blocks (with_random_blocks, defaults): the random tree
// case of the suites and benchmarks; nullopt when no well-conditioned blocks were drawn.
std::optional<Case> random_tree_case(std::mt19937& rng, const Model& model, int max_blocks = 6);

// Marks each joint prescribed with probability `share` (at least one stays free), with a
// random qdd_given in [-3, 3].
void prescribe_random_joints(std::mt19937& rng, const Model& model, Case& c, double share);

// Condition number sigma_max / sigma_min of K = A M_ff^-1 A^T, A the stacked
// alpha_k^T J_k(point_k) (tip block first) restricted to the joints that are not
// prescribed, computed densely from the test references (reference_dynamics.hpp,
// reference_kinematics.hpp). 1 without constraints, infinity when K is singular.
double tree_coupling_condition(const Model& model, const Case& c);

// A[k] = alpha_k^T J_k at the block's point (a relative block: alpha_k^T (J_P - J_Q)): the
// tip's columns, then each block's (the rows of nu), from reference_link_jacobian. nc x nj.
Eigen::MatrixXd stacked_constraint_jacobian(const Model& model, const Case& c);

// Calls f(tree, rng) for `num_trees` random trees drawn from `seed`: the first with one
// body, the second with 60, the rest with 1 .. 60; rng continues the same stream.
template <class F>
void for_random_trees(unsigned seed, int num_trees, F f) {
  std::mt19937 rng(seed);
  for (int k = 0; k < num_trees; ++k) {
    const int bodies = k == 0 ? 1 : k == 1 ? 60 : std::uniform_int_distribution<int>(1, 60)(rng);
    f(random_tree(rng, bodies), rng);
  }
}

}  // namespace achd::test
