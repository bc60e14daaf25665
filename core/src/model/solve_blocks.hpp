#pragma once
// The blocks of constraint columns a solve holds after the tip's: the case's own
// (Case::constraints), then one per loop joint (Data::Workspace::loop_blocks, set at the
// solve's q). ConstraintSource::block and Data::constraint_wrenches count them in that order.
#include "achd/case.hpp"
#include "achd/data.hpp"

namespace achd {

inline int num_solve_blocks(const Case& c, const Data& d) {
  return static_cast<int>(c.constraints.size() + d.workspace.loop_blocks.size());
}

// The columns of all of them with the tip's: the rows of nu.
inline int num_solve_columns(const Case& c, const Data& d) {
  int n = c.num_constraints();
  for (const ConstraintBlock& b : d.workspace.loop_blocks) n += static_cast<int>(b.alpha.cols());
  return n;
}

// Block b of the solve: the case's b-th, or after them loop b - (the case's blocks).
inline const ConstraintBlock& solve_block(const Case& c, const Data& d, int b) {
  const int own = static_cast<int>(c.constraints.size());
  return b < own ? c.constraints[b] : d.workspace.loop_blocks[b - own];
}

}  // namespace achd
