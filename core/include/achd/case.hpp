#pragma once
// The inputs of one hybrid-dynamics solve (the case format, docs/design.md section 5),
// owned by the caller and reused between solves.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// Columns of one constraint block (the tip's alpha, or one ConstraintBlock): a link has six
// directions to constrain.
constexpr int kMaxConstraints = 6;
// Columns in all of a case's blocks together: the largest capacity a Data can be created
// with (Data's constructor), so that every matrix of the constraint solve has fixed storage.
constexpr int kMaxConstraintColumns = 36;

// 6 x nc, nc <= 6: storage is fixed-size, so resizing never allocates.
using ConstraintMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxConstraints>;
// One value per constraint column (of a block, or of all blocks: nu), fixed storage.
using ConstraintVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraintColumns, 1>;

// Constraints on one link (Popov-Vereshchagin on trees): the spatial acceleration a_P of
// the link at `point` (linear part: of the point; base axes, as link_accelerations but
// taken at the point) must satisfy alpha^T a_P = beta, column by column; the force
// alpha nu acts at the point. Columns are oriented like the base, as Case::alpha.
// A relative block names a second link B (link_b >= 0): alpha^T (a_P - a_Q) = beta, with
// a_Q the acceleration of link B at point_b; the robot receives -alpha nu at P and
// +alpha nu at Q (a cut loop, or two bodies held together), and joint_torques =
// ff - sum_k (J_P,k - J_Q,k)^T alpha_k nu_k.
struct ConstraintBlock {
  int link = 0;                      // Model::links index of the constrained link
  Vector3 point = Vector3::Zero();   // where the constraint acts, in the link's frame
  int link_b = -1;                   // -1: none (relative to the world); else link B's index
  Vector3 point_b = Vector3::Zero(); // where it acts on link B, in link B's frame
  ConstraintMatrix alpha = ConstraintMatrix(6, 0);  // unit constraint forces, columns
  ConstraintVector beta = ConstraintVector(0);      // one per column of alpha
  ConstraintVector w_fext, w_ff;  // driver priorities per column (Case::w_fext, w_ff)
  // Columns that give way to the joints' efforts (bit k: column k; 0: none): where
  // following them would take a joint past its effort limit, the variable_damping solve
  // gives them up
  // (yield_to_efforts.hpp, Data::yielded). The simulator's pushed directions.
  std::uint8_t yields = 0;
};

struct Case {
  Eigen::VectorXd q;           // one per movable joint, root to tip
  Eigen::VectorXd qd;          // empty = zero
  Eigen::VectorXd ff_torques;  // empty = zero
  Vector3 gravity = Vector3(0, 0, -9.81);  // the physical vector, base frame
  // The tip's constraints (chains, KDL's alpha and beta): a block on the tip link's origin.
  ConstraintMatrix alpha = ConstraintMatrix(6, 0);  // unit constraint forces, columns
  ConstraintVector beta = ConstraintVector(0);      // one per column of alpha
  // Driver priorities, one per column in [0, 1] (empty: all 1): how far the column resists
  // the external wrenches f_ext (w_fext) and the feed-forward torques ff_torques (w_ff).
  // 1, KDL's behaviour: the driver cannot change alpha^T a. Below 1, the share 1 - w of
  // the driver's own unconstrained effect along the column passes through:
  //   alpha_k^T a = beta_k + (1 - w_fext,k) (A M^-1 J^T f_ext)_k + (1 - w_ff,k) (A M^-1 ff)_k
  // (driver_priorities.cpp).
  ConstraintVector w_fext, w_ff;
  // Constraints on any links, after the tip's: nu holds the tip's columns, then each
  // block's in order. Set once and reuse: a solve reads the blocks and never resizes them.
  std::vector<ConstraintBlock> constraints;
  std::vector<Vector6> f_ext;
  // Virtual wrenches: empty = none, else one per link after the root (at the link's
  // origin, base axes, as f_ext): wrenches a controller wants on the links, applied by the
  // joints as torques J^T f_virtual (Data::virtual_torques) added to ff_torques, so they
  // count in joint_torques and fall under w_ff. Unlike f_ext, nothing external acts.
  std::vector<Vector6> f_virtual;  // empty = none, else one per link after the root
  // Prescribed joints (Featherstone's hybrid dynamics): joint i with prescribed[i] true has
  // the acceleration qdd_given[i] instead of a torque (its ff_torques[i] is ignored); the
  // solve returns the torque it needs in Data::prescribed_torques. Both empty = no joint
  // prescribed (an all-false mask is the same); else both one per joint, and qdd_given is
  // finite everywhere (entries of joints that are not prescribed are not read).
  Eigen::VectorXd qdd_given;
  std::vector<bool> prescribed;
  // Coupled joints (Model::couplings): qdd_f - k qdd_l for each coupling, empty = 0 (what
  // q_f = k q_l + c asks); the simulator sets it to hold the coupling's drift.
  Eigen::VectorXd coupling_beta;
  // Loop joints (Model::loops): beta of every loop column, the loops in order and each
  // loop's directions in index order (Model::num_loop_columns() values), empty = 0 (the
  // loop's frames keep their relative velocity); the simulator sets it to hold the loops'
  // closure and the velocity terms of their turning directions.
  Eigen::VectorXd loop_beta;
  // Extra axial inertia per joint: empty = none, else one per joint, finite and >= 0. Added
  // to joint i's D = S^T IA S where its rotor inertia is (RBDA 9.28), whether or not
  // Effect::kRotorInertia is on: the mass matrix is M + diag(rotor) + diag(extra_inertia).
  // The implicit Euler step puts dt times the passive torques' derivative there
  // (core/src/simulation/integrators/implicit_euler.cpp).
  Eigen::VectorXd extra_inertia;

  // Constraint columns in all: the tip's and every block's.
  int num_constraints() const;
  // True when some joint is prescribed.
  bool any_prescribed() const;
  // A case of zeros for the model (q = 0, no constraints, gravity -9.81 z).
  static Case zeros(const Model& model);
};

// Throws achd::Error naming the field and index on a wrong length, a non-finite
// number, more than kMaxConstraints columns on the tip or in a block, a block on a link
// that is not in the model, a tip constraint on a model without a tip (a tree), or more
// constraint columns in all, the model's loop columns included, than `capacity` (the
// Data's: Data::constraint_capacity()), or a loop_beta of the wrong length.
void validate(const Model& model, const Case& c, int capacity = kMaxConstraintColumns);

}  // namespace achd
