// Second-order geometry of an element's chord: P-Delta and leaning columns (DESIGN §4).
//
// An element with geometry "p_delta" (and every leaning column) measures its axial strain along
// the chord to second order in the relative translation d = R (u_j - u_i) = (du, dv, dw) in its
// local axes (the von Karman strain of a straight bar, e.g. Crisfield, Non-linear Finite Element
// Analysis of Solids and Structures, vol. 1, §3.2):
//     eps l = du + (dv^2 + dw^2) / (2 l),        N = k (du + s / (2 l)),  s = dv^2 + dw^2,
// k = E A / l. Its potential is the linear beam's with k du^2 / 2 replaced by k (eps l)^2 / 2, so
// the internal force is the linear pass's (beam.hpp) plus, on node j in local axes,
//     g = (k s / (2 l), N dv / l, N dw / l),                   and -g on node i,
// whose tangent is the geometric stiffness N / l [[1, -1], [-1, 1]] on the transverse
// translations (the P-Delta "string" of the axial force) plus k (dv / l, dw / l) terms of the
// chord's rotation. Gravity thus does work through the shortening of a swaying column, and the
// element is conservative: the energy books close with the elastic account alone.
//
// The step adds g after the element pass (the same bits for any team size: one pass in element
// order). A leaning column (Geometry::kLeaning) has the axial stiffness alone (beam_stiffness):
// the linear pass gives k du, this pass the rest. Two paths compute the pass, as the element
// pass's (element_pass.hpp): geometric_forces() element by element, the reference, and the SIMD
// one (kernel/src/element_pass.cpp), geometric_force's and beam_to_global's operations in the same
// order for kBeamLanes elements at a time (GeometricBlock, in the model's order), their g then
// added element by element in element order: the same bits.
//
// The stable step (time_step.hpp) is taken without axial forces. Compression lowers an element's
// frequencies; tension and the chord's rotation raise them. The tangent of k (eps l)^2 / 2 is
// k a a^T + N / l S (a = (1, dv / l, dw / l) on node j, -a on node i; S the string above), which
// exceeds the linear k e e^T by k (a a^T - e e^T), whose largest eigenvalue is
// k (phi^2 + phi sqrt(phi^2 + 4)) / 2 <= k (phi + phi^2), phi^2 = s / l^2 the chord's rotation
// squared. By the element eigenvalue theorem and Weyl's inequality on M_e^-1/2 K_e M_e^-1/2, with
// the end translations' lumped mass m = rho A l / 2,
//     omega_e^2(u) <= omega_e^2 + 2 (N+ + k l (phi + phi^2)) / (l m) = omega_e^2 + 4 Q / (rho A
//     l^2), Q = N+ + k l (phi + phi^2).
// With dt = dt_stable / r (r >= 1), every node's bound dt^2 omega_n^2 + 2 dt eta_n < 4 still holds
// when each element's omega_e^2 grows by at most the factor r (each node's terms then grow by at
// most r, and dt_n >= r dt makes dt^2 omega_n^2 + 2 dt eta_n <= 4 / r). So the run is stable while
//     Q <= Q_max = (r - 1) omega_e^2 rho A l^2 / 4     (geometric_force_limit),
// which the step checks for every element without a root: with Y = Q_max - N+ - k s / l, Q <= Q_max
// is Y >= 0 and k^2 s <= Y^2. An element past it is counted (State::geometry_bound,
// kFaultGeometryBound). For a step at 0.9 dt_stable, Q_max is about 0.1 E A: a strain of 10 %, or
// a chord rotation of 0.1 rad with no axial force.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ntn/beam.hpp"
#include "ntn/element_pass.hpp"

