#pragma once
// The workspace of the algorithms, sized once from a Model: solves write here and
// never allocate. Outputs are the public members in the "results" block; the sweeps'
// quantities follow, named as in docs/design.md, section 6.4; `workspace` holds what only
// the sweeps' schedule needs.
#include <array>
#include <cstdint>
#include <vector>

#include "achd/case.hpp"
#include "achd/model.hpp"

namespace achd {

// 6 x m unit constraint forces of all columns, m <= kMaxConstraintColumns, fixed storage.
using ForceColumns = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxConstraintColumns>;

// One block of constraint columns as the sweeps see it: the tip's columns (Case::alpha), one
// Case::constraints block or one loop joint's (Data::Workspace::loop_blocks).
struct ConstraintSource {
  int body = -1;    // the body its link rides on (-1: fixed to the root)
  int column = 0;   // its first column in nu, K and E
  int columns = 0;  // how many
  int block = -1;   // -1 for the tip's; b < the case's blocks: Case::constraints[b]; else
                    // loop_blocks[b - the case's blocks] (solve_blocks.hpp)
  int ez = 0;       // where its EZ_i start in Data::Workspace::ez
  Vector3 arm = Vector3::Zero();  // from the body's origin to the point it acts at, base axes
  // A relative block's second link: its body, the arm to its point, and where the two
  // paths to the base meet (their lowest common ancestor, -1: the base). For a block on
  // one link, body_b = meet = body: its path is the body and its ancestors.
  bool relative = false;
  int body_b = -1, meet = -1;
  Vector3 arm_b = Vector3::Zero();
};

using CouplingMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraintColumns,
                                     kMaxConstraintColumns>;

struct Data {
  // constraint_capacity: the most constraint columns a case solved with this Data may
  // have, all blocks together (at most kMaxConstraintColumns); the storage of the
  // several-block constraint sweep grows with it, per body.
  explicit Data(const Model& model, int constraint_capacity = kMaxConstraintColumns);
  int constraint_capacity() const { return capacity_; }

  // The links whose accelerations the solves write into link_accelerations. A new Data
  // writes every link's (the root link's and each Model::links entry's).
  // set_link_outputs(links) narrows that to `links` (Model::links indices, -1 for the root
  // link; order and repeats do not matter; empty: none) and sets every other link's entry
  // to 0, which no solve writes again: a link that carries no constraint block and no
  // wrench (a sensor or marker frame on a fixed joint) then costs a solve nothing, and
  // every other result stays the same to the bit. Throws achd::Error naming the entry that
  // is not a link (and changes nothing then); allocates: call it once, outside the loop of
  // solves. set_all_link_outputs(): every link again.
  void set_link_outputs(const std::vector<int>& links);
  void set_all_link_outputs();
  bool all_link_outputs() const { return all_link_outputs_; }
  // The links set_link_outputs() asked for, sorted, each once (empty when all_link_outputs()).
  const std::vector<int>& link_outputs() const { return link_outputs_; }

