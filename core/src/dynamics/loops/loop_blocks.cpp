// The loop joints' blocks at a q (loop_blocks.hpp).
#include "loop_blocks.hpp"

namespace achd {

void set_loop_blocks(const Model& model, Data& d) {
  for (size_t b = 0; b < model.loops.size(); ++b) {
    const LoopJoint& loop = model.loops[b];
    ConstraintBlock& block = d.workspace.loop_blocks[b];
    ConstraintSource& place = d.workspace.loop_placements[b];
    // the loop frame's axes at link a, base axes (a frame fixed to its body's axes, the
    // spherical loops of a parallel robot, takes them as they are)
    const Matrix3& turn_a = loop.body_frame_a.R;
    const bool turned = !turn_a.isIdentity(0);
    const Matrix3 axes = loop.body_a < 0 ? turn_a
                         : turned        ? Matrix3(d.X0[loop.body_a].R * turn_a)
                                         : d.X0[loop.body_a].R;
    block.alpha.setZero();
    for (int k = 0, j = 0; k < kNumDirections; ++k)
      if ((loop.directions >> k) & 1u) block.alpha.col(j++).segment<3>(k < 3 ? 0 : 3) = axes.col(k % 3);
    // frame b's origin Q: from body b's origin (arm_b) and from the base's, base axes
    const Vector3& in_b = loop.body_frame_b.p;
    const Vector3 arm_b = loop.body_b < 0 ? in_b : Vector3(d.X0[loop.body_b].R * in_b);
    const Vector3 q_base = loop.body_b < 0 ? arm_b : Vector3(d.X0[loop.body_b].p + arm_b);
    if (loop.link_a < 0) {
      // a_A = 0: -e^T a_B(Q) = beta, a block on link b alone
      place.body = loop.body_b;
      place.arm = arm_b;
      place.relative = false;
      block.alpha = -block.alpha;
      block.link = loop.link_b;
      block.point = loop.frame_b.p;
      block.link_b = -1;
    } else {
      place.body = loop.body_a;
      place.arm = loop.body_a < 0 ? q_base : Vector3(q_base - d.X0[loop.body_a].p);
      place.relative = loop.link_b >= 0;
      place.body_b = loop.body_b;
      place.arm_b = arm_b;
      // the same block as a Case::constraints block would give it: Q in link a's frame
      const Link& a = model.links[loop.link_a];
      const Vector3 in_body = a.body < 0 ? place.arm : Vector3(d.X0[a.body].R.transpose() * place.arm);
      block.link = loop.link_a;
      block.point = a.offset.R.transpose() * (in_body - a.offset.p);
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