namespace ntn {

// One element with second-order geometry, as the step reads it.
struct GeometricElement {
  std::int32_t dof_i = 0, dof_j = 0;  // kDofsPerNode * node
  std::int32_t element = 0;           // its index in the model file (for the outputs)
  AxisMap axes = kGeneralAxes;        // axis_map(rotation)
  std::array<double, 9> rotation{};   // as BeamData::rotation
  double axial = 0;                   // N/m, k = E A / l
  double inv_length = 0;              // 1/m
  double limit = 0;                   // N, Q_max: Q above it breaks the stable step's bound
};

// Element `index` of a model (e, between nodes a and b) as the step reads it; its limit is set by
// init() from the stable step (geometric_force_limit).
inline GeometricElement geometric_element(const ElementSpec& e, std::int32_t index,
                                          const NodeSpec& a, const NodeSpec& b) {
  const BeamGeometry g = beam_geometry(a, b, e);
  GeometricElement ge;
  ge.dof_i = kDofsPerNode * e.node_i, ge.dof_j = kDofsPerNode * e.node_j;
  ge.element = index;
  ge.rotation = g.rotation;
  ge.axes = axis_map(g.rotation);
  ge.axial = e.E * e.A / g.length;
  ge.inv_length = 1.0 / g.length;
  return ge;
}

// The largest Q = N+ + k l (phi + phi^2) for which an element of top frequency omega_e (rad/s,
// without axial force), density rho, area A and length l keeps the step dt stable, dt_stable the
// model's stable step (the header's bound): 0 when dt is not below dt_stable.
inline double geometric_force_limit(double omega_e, double rho, double area, double length,
                                    double dt_stable, double dt) {
  if (!(dt > 0) || !(dt < dt_stable)) return 0;
  const double r = dt_stable / dt;
  return (r - 1.0) * omega_e * omega_e * rho * area * length * length / 4.0;
}

// What the second-order chord adds at u: g on node j in local axes (-g on node i), the axial
// force N (tension positive) and whether Q is above the element's limit.
struct GeometricForce {
  double g[3] = {};
  double normal = 0;  // N, N = k (du + s / (2 l))
  bool over = false;  // Q > GeometricElement::limit
};

inline GeometricForce geometric_force(const GeometricElement& e, const double* u) {
  const auto i = static_cast<std::size_t>(e.dof_i), j = static_cast<std::size_t>(e.dof_j);
  const double rel[3] = {u[j] - u[i], u[j + 1] - u[i + 1], u[j + 2] - u[i + 2]};
  double d[3];
  beam_to_local(e.axes, e.rotation, rel, d);
  const double s = d[1] * d[1] + d[2] * d[2];
  const double stretch = e.axial * (0.5 * s * e.inv_length);  // k s / (2 l)
  GeometricForce f;
  f.normal = e.axial * d[0] + stretch;
  const double string = f.normal * e.inv_length;  // N / l
  f.g[0] = stretch, f.g[1] = string * d[1], f.g[2] = string * d[2];
  const double y = e.limit - (f.normal > 0 ? f.normal : 0.0) - 2.0 * stretch;
  f.over = !(y >= 0 && (e.axial * e.axial) * s <= y * y);
  return f;
}

// The second-order part of an element's strain energy at u: k (eps l)^2 / 2 - k du^2 / 2 =
// k (du s / l + s^2 / (4 l^2)) / 2, what the energy books add to the linear pass's (not for the
// step).
inline double geometric_energy(const GeometricElement& e, const double* u) {
  const auto i = static_cast<std::size_t>(e.dof_i), j = static_cast<std::size_t>(e.dof_j);
  const double rel[3] = {u[j] - u[i], u[j + 1] - u[i + 1], u[j + 2] - u[i + 2]};
  double d[3];
  beam_to_local(e.axes, e.rotation, rel, d);
  const double h = 0.5 * (d[1] * d[1] + d[2] * d[2]) * e.inv_length;  // s / (2 l)
  return 0.5 * e.axial * (2.0 * d[0] * h + h * h);
}

// f += the second-order forces of `count` elements at u, in their order; returns how many
// exceeded their limit (GeometricForce::over).
inline std::size_t geometric_forces(const GeometricElement* elements, std::size_t count,
                                    const double* u, double* f) {
  std::size_t over = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const GeometricElement& e = elements[k];
    const GeometricForce gf = geometric_force(e, u);
    double g[3];
    beam_to_global(e.axes, e.rotation, gf.g, g);
    const auto i = static_cast<std::size_t>(e.dof_i), j = static_cast<std::size_t>(e.dof_j);
    for (std::size_t c = 0; c < 3; ++c) {
      f[j + c] += g[c];
      f[i + c] -= g[c];
    }
    over += gf.over ? 1 : 0;
  }
  return over;
}

