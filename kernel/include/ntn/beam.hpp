// Two-node 3D frame element: local frame, stiffness, HRZ lumped mass, internal force (DESIGN §4).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "ntn/model_spec.hpp"

namespace ntn {

enum class ElementCheck : std::uint8_t { kOk, kZeroLength, kOrientationParallel, kBadProperty };

// Stiffness constants of one element in its local frame (Euler-Bernoulli, Timoshenko with
// Phi = 12 E I / (G A_s l^2)). Bending entries a..d of one plane: a = 12EI/(l^3(1+Phi)),
// b = 6EI/(l^2(1+Phi)), c = (4+Phi)EI/(l(1+Phi)), d = (2-Phi)EI/(l(1+Phi)).
struct BeamStiffness {
  double axial = 0;            // N/m, EA/l
  double torsion = 0;          // N m, GJ/l
  std::array<double, 4> xy{};  // plane x-y: v along y, rotation about z (uses Iz)
  std::array<double, 4> xz{};  // plane x-z: w along z, rotation about y (uses Iy)
};

// An element whose local axes lie along global axes (a member along x, y or z with its
// orientation along another: most members of a building frame) has a rotation whose rows are
// signed unit vectors: local component k is global component axis(k), negated or not. Such an
// element rotates by picking components, with no product and no sum (kernel/README). AxisMap codes
// it: 0 for any other rotation; else bit 15 set, bits 2k..2k+1 the global axis of local axis k and
// bit 6 + k set when it is negated. The code is part of the arithmetic (a picked component keeps
// its sign of zero where the full product would add +0.0), so both element passes read it from the
// model, never from a threshold of their own.
using AxisMap = std::uint16_t;
inline constexpr AxisMap kGeneralAxes = 0;
inline constexpr AxisMap kAlignedAxes = 0x8000;

constexpr std::size_t axis_of(AxisMap m, std::size_t k) {
  return (static_cast<unsigned>(m) >> (2 * k)) & 3U;
}
constexpr bool axis_negated(AxisMap m, std::size_t k) {
  return ((static_cast<unsigned>(m) >> (6 + k)) & 1U) != 0;
}
// Bit k set where local axis k is negated (axis_negated), for all three axes at once.
constexpr unsigned negated_axes(AxisMap m) {
  return (static_cast<unsigned>(m) >> 6) & 7U;
}
// The AxisMap of local x, y along global a0, a1 (z along the third), negated where bit k of
// `negated` is set (negated_axes).
constexpr AxisMap aligned_axes(std::size_t a0, std::size_t a1, unsigned negated) {
  return static_cast<AxisMap>(kAlignedAxes | a0 | (a1 << 2) | ((3 - a0 - a1) << 4) |
                              ((negated & 7U) << 6));
}
// An aligned map whose determinant is +1 (a rotation, not a mirror image): an odd permutation of
// the axes (one axis in place) with an odd number of them negated, or an even one with an even
// number. beam_geometry's frames (y = z x x) are all right-handed.
constexpr bool right_handed(AxisMap m) {
  const std::size_t a0 = axis_of(m, 0), a1 = axis_of(m, 1), a2 = axis_of(m, 2);
  const bool odd_order = (a0 == 0) + (a1 == 1) + (a2 == 2) == 1;
  const unsigned n = negated_axes(m);
  const bool odd_signs = ((n ^ (n >> 1) ^ (n >> 2)) & 1U) != 0;
  return odd_order == odd_signs;
}

// The AxisMap of a rotation: aligned when each row has one entry +1 or -1 and zeros (of either
// sign) elsewhere, exactly.
inline AxisMap axis_map(const std::array<double, 9>& R) {
  unsigned code = kAlignedAxes, seen = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    std::size_t unit = 3;
    for (std::size_t c = 0; c < 3; ++c) {
      const double r = R[3 * k + c];
      if (r == 1.0 || r == -1.0) {
        if (unit != 3) return kGeneralAxes;
        unit = c;
      } else if (r != 0.0) {
        return kGeneralAxes;
      }
    }
    if (unit == 3 || (seen & (1U << unit)) != 0) return kGeneralAxes;
    seen |= 1U << unit;
    code |= static_cast<unsigned>(unit) << (2 * k);
    if (R[3 * k + unit] < 0) code |= 1U << (6 + k);
  }
  return static_cast<AxisMap>(code);
}

