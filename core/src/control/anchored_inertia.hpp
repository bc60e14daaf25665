#pragma once
// The inertia each joint moves when some links are held still: what the joint PD
// controller's frequency gains scale with (JointControl::frequency).
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// For each joint i, the inertia m_i of the bodies that move when joint i turns (or slides)
// at unit rate and the anchors do not move: 2 x the kinetic energy of that side,
//   m_i = sum over the side's bodies b of V_b^T I_b V_b,  V_b = the body's twist,
// which for the subtree after joint i is the joint-space inertia's M_ii. The side is the
// subtree unless the anchors are all in it (a foot held below an ankle: the ankle then
// moves the rest of the robot); with anchors on both sides (a joint in a loop through the
// ground), the larger of the two. Anchors are bodies (Model::links[l].body; -1 is the
// root); a fixed base is always anchored at the root. The joint's rotor inertia is added.
// A floating base's free joint: 0.
Eigen::VectorXd anchored_joint_inertias(const Model& model, const Eigen::VectorXd& q,
                                        const std::vector<int>& anchors);

}  // namespace achd
