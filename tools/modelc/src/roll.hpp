// The one rule for `roll` (members' roll, mesh_members.cpp; hinge axes = { member, roll },
// hinges_supports.cpp): a right-handed turn by `deg` degrees about a frame's local x, which
// takes its y and z axes to
//     y' = cos(roll) y + sin(roll) z,    z' = cos(roll) z - sin(roll) y.
// A roll of 0 leaves both exactly as they are (cos and sin are not evaluated).
#pragma once

#include <array>
#include <cmath>
#include <numbers>

namespace ntn::modelc::compile {

// A roll is an angle of at most one turn either way: a larger one is a slip of units (radians
// times 180/pi twice, or a bad exponent), and cos and sin of 1e308 degrees are noise.
inline constexpr double kMaxRollDegrees = 360.0;
inline bool roll_in_range(double deg) {
  return std::fabs(deg) <= kMaxRollDegrees;
}

inline void roll_about_x(double deg, std::array<double, 3>& y, std::array<double, 3>& z) {
  if (deg == 0.0) return;
  const double th = deg * std::numbers::pi / 180.0;
  const double c = std::cos(th), s = std::sin(th);
  const std::array<double, 3> y0 = y, z0 = z;
  for (std::size_t i = 0; i < 3; ++i) {
    y[i] = c * y0[i] + s * z0[i];
    z[i] = c * z0[i] - s * y0[i];
  }
}

}  // namespace ntn::modelc::compile
