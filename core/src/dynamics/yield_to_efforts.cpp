#include "yield_to_efforts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "constraint_sweep.hpp"
#include "coupling_solve.hpp"

namespace achd {

std::uint64_t yielding_columns(const Case& c) {
  // in nu's order: the tip's columns (none yield), then each block's
  std::uint64_t mask = 0;
  int column = static_cast<int>(c.alpha.cols());
  for (const ConstraintBlock& b : c.constraints) {
    mask |= static_cast<std::uint64_t>(b.yields & ((1u << b.alpha.cols()) - 1)) << column;
    column += static_cast<int>(b.alpha.cols());
  }
  return mask;
}

void yield_to_efforts(const Model& model, Data& d, const Case& c, const Options& options) {
  d.effort_ratio = 0;
  d.yielded = 0;
  // Coupled joints superpose several solves (joint_couplings.hpp), which a nonlinear
  // yield inside each would break: their columns are followed as asked.
  if (!model.couplings.empty()) return;
  const std::uint64_t mask = d.workspace.yielding;
  if (!mask) return;
  bool yielding[kMaxConstraintColumns] = {false};
  for (int j = 0; j < kMaxConstraintColumns; ++j) yielding[j] = mask >> j & 1u;
  constraint_force_torques(model, d, c, d.nu);
  const bool prescribed = c.any_prescribed();
  double r = 0;
  for (int i = model.free_joint_rates(); i < model.num_rates(); ++i) {
    const double effort = model.bodies[i].limits.effort;
    if (!(effort > 0) || (prescribed && c.prescribed[i])) continue;
    const double ratio = std::abs(d.joint_torques[i]) / effort;
    r = std::max(r, std::isnan(ratio) ? INFINITY : ratio);  // (a push beyond a double's range: NaN torques)
  }
  // (a denormal effort limit makes the ratio overflow: reported as the largest double)
  d.effort_ratio = std::min(r, std::numeric_limits<double>::max());
  if (!(r > 1)) return;
  const double x = std::min(r - 1, 1.0), s = x * x * (3 - 2 * x);
  ConstraintVector given_up;
  solve_coupling_without(d, options, yielding, given_up);
  // nu + s (nu_w - nu), nu_w itself where wholly given up (the followed nu may not be finite)
  if (s == 1) d.nu = given_up;
  else d.nu += s * (given_up - d.nu);
  d.yielded = s;
}

}  // namespace achd
