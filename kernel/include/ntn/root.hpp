// Roots without libm (the step calls none).
#pragma once

#include <bit>
#include <cstdint>

namespace ntn {

// sqrt(x) for finite x >= 0: Newton's iteration from half the exponent, arithmetic only, so the
// same bits on every build (within an ulp of the rounded root).
inline double root(double x) {
  if (!(x > 0)) return 0.0;
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto exponent = static_cast<std::int64_t>((bits >> 52) & 0x7ff) - 1023;
  double y = std::bit_cast<double>(static_cast<std::uint64_t>(exponent / 2 + 1023) << 52);
  for (int i = 0; i < 8; ++i)
    y = 0.5 * (y + x / y);
  return y;
}

}  // namespace ntn
