#pragma once
// The Pareto front of (cost, error) points: the points that no other point beats in
// both, i.e. p is on the front unless some q has cost_q <= cost_p and error_q <= error_p
// with at least one of them strictly smaller.
#include <vector>

namespace achd::cli {

struct CostError {
  double cost, error;
};

// on_front[i] is true when point i is on the front.
std::vector<bool> pareto_front(const std::vector<CostError>& points);

}  // namespace achd::cli
