#pragma once
// The model's loop joints (Model::loops) as relative constraint blocks at a case's q, so
// that every solve holds them after the case's own blocks.
#include "achd/case.hpp"
#include "achd/data.hpp"

namespace achd {

// `c` with one block per loop appended, into d.workspace.loop_case (allocates nothing
// once the Data was made for the model): for loop l and each held direction k of its loop
// frame, the column [e; 0] (x y z) or [0; e] (rx ry rz), e the frame's axis k in base
// axes at c.q, on link a at the point where frame b's origin is and on link b at frame
// b's origin, with beta from c.loop_beta (0 when empty):
//   e^T (a_A(Q) - a_B(Q)) = beta.
// A loop with the root of a fixed base as one of its links becomes a block on the other
// link alone (the root does not move). The case must be validated. Leaves the body poses
// at c.q in d.X0 and d.r, where the solve that follows takes them.
const Case& case_with_loops(const Model& model, const Case& c, Data& d);

}  // namespace achd
