#pragma once
// The model's loop joints (Model::loops) as relative constraint blocks at a q, held by
// every solve after the case's own blocks (solve_blocks.hpp).
#include "achd/case.hpp"
#include "achd/data.hpp"

namespace achd {

// One block per loop into d.workspace.loop_blocks, where it acts into loop_placements
// (allocates nothing: the Data was made for the model): for loop l and each held
// direction k of its loop frame, the column
// [e; 0] (x y z) or [0; e] (rx ry rz), e the frame's axis k in base axes at q, on link a at
// the point where frame b's origin is and on link b at frame b's origin:
//   e^T (a_A(Q) - a_B(Q)) = beta.
// A loop with the root of a fixed base as one of its links becomes a block on the other
// link alone (the root does not move). Reads the body poses at q from d.X0 (the solve's,
// which hybrid_dynamics computed first). beta is the case's (set_loop_betas).
void set_loop_blocks(const Model& model, Data& d);

// The loop blocks' beta from c.loop_beta (one per loop column, the loops in order; 0 when
// empty).
void set_loop_betas(const Case& c, Data& d);

}  // namespace achd
