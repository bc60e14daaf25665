#pragma once
// The singularity sweep shared by hard_singularity.cpp and the KDL table: a planar
// three-joint arm (all axes +y, links along +x, 1 m, 1 m, 0.5 m, tool frame at the
// end through a fixed joint) at q = (0, theta, theta). As theta -> 0 the arm
// stretches along +x and the tip loses the radial (x) direction: the x row of the tip
// Jacobian is O(theta), so K = A^T J M^-1 J^T A has sigma_min = O(theta^2).
// Constraints: tip x acceleration beta_x = 1 m/s^2 outward (the lost direction, not
// reachable at the singularity) and tip z acceleration 0 (held against gravity, a
// direction that stays controllable).
#include <cmath>
#include <vector>

#include "achd/achd.hpp"
#include "hard_chain_urdf.hpp"

namespace achd::test {

inline std::string stretched_arm_urdf() {
  std::vector<LinkSpec> links(4);
  const double length[3] = {1.0, 1.0, 0.5}, mass[3] = {2.0, 1.5, 0.5};
  for (int i = 0; i < 3; ++i) {
    links[i].axis = {0, 1, 0};
    links[i].joint_xyz = {i == 0 ? 0.0 : length[i - 1], 0, 0};
    links[i].mass = mass[i];
    links[i].com = {length[i] / 2, 0, 0};
    // a rod of radius 0.03 m: I_axial = m r^2 / 2, I_transverse = m (3 r^2 + l^2) / 12
    const double r = 0.03, t = mass[i] * (3 * r * r + length[i] * length[i]) / 12;
    links[i].inertia_diag = {mass[i] * r * r / 2, t, t};
  }
  links[3].joint_type = "fixed";
  links[3].joint_xyz = {length[2], 0, 0};
  links[3].has_inertial = false;
  links[3].name = "tool";
  return chain_urdf(links);
}

inline Model stretched_arm() { return load_urdf_string(stretched_arm_urdf(), "link0", "tool"); }

inline Case stretched_arm_case(const Model& model, double theta) {
  Case c = Case::zeros(model);
  c.q << 0.0, theta, theta;
  c.alpha.resize(6, 2);
  c.alpha.setZero();
  c.alpha(0, 0) = 1;  // x: radial, lost at the singularity
  c.alpha(2, 1) = 1;  // z: vertical, still held
  c.beta.resize(2);
  c.beta << 1.0, 0.0;
  return c;
}

// theta = 1e-1, 1e-2, ..., 1e-12
inline std::vector<double> sweep_angles() {
  std::vector<double> t;
  for (int k = 1; k <= 12; ++k) t.push_back(std::pow(10.0, -k));
  return t;
}

}  // namespace achd::test
