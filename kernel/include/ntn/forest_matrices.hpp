// The constraint forest's 6x6 matrices in Eigen form (init time): what build_forest
// (kernel/src/constraint_forest.cpp) and modal analysis (tools/modal) compute the forest's
// constant matrices with. The step never sees Eigen: it reads the Mat6 and Diag6 of
// constraint_forest.hpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>

#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"

namespace ntn {

namespace detail {

using M6 = Eigen::Matrix<double, 6, 6>;

inline Mat6 to_mat6(const M6& m) {
  Mat6 r;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const double x = m(i, j);
      r.a[static_cast<std::size_t>(6 * i + j)] = x;
      if (x != 0.0) r.blocks |= static_cast<std::uint8_t>(1U << (2 * (i / 3) + j / 3));
    }
  }
  return r;
}

inline M6 to_m6(const Mat6& m) {
  M6 r;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j)
      r(i, j) = m.a[static_cast<std::size_t>(6 * i + j)];
  }
  return r;
}

inline M6 frame6(const HingeData& h) {
  M6 t = M6::Zero();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      t(r, c) = t(r + 3, c + 3) = h.frame[static_cast<std::size_t>(3 * r + c)];
    }
  }
  return t;
}

// X = [I E; 0 I] with E phi = phi x e: the motion of a rigid link at a point offset by e.
inline M6 link(const std::array<double, 3>& e, double sign) {
  M6 x = M6::Identity();
  const double ex = sign * e[0], ey = sign * e[1], ez = sign * e[2];
  // phi x e = (phi_y e_z - phi_z e_y, phi_z e_x - phi_x e_z, phi_x e_y - phi_y e_x)
  x(0, 4) = ez, x(0, 5) = -ey;
  x(1, 3) = -ez, x(1, 5) = ex;
  x(2, 3) = ey, x(2, 4) = -ex;
  return x;
}

inline M6 own_mass(std::span<const double> mass, int node) {
  M6 m = M6::Zero();
  for (int d = 0; d < 6; ++d)
    m(d, d) = mass[static_cast<std::size_t>(6 * node + d)];
  return m;
}

}  // namespace detail

}  // namespace ntn
