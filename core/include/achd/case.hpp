#pragma once
// The inputs of one hybrid-dynamics solve (the case format, docs/design.md section 5),
// owned by the caller and reused between solves.
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

constexpr int kMaxConstraints = 6;

// 6 x nc, nc <= 6: storage is fixed-size, so resizing never allocates.
using ConstraintMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxConstraints>;
using ConstraintVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraints, 1>;

struct Case {
  Eigen::VectorXd q;           // one per movable joint, root to tip
  Eigen::VectorXd qd;          // empty = zero
  Eigen::VectorXd ff_torques;  // empty = zero
  Vector3 gravity = Vector3(0, 0, -9.81);  // the physical vector, base frame
  ConstraintMatrix alpha = ConstraintMatrix(6, 0);  // unit constraint forces, columns
  ConstraintVector beta = ConstraintVector(0);      // one per column of alpha
  std::vector<Vector6> f_ext;  // empty = none, else one per link after the root
  // Prescribed joints (Featherstone's hybrid dynamics): joint i with prescribed[i] true has
  // the acceleration qdd_given[i] instead of a torque (its ff_torques[i] is ignored); the
  // solve returns the torque it needs in Data::prescribed_torques. Both empty = no joint
  // prescribed (an all-false mask is the same); else both one per joint, and qdd_given is
  // finite everywhere (entries of joints that are not prescribed are not read).
  Eigen::VectorXd qdd_given;
  std::vector<bool> prescribed;

  int num_constraints() const { return static_cast<int>(alpha.cols()); }
  // True when some joint is prescribed.
  bool any_prescribed() const;
  // A case of zeros for the model (q = 0, no constraints, gravity -9.81 z).
  static Case zeros(const Model& model);
};

// Throws achd::Error naming the field and index on a wrong length, a non-finite
// number or more than kMaxConstraints constraints.
void validate(const Model& model, const Case& c);

}  // namespace achd