// What step() needs of an element: its nodes, rotation (rows: local x, y, z in global), its
// AxisMap and stiffness constants. The force is applied on the fly from these.
struct BeamData {
  std::int32_t node_i = 0, node_j = 0;
  std::array<double, 9> rotation{};  // row-major 3x3, local = rotation * global
  BeamStiffness k;
  AxisMap axes = kGeneralAxes;  // axis_map(rotation), or kGeneralAxes: the full products
};

struct BeamGeometry {
  double length = 0;                 // m
  std::array<double, 9> rotation{};  // as in BeamData
  ElementCheck check = ElementCheck::kOk;
};

inline BeamGeometry beam_geometry(const NodeSpec& a, const NodeSpec& b, const ElementSpec& e) {
  BeamGeometry g;
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  g.length = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(g.length > 0)) {
    g.check = ElementCheck::kZeroLength;
    return g;
  }
  const double ex[3] = {dx / g.length, dy / g.length, dz / g.length};
  // local z: the orientation vector with its component along x removed (DESIGN §3).
  const double rx = e.ref_x, ry = e.ref_y, rz = e.ref_z;
  const double rn = std::sqrt(rx * rx + ry * ry + rz * rz);
  const double along = rx * ex[0] + ry * ex[1] + rz * ex[2];
  double ez[3] = {rx - along * ex[0], ry - along * ex[1], rz - along * ex[2]};
  const double zn = std::sqrt(ez[0] * ez[0] + ez[1] * ez[1] + ez[2] * ez[2]);
  if (!(rn > 0) || !(zn > 1e-6 * rn)) {
    g.check = ElementCheck::kOrientationParallel;
    return g;
  }
  for (double& c : ez)
    c /= zn;
  const double ey[3] = {ez[1] * ex[2] - ez[2] * ex[1], ez[2] * ex[0] - ez[0] * ex[2],
                        ez[0] * ex[1] - ez[1] * ex[0]};  // y = z x x
  g.rotation = {ex[0], ex[1], ex[2], ey[0], ey[1], ey[2], ez[0], ez[1], ez[2]};
  return g;
}

inline std::array<double, 4> bending_terms(double E, double I, double G, double shear_area,
                                           double l) {
  const double phi = shear_area > 0 ? 12.0 * E * I / (G * shear_area * l * l) : 0.0;
  const double s = 1.0 / (1.0 + phi);
  return {12.0 * E * I / (l * l * l) * s, 6.0 * E * I / (l * l) * s, (4.0 + phi) * E * I / l * s,
          (2.0 - phi) * E * I / l * s};
}

// A leaning column (Geometry::kLeaning) has the axial stiffness alone: no bending, no torsion.
inline BeamStiffness beam_stiffness(const ElementSpec& e, double l) {
  BeamStiffness k;
  k.axial = e.E * e.A / l;
  if (e.geometry == Geometry::kLeaning) return k;
  k.torsion = e.G * e.J / l;
  k.xy = bending_terms(e.E, e.Iz, e.G, e.shear_area_y, l);
  k.xz = bending_terms(e.E, e.Iy, e.G, e.shear_area_z, l);
  return k;
}

// A leaning column needs E, rho and A alone (its G, I and J may be 0).
inline bool beam_properties_valid(const ElementSpec& e) {
  if (e.geometry == Geometry::kLeaning)
    return e.E > 0 && e.rho > 0 && e.A > 0 && e.G >= 0 && e.Iy >= 0 && e.Iz >= 0 && e.J >= 0;
  return e.E > 0 && e.G > 0 && e.rho > 0 && e.A > 0 && e.Iy > 0 && e.Iz > 0 && e.J > 0 &&
         e.shear_area_y >= 0 && e.shear_area_z >= 0;
}

// Local 12x12 stiffness, DOF order [u_i, theta_i, u_j, theta_j] in local axes. Row-major.
using Matrix12 = std::array<double, 144>;