  // ---- results of the last hybrid_dynamics() ----
  Eigen::VectorXd qdd;                 // joint accelerations
  Eigen::VectorXd constraint_torques;  // KDL's -S^T E nu
  Eigen::VectorXd total_torques;       // KDL's D qdd
  Eigen::VectorXd joint_torques;       // ff - J^T alpha nu = RNEA(q, qd, qdd), with a
                                       // prescribed joint's prescribed_torques as its ff
  Eigen::VectorXd virtual_torques;     // J^T f_virtual, the joint torques of the virtual
                                       // wrenches (0 without), part of the ff torques
  Eigen::VectorXd prescribed_torques;  // per joint: for a prescribed joint (Case::prescribed)
                                       // the actuator torque its given qdd needs while the
                                       // constraint forces act (the ff_torques that, with the
                                       // joint free, gives the same solve); 0 for the others
  ConstraintVector nu;                 // constraint force magnitudes: the tip's columns,
                                       // then each block's (Case::constraints) in order
  Vector6 constraint_wrench;           // alpha nu of the tip's columns, at the tip link's
                                       // origin: what the tip exerts on the constraint
  std::vector<Vector6> constraint_wrenches;  // per Case::constraints block, then per loop
                                             // joint: alpha nu at its point, base axes
  std::vector<Vector6> link_accelerations;  // root link first, then Model::links; those
                                            // of the links asked for (set_link_outputs)
  Eigen::VectorXd coupling_forces;  // per Model::couplings entry: nu_c, the robot receiving
                                    // the torques -C^T nu_c (joint_couplings.hpp)
  int rank = 0;                  // of the coupling matrix K (nc x nc); its
                                 // smallest singular value: sigma_min(data)
  CouplingMatrix dropped;        // nc x k: constraint-space directions truncated/damped
  // variable_damping: the eigen-directions of K in the singular region (nc x k, unit
  // columns; dropped holds those where sigma <= lambda), with their singular values and
  // damping lambda (K's units, the scaled columns'); k = 0 when the solve was exact.
  CouplingMatrix damped;
  ConstraintVector damped_sigma, damped_lambda;
  // The blocks' yielding columns (ConstraintBlock::yields, variable_damping): effort_ratio, the largest
  // |tau_i| / effort_i the constraint forces would take from a joint if they were followed,
  // and how far the solve gave them up for it, yielded in [0, 1] (0: followed; 1: their
  // nu is 0, the other columns solved without them). Both 0 without yielding columns.
  double effort_ratio = 0, yielded = 0;

  // ---- the sweeps' quantities per body (Featherstone's names; index = body) ----
  // The sweeps use base axes everywhere, and express body i's vectors and inertias about
  // the body's origin p_i (the "mixed" representation KDL reports link accelerations in):
  // passing them between a body and its parent is a shift by r_i, never a rotation, and
  // nothing is taken about a far-away point (the base origin), which would cost digits.
  // The joint subspace is S_i = [0; z_i] (revolute) or [z_i; 0] (prismatic), z_i the
  // body's z axis, X0_i.R.col(2).
  std::vector<Transform> X0;     // body pose in the base (axes R, origin p)
  std::vector<Vector3> r;        // p_i - p_parent, base axes (kinematics.hpp's body_poses)
  std::vector<Vector6> v;        // velocity
  std::vector<Vector6> kappa;    // velocity-product acceleration, summed from the base
                                 // (what the body's acceleration would be with qdd = 0
                                 // and no gravity)
  std::vector<Vector6> a;        // a~ = a - kappa, where a is KDL's acc: it includes the
                                 // fictitious base acceleration a_0 = [-g; 0] when gravity
                                 // is on (physical acceleration: a~ + kappa - a_0)
  std::vector<Matrix6> IA;       // the rigid inertia I_i in base axes (outward sweep);
                                 // the inward sweep adds the children's shares, so from
                                 // when it reaches body i it is the articulated inertia IA_i
  std::vector<Vector6> pA;       // the rigid bias force v x* I v + I kappa - f_ext
                                 // (outward sweep and external wrenches); the inward sweep
                                 // adds the children's shares, so from when it reaches
                                 // body i it is the articulated bias force pA_i

  // ---- the constraint part at the base (nc = the number of constraints) ----
  // The sweeps work on the columns alpha_k s_k, s_k = workspace.alpha_scale[k] (a power of
  // two, see docs/design.md "Column scaling"), whose forces are nu_k / s_k.
  ForceColumns E;        // unit constraint forces alpha_k s_k (6 x nc), each block's moved
                         // from its point to the base (after the solve: E_0)
  CouplingMatrix K;      // K = -M_0 = sum_i EZ_i EZ_i^T / D_i (nc x nc), the coupling of
                         // the columns alpha_k s_k at the base (sigma_min() reads it)
  ConstraintVector G0;   // G_0 = sum_i EZ_i u_i / D_i, acceleration energy of the bias terms

