#pragma once
// The Simulator's loop joints (Model::loops): how far each loop is open, and the beta
// that closes it again, as held directions do on a link (held_directions.hpp).
#include <vector>

#include <Eigen/Core>

#include "achd/model.hpp"

namespace achd {

// Loop `loop`'s errors at the body poses X0 and velocities v (tip_kinematics.hpp's
// body_motion), per held direction of its loop frame, in index order:
//   e_k: the closure error, frame a relative to frame b in the loop frame's axes: the
//        offset R_A^T (p_A - p_B) (x y z); the turn log(R_B^T R_A) (rx ry rz; with rz
//        free, the tilt of the axis R_A^T (z_B x z_A) instead);
//   g_k: the velocity error c_k^T (V_A(Q) - V_B(Q)), c_k the direction in base axes, V_A(Q)
//        link a's velocity at frame b's origin Q, V_B(Q) link b's.
// `e` and `g` receive num_columns() values each.
void loop_errors(const Model& model, const LoopJoint& loop, const std::vector<Transform>& X0,
                 const std::vector<Vector6>& v, double* e, double* g);

// The largest |e_k| of the loop (m or rad).
double loop_error(const Model& model, const LoopJoint& loop, const std::vector<Transform>& X0,
                  const std::vector<Vector6>& v);

// beta of every loop column (Case::loop_beta), so that each error decays as a held
// direction's does, e'' = -2 zeta w_n e' - w_n^2 e (Baumgarte), with e' = g. The solver
// constrains c_k^T (a_A(Q) - a_B(Q)) (spatial accelerations); the rate of g also holds
// the turning of c_k with link a and, on x y z, the motion of Q over link a:
//   g_k' = c_k^T (a_A(Q) - a_B(Q)) + (w_A x c_k)^T dV + [x y z] c_k^T ((w_A - w_B) x v_B(Q)),
// so beta_k = -2 zeta w_n g_k - w_n^2 e_k - the last two terms (these only when the solver
// computes velocity products, as for held directions).
void loop_targets(const Model& model, const std::vector<Transform>& X0, const std::vector<Vector6>& v,
                  double w_n, double zeta, bool velocity_products, Eigen::VectorXd& beta);

}  // namespace achd