inline Matrix12 beam_local_stiffness(const BeamStiffness& k) {
  Matrix12 K{};
  auto set = [&K](int r, int c, double v) {
    K[static_cast<std::size_t>(r * 12 + c)] = v;
    K[static_cast<std::size_t>(c * 12 + r)] = v;
  };
  set(0, 0, k.axial), set(0, 6, -k.axial), set(6, 6, k.axial);
  set(3, 3, k.torsion), set(3, 9, -k.torsion), set(9, 9, k.torsion);
  const auto& p = k.xy;  // v: 1, 7; theta_z: 5, 11
  set(1, 1, p[0]), set(1, 5, p[1]), set(1, 7, -p[0]), set(1, 11, p[1]);
  set(5, 5, p[2]), set(5, 7, -p[1]), set(5, 11, p[3]);
  set(7, 7, p[0]), set(7, 11, -p[1]), set(11, 11, p[2]);
  const auto& q = k.xz;  // w: 2, 8; theta_y: 4, 10
  set(2, 2, q[0]), set(2, 4, -q[1]), set(2, 8, -q[0]), set(2, 10, -q[1]);
  set(4, 4, q[2]), set(4, 8, q[1]), set(4, 10, q[3]);
  set(8, 8, q[0]), set(8, 10, q[1]), set(10, 10, q[2]);
  return K;
}

// A local 12x12 matrix in global axes, T^T K_L T with T = diag(R, R, R, R). Row-major.
inline Matrix12 to_global_axes(const Matrix12& KL, const std::array<double, 9>& R) {
  Matrix12 KT{}, K{};
  for (int r = 0; r < 12; ++r) {  // KT = KL T
    for (int blk = 0; blk < 4; ++blk) {
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        for (int m = 0; m < 3; ++m) {
          s += KL[static_cast<std::size_t>(r * 12 + blk * 3 + m)] *
               R[static_cast<std::size_t>(m * 3 + c)];
        }
        KT[static_cast<std::size_t>(r * 12 + blk * 3 + c)] = s;
      }
    }
  }
  for (int blk = 0; blk < 4; ++blk) {  // K = T^T KT
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 12; ++c) {
        double s = 0;
        for (int m = 0; m < 3; ++m) {
          s += R[static_cast<std::size_t>(m * 3 + r)] *
               KT[static_cast<std::size_t>((blk * 3 + m) * 12 + c)];
        }
        K[static_cast<std::size_t>((blk * 3 + r) * 12 + c)] = s;
      }
    }
  }
  return K;
}

// Global 12x12 stiffness T^T K_L T, T = diag(R, R, R, R). Row-major.
inline Matrix12 beam_global_stiffness(const BeamData& b) {
  return to_global_axes(beam_local_stiffness(b.k), b.rotation);
}

// HRZ lumped mass of one element end, in global axes (DESIGN §4): translations rho A l / 2;
// rotations diag(rho I_p l/2, rho A l^3/78 [+ rho Iy l/2], rho A l^3/78 [+ rho Iz l/2]) in local
// axes, taken to global as the diagonal of R^T D R (keeps the trace; exact for aligned members).
inline std::array<double, kDofsPerNode> beam_end_mass(const ElementSpec& e, const BeamGeometry& g,
                                                      bool rotary_inertia) {
  const double l = g.length;
  const double mt = e.rho * e.A * l / 2.0;
  const double bend = e.rho * e.A * l * l * l / 78.0;
  const double d[3] = {e.rho * (e.Iy + e.Iz) * l / 2.0,
                       bend + (rotary_inertia ? e.rho * e.Iy * l / 2.0 : 0.0),
                       bend + (rotary_inertia ? e.rho * e.Iz * l / 2.0 : 0.0)};
  std::array<double, kDofsPerNode> m{mt, mt, mt, 0, 0, 0};
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 3; ++k) {
      const double r = g.rotation[static_cast<std::size_t>(k * 3 + c)];
      m[static_cast<std::size_t>(3 + c)] += r * r * d[k];
    }
  }
  return m;
}