// kBeamLanes elements with second-order geometry, lane l of each field (GeometricElement), for
// the SIMD pass; their rotations are a BeamRotations beside it. The blocks take the elements in
// the model's order (element_order.hpp: of one orientation together, so a block has one pick),
// each lane with its element's place in Model::geometric (`slot`), where its g goes. Lanes past
// the last element have DOF offset 0, zero stiffness and lane 0's axes: the pass computes them and
// keeps nothing of them.
struct alignas(32) GeometricBlock {
  BeamLanes axial{};       // N/m, k = E A / l (each lane array 32-byte aligned, as the vectors)
  BeamLanes inv_length{};  // 1/m
  BeamLanes limit{};       // N, Q_max
  std::array<std::int32_t, kBeamLanes> dof_i{};  // kDofsPerNode * node
  std::array<std::int32_t, kBeamLanes> dof_j{};
  std::array<std::int32_t, kBeamLanes> slot{};  // its index in Model::geometric
  std::array<AxisMap, kBeamLanes> axes{};
};

// What the SIMD pass reads: the blocks and their rotations, block by block.
struct GeometricArrays {
  const GeometricBlock* blocks = nullptr;
  const BeamRotations* rotations = nullptr;
};

// The `count` elements (in element order) into beam_blocks(count) blocks and rotations, lane by
// lane in the model's order `order` (the file indices of all its elements, element_order.hpp).
inline void fill_geometric_blocks(const GeometricElement* elements, std::size_t count,
                                  std::span<const std::int32_t> order, GeometricBlock* blocks,
                                  BeamRotations* rotations) {
  std::size_t n = 0;
  for (const std::int32_t index : order) {
    const GeometricElement* e =
        std::lower_bound(elements, elements + count, index,
                         [](const GeometricElement& g, std::int32_t i) { return g.element < i; });
    if (e == elements + count || e->element != index) continue;
    const std::size_t b = n / kBeamLanes, l = n % kBeamLanes;
    ++n;
    GeometricBlock& blk = blocks[b];
    if (l == 0) blk = GeometricBlock{}, rotations[b] = BeamRotations{};
    blk.dof_i[l] = e->dof_i, blk.dof_j[l] = e->dof_j;
    blk.slot[l] = static_cast<std::int32_t>(e - elements);
    blk.axes[l] = e->axes;
    blk.axial[l] = e->axial, blk.inv_length[l] = e->inv_length, blk.limit[l] = e->limit;
    for (std::size_t r = 0; r < 9; ++r)
      rotations[b].rotation[r][l] = e->rotation[r];
  }
  if (n % kBeamLanes != 0) {
    GeometricBlock& last = blocks[n / kBeamLanes];
    for (std::size_t l = n % kBeamLanes; l < kBeamLanes; ++l)
      last.axes[l] = last.axes[0];
  }
}

namespace detail {
#if defined(NTN_SIMD)
// kernel/src/element_pass.cpp: geometric_forces over the blocks, each element's g into `rows`
// (4 doubles an element, in element order), then added to f from there in element order (on
// vectors of another width than kBeamLanes, geometric_forces itself over `elements`).
std::size_t geometric_forces_simd(const GeometricArrays& a, const GeometricElement* elements,
                                  std::size_t count, const double* u, double* f, double* rows);
#endif
}  // namespace detail

// geometric_forces by the chosen path (Model::element_pass): the same bits either way. `rows`:
// 4 * count doubles of scratch for the SIMD path.
inline std::size_t geometric_forces(ElementPass path, const GeometricArrays& a,
                                    const GeometricElement* elements, std::size_t count,
                                    const double* u, double* f, double* rows) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd)
    return detail::geometric_forces_simd(a, elements, count, u, f, rows);
#else
  (void)path, (void)a, (void)rows;
#endif
  return geometric_forces(elements, count, u, f);
}

// The geometric stiffness of an axial force N (tension positive) in global axes (DOF order of
// beam_global_stiffness): in local axes N / l [[1, -1], [-1, 1]] on the transverse translations
// (v: 1, 7; w: 2, 8). What the static preload and modal analysis add to K about a preloaded state
// (the chord-rotation terms of the tangent, of the order of the rotation, are left out).
inline Matrix12 geometric_stiffness(const GeometricElement& e, double normal) {
  Matrix12 K{};
  const double c = normal * e.inv_length;
  for (const std::size_t t : {std::size_t{1}, std::size_t{2}}) {
    K[t * 12 + t] = c, K[(t + 6) * 12 + t + 6] = c;
    K[t * 12 + t + 6] = -c, K[(t + 6) * 12 + t] = -c;
  }
  return to_global_axes(K, e.rotation);
}

}  // namespace ntn
