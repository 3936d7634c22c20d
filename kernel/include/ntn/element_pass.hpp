// The element pass F_n = sum T^T K_L T u_n (S 2, DESIGN §4) over elements stored in blocks of
// kBeamLanes, one element per lane (structure of arrays), so that one vector instruction does the
// same operation for kBeamLanes elements. Two paths compute it:
//   - the scalar reference: beam_force() (beam.hpp) element by element, in the model's order;
//   - the SIMD path (kernel/src/element_pass.cpp, Highway, the CPU's widest vectors picked at
//     run time): beam_force's operations in beam_force's order in every lane (IEEE products and
//     sums, no contraction; the picks of an aligned element where beam_force picks, by the
//     element's AxisMap), the end forces then added to the nodes lane by lane in the model's
//     element order.
// So both give the same bits, on every build (tests/kernel/element_pass_test.cpp). A build
// without NTN_SIMD (embedded, cross builds) has the scalar path alone.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "ntn/beam.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

inline constexpr std::size_t kBeamLanes = 4;  // elements per block: one AVX2 vector of doubles

constexpr std::size_t beam_blocks(std::size_t elements) {
  return (elements + kBeamLanes - 1) / kBeamLanes;
}

// kBeamLanes elements, field by field (BeamData's fields but the rotation, lane l of each).
// Lanes past the model's last element have zero stiffness and DOF offset 0; the pass computes
// them and adds them nowhere. Every lane array is 32-byte aligned (one AVX2 vector, never across a
// cache line).
struct alignas(32) BeamBlock {
  using Lanes = std::array<double, kBeamLanes>;
  Lanes axial{};
  Lanes torsion{};
  std::array<Lanes, 4> xy{};
  std::array<Lanes, 4> xz{};
  std::array<std::int32_t, kBeamLanes> dof_i{};  // kDofsPerNode * node_i
  std::array<std::int32_t, kBeamLanes> dof_j{};  // kDofsPerNode * node_j
  std::array<AxisMap, kBeamLanes> axes{};        // axis_map(rotation), lane by lane
};

// The rotations of a block's elements (BeamData::rotation[k], lane by lane), in an array of their
// own beside the blocks: a block of aligned elements (beam.hpp, AxisMap) never reads its
// rotations, so a pass over an aligned frame streams 384 bytes per block instead of 672.
struct alignas(32) BeamRotations {
  std::array<BeamBlock::Lanes, 9> rotation{};
};
static_assert(sizeof(BeamBlock) + sizeof(BeamRotations) == kBeamLanes * sizeof(BeamData),
              "one BeamData per lane");

inline void set_lane(BeamBlock& blk, BeamRotations& rot, std::size_t l, const BeamData& b) {
  blk.dof_i[l] = kDofsPerNode * b.node_i;
  blk.dof_j[l] = kDofsPerNode * b.node_j;
  blk.axes[l] = axis_map(b.rotation);  // from the rotation: the one rule, whatever b.axes says
  for (std::size_t k = 0; k < 9; ++k)
    rot.rotation[k][l] = b.rotation[k];
  blk.axial[l] = b.k.axial;
  blk.torsion[l] = b.k.torsion;
  for (std::size_t k = 0; k < 4; ++k) {
    blk.xy[k][l] = b.k.xy[k];
    blk.xz[k][l] = b.k.xz[k];
  }
}

inline BeamData lane(const BeamBlock& blk, const BeamRotations& rot, std::size_t l) {
  BeamData b;
  b.node_i = blk.dof_i[l] / kDofsPerNode;
  b.node_j = blk.dof_j[l] / kDofsPerNode;
  b.axes = blk.axes[l];
  for (std::size_t k = 0; k < 9; ++k)
    b.rotation[k] = rot.rotation[k][l];
  b.k.axial = blk.axial[l];
  b.k.torsion = blk.torsion[l];
  for (std::size_t k = 0; k < 4; ++k) {
    b.k.xy[k] = blk.xy[k][l];
    b.k.xz[k] = blk.xz[k][l];
  }
  return b;
}

// Which path the step's element pass and DOF pass (dof_pass.hpp) take (Model::element_pass). kSimd
// falls back to the scalar reference in a build without NTN_SIMD.
enum class ElementPass : std::uint8_t { kSimd, kScalar };

// The multi-core pass's mask of a block (team.hpp): bit direct_bit(l, end) is set when the force
// of lane l's end (0: node i, 1: node j) is added to F_n directly, else stored.
constexpr std::uint8_t direct_bit(std::size_t l, std::size_t end) {
  return static_cast<std::uint8_t>(1U << (2 * l + end));
}
constexpr bool direct_end(std::uint8_t direct, std::size_t l, std::size_t end) {
  return (direct & direct_bit(l, end)) != 0;
}

