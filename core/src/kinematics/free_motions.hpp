#pragma once
// Which joint, if any, moves nothing: decided from the structure of the tree (which
// motions each body's inertia resists, which motions the joints after it can take up), not
// from the size of D = S^T IA S, so that neither the length of the chain nor the ratio of
// its masses enters the decision. See free_motions.cpp.
#include <array>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// The highest index of a joint that moves nothing at configuration q, or -1 (on a chain,
// the one nearest the tip).
// The model's inertias and origins must be finite.
int joint_moving_nothing(const Model& model, const Eigen::VectorXd& q);

// The two configurations a model is checked at (validate): the zero pose, and a generic
// one within the joints' limits.
std::array<Eigen::VectorXd, 2> check_configurations(const Model& model);

// A joint that moves nothing at either check configuration (the zero pose's first), or -1.
int joint_moving_nothing_at_checks(const Model& model);

}  // namespace achd
