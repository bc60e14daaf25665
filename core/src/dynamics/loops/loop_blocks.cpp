// The loop joints' blocks at a q (loop_blocks.hpp).
#include "loop_blocks.hpp"

namespace achd {

void set_loop_blocks(const Model& model, Data& d) {
  const auto link_pose = [&](int link) {
    if (link < 0) return Transform{};
    const Link& l = model.links[link];
    return l.body < 0 ? l.offset : d.X0[l.body] * l.offset;
  };
  for (size_t b = 0; b < model.loops.size(); ++b) {
    const LoopJoint& loop = model.loops[b];
    ConstraintBlock& block = d.workspace.loop_blocks[b];
    const Transform A = link_pose(loop.link_a), B = link_pose(loop.link_b);
    const Matrix3 axes = A.R * loop.frame_a.R;  // the loop frame at link a, base axes
    block.alpha.setZero();
    for (int k = 0, j = 0; k < kNumDirections; ++k)
      if ((loop.directions >> k) & 1u) block.alpha.col(j++).segment<3>(k < 3 ? 0 : 3) = axes.col(k % 3);
    const Vector3 q_base = B.p + B.R * loop.frame_b.p;  // frame b's origin, base frame
    if (loop.link_a < 0) {
      // a_A = 0: -e^T a_B(Q) = beta, a block on link b alone
      block.link = loop.link_b;
      block.point = loop.frame_b.p;
      block.link_b = -1;
      block.alpha = -block.alpha;
    } else {
      block.link = loop.link_a;
      block.point = A.R.transpose() * (q_base - A.p);
      block.link_b = loop.link_b;
      if (loop.link_b >= 0) block.point_b = loop.frame_b.p;
    }
  }
}

void set_loop_betas(const Case& c, Data& d) {
  int column = 0;
  for (ConstraintBlock& block : d.workspace.loop_blocks)
    for (int j = 0; j < block.beta.size(); ++j, ++column) block.beta[j] = c.loop_beta.size() ? c.loop_beta[column] : 0.0;
}

}  // namespace achd