namespace detail {

// Element l of a block: its global end forces fi (on node i), fj at u (+ beta v when beta != 0).
inline void lane_force(const BeamBlock& blk, const BeamRotations& rot, std::size_t l,
                       const double* u, const double* v, double beta, double* fi, double* fj) {
  const BeamData b = lane(blk, rot, l);
  const auto i = static_cast<std::size_t>(blk.dof_i[l]);
  const auto j = static_cast<std::size_t>(blk.dof_j[l]);
  if (beta != 0.0) {
    double ui[6], uj[6];
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      ui[d] = u[i + d] + beta * v[i + d];
      uj[d] = u[j + d] + beta * v[j + d];
    }
    beam_force(b, ui, uj, fi, fj);
  } else {
    beam_force(b, &u[i], &u[j], fi, fj);
  }
}

// The scalar reference: f += the elements' forces at u (+ beta v when beta != 0), in order.
inline void element_forces_scalar(const BeamBlock* blocks, const BeamRotations* rotations,
                                  std::size_t elements, const double* u, const double* v,
                                  double beta, double* f) {
  for (std::size_t e = 0; e < elements; ++e) {
    const BeamBlock& blk = blocks[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    double fi[6], fj[6];
    lane_force(blk, rotations[e / kBeamLanes], l, u, v, beta, fi, fj);
    const auto i = static_cast<std::size_t>(blk.dof_i[l]);
    const auto j = static_cast<std::size_t>(blk.dof_j[l]);
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      f[i + d] += fi[d];
      f[j + d] += fj[d];
    }
  }
}

// The scalar reference of the multi-core pass (team.hpp), over the elements of blocks
// [first, last), whole blocks, in element order: each end's force added to f at its node where
// direct[block] has the end's bit (direct_end), else stored into fe[12 e + 6 end + c] (the lanes
// past the model's last element have no bit: stored, never read).
inline void element_forces_split_scalar(const BeamBlock* blocks, const BeamRotations* rotations,
                                        std::size_t first, std::size_t last,
                                        const std::uint8_t* direct, const double* u,
                                        const double* v, double beta, double* f, double* fe) {
  for (std::size_t e = first * kBeamLanes; e < last * kBeamLanes; ++e) {
    const BeamBlock& blk = blocks[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    double fij[12];
    lane_force(blk, rotations[e / kBeamLanes], l, u, v, beta, fij, fij + 6);
    const std::int32_t node_dof[2] = {blk.dof_i[l], blk.dof_j[l]};
    for (std::size_t end = 0; end < 2; ++end) {
      if (direct_end(direct[e / kBeamLanes], l, end)) {
        for (std::size_t d = 0; d < kDofsPerNode; ++d)
          f[static_cast<std::size_t>(node_dof[end]) + d] += fij[6 * end + d];
      } else {
        for (std::size_t d = 0; d < kDofsPerNode; ++d)
          fe[12 * e + 6 * end + d] = fij[6 * end + d];
      }
    }
  }
}

#if defined(NTN_SIMD)
// kernel/src/element_pass.cpp: the same, kBeamLanes elements at a time.
void element_forces_simd(const BeamBlock* blocks, const BeamRotations* rotations,
                         std::size_t elements, const double* u, const double* v, double beta,
                         double* f);
void element_forces_split_simd(const BeamBlock* blocks, const BeamRotations* rotations,
                               std::size_t first, std::size_t last, const std::uint8_t* direct,
                               const double* u, const double* v, double beta, double* f,
                               double* fe);
#endif

}  // namespace detail

// The instruction set the SIMD path runs on here ("AVX2", "SSE4", "NEON", ...), or "scalar" in a
// build without NTN_SIMD. Not for step(): for reports.
const char* element_pass_target();

// f += the elements' forces at u (+ beta v), by the chosen path.
inline void element_forces(ElementPass path, const BeamBlock* blocks,
                           const BeamRotations* rotations, std::size_t elements, const double* u,
                           const double* v, double beta, double* f) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd) {
    detail::element_forces_simd(blocks, rotations, elements, u, v, beta, f);
    return;
  }
#else
  (void)path;
#endif
  detail::element_forces_scalar(blocks, rotations, elements, u, v, beta, f);
}

// The multi-core pass over blocks [first, last) (element_forces_split_scalar), by the chosen path.
inline void element_forces_split(ElementPass path, const BeamBlock* blocks,
                                 const BeamRotations* rotations, std::size_t first,
                                 std::size_t last, const std::uint8_t* direct, const double* u,
                                 const double* v, double beta, double* f, double* fe) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd) {
    detail::element_forces_split_simd(blocks, rotations, first, last, direct, u, v, beta, f, fe);
    return;
  }
#else
  (void)path;
#endif
  detail::element_forces_split_scalar(blocks, rotations, first, last, direct, u, v, beta, f, fe);
}

}  // namespace ntn
