// The 48 signed orders of the axes (rotations and reflections) as row-major 3x3 matrices: the
// rotations of axis-aligned members (beam.hpp, AxisMap), for the kernel's element tests.
#pragma once

#include <array>
#include <cstddef>

namespace ntn_test {

// Order `which % 6` of x, y, z, row k negated where bit k of `which / 6` is set; entry e of the
// zeros is zero(e) (+0.0 or -0.0).
template <class Zero>
std::array<double, 9> signed_order(std::size_t which, Zero zero) {
  constexpr std::size_t kOrders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                         {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::array<double, 9> r{};
  for (std::size_t e = 0; e < 9; ++e)
    r[e] = zero(e);
  for (std::size_t k = 0; k < 3; ++k)
    r[3 * k + kOrders[which % 6][k]] = ((which / 6) >> k) % 2 == 0 ? 1.0 : -1.0;
  return r;
}

}  // namespace ntn_test
