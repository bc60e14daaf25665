// The loop joints' closure errors and the beta that holds them (loop_closure.hpp).
#include "loop_closure.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "tip_kinematics.hpp"

namespace achd {
namespace {

// Both frames of a loop in the base frame, with the links' velocities at Q (frame b's
// origin) and the difference dV = V_A(Q) - V_B(Q).
struct LoopMotion {
  Transform A, B;  // the loop frame on link a and on link b
  Vector3 w_a, w_b, v_b;  // link a's and b's angular velocities, link b's velocity at Q
  Vector6 dV;
};

LoopMotion loop_motion(const Model& model, const LoopJoint& loop, const std::vector<Transform>& X0,
                       const std::vector<Vector6>& v) {
  // A link of -1 is the fixed root: the base frame, at rest.
  const auto state = [&](int link, const Vector3& point) {
    if (link >= 0) return link_state(model, X0, v, link, point);
    TipState s;
    s.pose.p = point;
    return s;
  };
  const TipState a = state(loop.link_a, loop.frame_a.p), b = state(loop.link_b, loop.frame_b.p);
  LoopMotion m;
  m.A = Transform{a.pose.R * loop.frame_a.R, a.pose.p};
  m.B = Transform{b.pose.R * loop.frame_b.R, b.pose.p};
  m.w_a = a.w;
  m.w_b = b.w;
  m.v_b = b.v;
  const Vector3 v_a_at_q = a.v + a.w.cross(m.B.p - m.A.p);
  m.dV << v_a_at_q - b.v, a.w - b.w;
  return m;
}

// e_k of every direction (x y z rx ry rz), as loop_errors states.
Vector6 closure_error(const LoopJoint& loop, const LoopMotion& m) {
  Vector6 e;
  e.head<3>() = m.A.R.transpose() * (m.A.p - m.B.p);
  if ((loop.directions >> 5) & 1u) {
    const Eigen::AngleAxisd turn(m.B.R.transpose() * m.A.R);
    e.tail<3>() = turn.angle() * turn.axis();
  } else {
    e.tail<3>() = m.A.R.transpose() * m.B.R.col(2).cross(m.A.R.col(2));
  }
  return e;
}

}  // namespace

void loop_errors(const Model& model, const LoopJoint& loop, const std::vector<Transform>& X0,
                 const std::vector<Vector6>& v, double* e, double* g) {
  const LoopMotion m = loop_motion(model, loop, X0, v);
  const Vector6 all = closure_error(loop, m);
  for (int k = 0, j = 0; k < kNumDirections; ++k) {
    if (!((loop.directions >> k) & 1u)) continue;
    const Vector3 c = m.A.R.col(k % 3);
    e[j] = all[k];
    g[j++] = c.dot(m.dV.segment<3>(k < 3 ? 0 : 3));
  }
}

double loop_error(const Model& model, const LoopJoint& loop, const std::vector<Transform>& X0,
                  const std::vector<Vector6>& v) {
  double e[kNumDirections], g[kNumDirections], worst = 0;
  loop_errors(model, loop, X0, v, e, g);
  for (int j = 0; j < loop.num_columns(); ++j) worst = std::max(worst, std::abs(e[j]));
  return worst;
}

void loop_targets(const Model& model, const std::vector<Transform>& X0, const std::vector<Vector6>& v,
                  double w_n, double zeta, bool velocity_products, Eigen::VectorXd& beta) {
  int column = 0;
  for (const LoopJoint& loop : model.loops) {
    const LoopMotion m = loop_motion(model, loop, X0, v);
    const Vector6 e = closure_error(loop, m);
    for (int k = 0; k < kNumDirections; ++k) {
      if (!((loop.directions >> k) & 1u)) continue;
      const Vector3 c = m.A.R.col(k % 3);
      const bool linear = k < 3;
      const Vector3 dv = m.dV.segment<3>(linear ? 0 : 3);
      double b = -2 * zeta * w_n * c.dot(dv) - w_n * w_n * e[k];
      if (velocity_products) {
        b -= m.w_a.cross(c).dot(dv);
        if (linear) b -= c.dot((m.w_a - m.w_b).cross(m.v_b));
      }
      beta[column++] = b;
    }
  }
}

}  // namespace achd
