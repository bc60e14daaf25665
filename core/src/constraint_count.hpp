#pragma once
// Dispatch on the number of constraints: calls f(std::integral_constant<int, nc>{}) for
// nc = 1 .. kMaxConstraints, so that code templated on nc unrolls its loops over the
// constraint columns.
#include <type_traits>

#include "achd/case.hpp"

namespace achd {

template <typename F>
decltype(auto) with_constraint_count(int nc, F&& f) {
  static_assert(kMaxConstraints == 6, "with_constraint_count dispatches nc = 1..6");
  switch (nc) {
    case 1: return f(std::integral_constant<int, 1>{});
    case 2: return f(std::integral_constant<int, 2>{});
    case 3: return f(std::integral_constant<int, 3>{});
    case 4: return f(std::integral_constant<int, 4>{});
    case 5: return f(std::integral_constant<int, 5>{});
    default: return f(std::integral_constant<int, 6>{});
  }
}

}  // namespace achd