// Local end forces K_L d of one element: d and f in local axes [u_i, theta_i, u_j, theta_j].
inline void beam_local_force(const BeamStiffness& k, const double* d, double* f) {
  const double n = k.axial * (d[6] - d[0]);
  const double t = k.torsion * (d[9] - d[3]);
  f[0] = -n, f[6] = n, f[3] = -t, f[9] = t;
  const auto& p = k.xy;  // plane x-y
  const double dv = d[1] - d[7];
  f[1] = p[0] * dv + p[1] * (d[5] + d[11]);
  f[7] = -f[1];
  f[5] = p[1] * dv + p[2] * d[5] + p[3] * d[11];
  f[11] = p[1] * dv + p[3] * d[5] + p[2] * d[11];
  const auto& q = k.xz;  // plane x-z
  const double dw = d[2] - d[8];
  f[2] = q[0] * dw - q[1] * (d[4] + d[10]);
  f[8] = -f[2];
  f[4] = -q[1] * dw + q[2] * d[4] + q[3] * d[10];
  f[10] = -q[1] * dw + q[3] * d[4] + q[2] * d[10];
}

inline void rotate_to_local(const std::array<double, 9>& R, const double* g, double* l) {
  l[0] = R[0] * g[0] + R[1] * g[1] + R[2] * g[2];
  l[1] = R[3] * g[0] + R[4] * g[1] + R[5] * g[2];
  l[2] = R[6] * g[0] + R[7] * g[1] + R[8] * g[2];
}

inline void rotate_to_global(const std::array<double, 9>& R, const double* l, double* g) {
  g[0] = R[0] * l[0] + R[3] * l[1] + R[6] * l[2];
  g[1] = R[1] * l[0] + R[4] * l[1] + R[7] * l[2];
  g[2] = R[2] * l[0] + R[5] * l[1] + R[8] * l[2];
}

// x or -x: a sign flip, exact for every x (the SIMD pass flips the same bit).
constexpr double flip(double x, bool negated) {
  return negated ? -x : x;
}

// rotate_to_local / rotate_to_global of an element: by picking components where its axes are
// aligned (m != kGeneralAxes), else by the full products.
inline void beam_to_local(AxisMap m, const std::array<double, 9>& R, const double* g, double* l) {
  if (m == kGeneralAxes) {
    rotate_to_local(R, g, l);
    return;
  }
  for (std::size_t k = 0; k < 3; ++k)
    l[k] = flip(g[axis_of(m, k)], axis_negated(m, k));
}

inline void beam_to_global(AxisMap m, const std::array<double, 9>& R, const double* l, double* g) {
  if (m == kGeneralAxes) {
    rotate_to_global(R, l, g);
    return;
  }
  for (std::size_t k = 0; k < 3; ++k)
    g[axis_of(m, k)] = flip(l[k], axis_negated(m, k));
}

// Local displacements of one element from its nodes' global DOFs.
inline void beam_local_displacements(const BeamData& b, const double* ui, const double* uj,
                                     double* d) {
  beam_to_local(b.axes, b.rotation, ui, d), beam_to_local(b.axes, b.rotation, ui + 3, d + 3);
  beam_to_local(b.axes, b.rotation, uj, d + 6), beam_to_local(b.axes, b.rotation, uj + 3, d + 9);
}

// Internal force of one element on its two nodes, in global axes: f = T^T K_L T u (DESIGN §4),
// applied on the fly. Fixed operation order: it is part of the result.
inline void beam_force(const BeamData& b, const double* ui, const double* uj, double* fi,
                       double* fj) {
  double d[12], f[12];
  beam_local_displacements(b, ui, uj, d);
  beam_local_force(b.k, d, f);
  beam_to_global(b.axes, b.rotation, f, fi), beam_to_global(b.axes, b.rotation, f + 3, fi + 3);
  beam_to_global(b.axes, b.rotation, f + 6, fj), beam_to_global(b.axes, b.rotation, f + 9, fj + 3);
}

// End forces of one element in its local axes [N, Vy, Vz, T, My, Mz] at node i then node j:
// the forces the nodes exert on the element, K_L T u (tension positive as -N at node i).
inline std::array<double, 12> beam_local_end_forces(const BeamData& b, const double* ui,
                                                    const double* uj) {
  double d[12];
  std::array<double, 12> f{};
  beam_local_displacements(b, ui, uj, d);
  beam_local_force(b.k, d, f.data());
  return f;
}

}  // namespace ntn
