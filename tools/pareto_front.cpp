// Pareto front by direct comparison of every pair (a study has tens of points).
#include "pareto_front.hpp"

namespace achd::cli {

std::vector<bool> pareto_front(const std::vector<CostError>& points) {
  std::vector<bool> on_front(points.size(), true);
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::size_t q = 0; q < points.size() && on_front[p]; ++q) {
      const CostError &a = points[p], &b = points[q];
      const bool no_worse = b.cost <= a.cost && b.error <= a.error;
      const bool better = b.cost < a.cost || b.error < a.error;
      if (q != p && no_worse && better) on_front[p] = false;
    }
  return on_front;
}

}  // namespace achd::cli