  // ---- internal: caches of the sweeps' schedule, not results ----
  // Public only so that tests can inspect a solve; their layout may change.
  struct Workspace {
    Eigen::VectorXd tau;            // joint torques fed to the sweeps: ff less damping, friction
    std::vector<Vector6> U;         // IA S
    std::vector<Vector6> W;         // U / D about the parent's origin (X^T U / D), for
                                    // the final outward sweep
    std::vector<double> D, Dinv;    // S^T IA S (+ rotor inertia), 1 / D
    std::vector<double> u;          // tau - S^T pA
    // The blocks of columns of the last solve (the tip's first), reserved to the capacity.
    std::vector<ConstraintSource> sources;
    // EZ_i = E^T S_i of each block at each body on its path to the base: block s's at
    // ez[s.ez + i * stride], stride its column count rounded up to even, the slot after an
    // odd count 0 (the columns are held two to a pair: constraint_pairs.hpp)
    std::vector<double> ez;
    // Relative blocks that all end on one second body (shared_second_body.hpp): that body
    // (-1: the last sweep took each block's legs), the EZ_i of six unit wrenches there at
    // each body on its path (6 per body), and each column's force at its origin (6 each).
    int shared_body = -1;
    std::vector<double> shared_ez;
    std::array<double, 6 * kMaxConstraintColumns> shared_C;
    std::vector<int> path;          // scratch: the bodies from one body to the base
    std::vector<unsigned char> walked;  // scratch: 1 at the bodies a walk has passed, else 0
    // Driver priorities (driver_priorities.cpp): per body the bias of f_ext alone and of
    // ff_torques alone (6 + 6), and their u / D (2 per body).
    std::vector<Eigen::Matrix<double, 12, 1>> driver_bias;
    std::vector<double> driver_qdd;
    std::vector<Vector6> virtual_force;  // per body: the virtual wrenches of its subtree
    ConstraintVector alpha_scale;   // s_k: the sweeps use the columns alpha_k s_k
    // per column: true when alpha_k has a force part (variable_damping's kinds)
    std::array<bool, kMaxConstraintColumns> has_force;
    ConstraintVector rhs;           // K nu' = rhs: E_0^T a_0 + G_0 - beta' (scaled columns)
    // variable_damping, when it damped a direction: the exact solve nu' = K^-1 rhs (every
    // eigenvalue above the truncation threshold), kept if the joints' efforts allow it
    // (hybrid_dynamics.cpp); size 0 when there is none.
    ConstraintVector exact_nu;
    // variable_damping: the columns that gave way in the last solve, or were chosen to
    // (solve_held_first; Options::gives_way; bit j: column j), 0 when none was.
    std::uint64_t gave_way = 0;
    // variable_damping: the columns that may yield (ConstraintBlock::yields, bit j: column
    // j), which give way first where the solve must give way (solve_held_first).
    std::uint64_t yielding = 0;
    // Set by a caller that has already put body_poses at the next solve's q into X0 and r
    // (the simulator, whose held directions need the poses before the solve): that solve
    // takes them as they are and clears the flag; any other solve computes them.
    bool poses_given = false;
    // The last constraint sweep took a floating base's free joint in one 6-DoF step
    // (free_joint_constraints.hpp): d.E then holds the columns at the root, E_0 being 0.
    bool free_joint_step = false;
    // A floating base's qd, ff_torques and qdd_given in the solver's coordinates
    // (free_joint.hpp), sized by the constructor.
    Eigen::VectorXd free_qd, free_ff_torques, free_qdd_given;
    // Coupled joints (joint_couplings.cpp): the case of the extra solves and the
    // accelerations under each coupling's unit torques (n x p), reserved by the constructor.
    Case coupling_case;
    // Loop joints (loop_blocks.hpp): one block per Model::loops entry at the solve's q, held
    // after the case's own blocks; sized by the constructor.
    std::vector<ConstraintBlock> loop_blocks;
    // where each loop block acts at the solve's q: its bodies and arms (ConstraintSource's
    // body, arm, relative, body_b, arm_b), set with loop_blocks
    std::vector<ConstraintSource> loop_placements;
    Eigen::MatrixXd coupling_response;
  } workspace;
 private:
  int capacity_;
  bool all_link_outputs_ = true;
  std::vector<int> link_outputs_;
};

}  // namespace achd
