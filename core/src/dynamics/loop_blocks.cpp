// The loop joints' blocks at a case's q (loop_blocks.hpp).
#include "loop_blocks.hpp"

#include "achd/kinematics.hpp"

namespace achd {

const Case& case_with_loops(const Model& model, const Case& c, Data& d) {
  Case& out = d.workspace.loop_case;
  out = c;
  body_poses(model, c.q, d.X0, d.r);  // the solve's: it does not compute them again
  const auto link_pose = [&](int link) {
    if (link < 0) return Transform{};
    const Link& l = model.links[link];
    return l.body < 0 ? l.offset : d.X0[l.body] * l.offset;
  };
  int column = 0;
  for (const LoopJoint& loop : model.loops) {
    const Transform A = link_pose(loop.link_a), B = link_pose(loop.link_b);
    const Matrix3 axes = A.R * loop.frame_a.R;  // the loop frame at link a, base axes
    ConstraintBlock block;
    block.alpha.resize(6, loop.num_columns());
    block.alpha.setZero();
    block.beta.resize(loop.num_columns());
    for (int k = 0, j = 0; k < kNumDirections; ++k) {
      if (!((loop.directions >> k) & 1u)) continue;
      block.alpha.col(j).segment<3>(k < 3 ? 0 : 3) = axes.col(k % 3);
      block.beta[j++] = c.loop_beta.size() ? c.loop_beta[column] : 0.0;
      ++column;
    }
    const Vector3 q_base = B.p + B.R * loop.frame_b.p;  // frame b's origin, base frame
    if (loop.link_a < 0) {
      // a_A = 0: -e^T a_B(Q) = beta, a block on link b alone
      block.link = loop.link_b;
      block.point = loop.frame_b.p;
      block.alpha = -block.alpha;
    } else {
      block.link = loop.link_a;
      block.point = A.R.transpose() * (q_base - A.p);
      block.link_b = loop.link_b;
      if (loop.link_b >= 0) block.point_b = loop.frame_b.p;
    }
    out.constraints.push_back(block);
  }
  return out;
}

}  // namespace achd
