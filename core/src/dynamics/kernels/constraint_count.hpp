#pragma once
// Dispatch on the number of constraint columns of a block: calls
// f(std::integral_constant<int, nc>{}) for nc = 1 .. kMaxConstraints, so that code
// templated on nc unrolls its loops over the constraint columns.
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

// The same for the size m of the coupling matrix (all blocks' columns, up to
// kMaxConstraintColumns): m = 1 .. kMaxConstraints as above, larger m as
// std::integral_constant<int, 0> (code templated on it takes the size at run time).
template <typename F>
decltype(auto) with_coupling_size(int m, F&& f) {
  if (m > kMaxConstraints) return f(std::integral_constant<int, 0>{});
  return with_constraint_count(m, f);
}

}  // namespace achd
