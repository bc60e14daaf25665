#pragma once
// The directions a link's set holds or accelerates (Simulator), as the columns of its
// constraint block alpha^T a_P = beta of the hybrid solver (physical convention: beta is
// the real spatial acceleration of the point P along alpha).
#include <array>
#include <string>

#include "achd/case.hpp"
#include "achd/directions.hpp"
#include "achd/model.hpp"
#include "tip_kinematics.hpp"

namespace achd {

// The unit vector of direction k (x, y, z, rx, ry, rz) in base axes.
inline Vector3 direction_axis(int k) { return Vector3::Unit(k % 3); }
inline bool is_linear_direction(int k) { return k < 3; }

// "direction z" on a chain's tip (the directions the tip-only API sets), else
// "direction z of link 'foot'": how messages name direction `index` of link `link`.
std::string direction_label(const Model& model, int link, int index);

// One column of alpha per active direction, in index order: [e; 0] (force along e at
// the point) for x, y, z and [0; e] (moment about e) for rx, ry, rz.
void direction_columns(const HeldDirections& h, ConstraintMatrix& alpha);

// The driver weights of the active directions' columns (same order as direction_columns),
// or none (empty) when every weight is 1.
void direction_weights(const HeldDirections& h, ConstraintVector& w_fext, ConstraintVector& w_ff);

// Bit k set for each held direction that yields to a driver (a weight below 1).
unsigned yielding_directions(const HeldDirections& h);

// Held quantity minus its target: e . p_point - target (linear) or the held angle.
// `angles` holds the set's kNumDirections held angles.
double direction_error(const HeldDirections& h, int k, const TipState& point, const double* angles);

// beta for each active direction. The desired classical acceleration is the setpoint
// (Accelerate) or the Baumgarte law -2 zeta w_n e_dot - w_n^2 e_err (Hold). A linear
// spatial acceleration differs from the classical one of the point by w x v
// (p_ddot = a_lin + w x v), so linear rows subtract e . (w x v) when the solver computes
// velocity products; angular spatial and classical accelerations are equal.
void direction_targets(const HeldDirections& h, const TipState& point, const double* angles, double w_n,
                       double zeta, bool velocity_products, ConstraintVector& beta);

}  // namespace achd
