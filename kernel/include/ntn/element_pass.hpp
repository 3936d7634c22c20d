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
#include "ntn/shared_table.hpp"

namespace ntn {

inline constexpr std::size_t kBeamLanes = 4;  // elements per block: one AVX2 vector of doubles

constexpr std::size_t beam_blocks(std::size_t elements) {
  return (elements + kBeamLanes - 1) / kBeamLanes;
}

// One double per lane of a block.
using BeamLanes = std::array<double, kBeamLanes>;

// The stiffness of kBeamLanes elements, lane l of each field (BeamStiffness, beam.hpp). Lanes past
// the model's last element have zero stiffness. Every lane array is 32-byte aligned (one AVX2
// vector, never across a cache line).
struct alignas(32) BeamStiffnessBlock {
  using Lanes = BeamLanes;
  Lanes axial{};
  Lanes torsion{};
  std::array<Lanes, 4> xy{};
  std::array<Lanes, 4> xz{};
};

// kBeamLanes elements: their nodes, how they rotate, and which entry of the model's stiffness
// table (BeamArrays::stiffness) holds their stiffness. Blocks of equal stiffness (the same bits in
// every lane) share one entry, so that a frame of a few member types streams 48 bytes per block
// and finds its stiffness in L1 (dedupe_stiffness). Lanes past the model's last element have DOF
// offset 0; the pass computes them and adds them nowhere.
struct BeamBlock {
  std::array<std::int32_t, kBeamLanes> dof_i{};  // kDofsPerNode * node_i
  std::array<std::int32_t, kBeamLanes> dof_j{};  // kDofsPerNode * node_j
  std::array<AxisMap, kBeamLanes> axes{};        // axis_map(rotation), lane by lane
  std::int32_t stiffness = 0;                    // its entry of the stiffness table
  // direct_bit(l, end) where lane l's end is the first of its node's element ends in the model's
  // order (mark_first_ends): the SIMD pass, and the multi-core pass on both paths, write 0.0 + f
  // there instead of adding to F.
  std::uint8_t first = 0;
};

// The rotations of a block's elements (BeamData::rotation[k], lane by lane), in an array of their
// own beside the blocks: a block of aligned elements (beam.hpp, AxisMap) never reads its
// rotations, so a pass over an aligned frame streams the blocks alone.
struct alignas(32) BeamRotations {
  std::array<BeamLanes, 9> rotation{};
};

// What the element pass reads: the blocks, their rotations (block by block) and the stiffness
// table (by BeamBlock::stiffness).
struct BeamArrays {
  const BeamBlock* blocks = nullptr;
  const BeamRotations* rotations = nullptr;
  const BeamStiffnessBlock* stiffness = nullptr;
};

// Element b * kBeamLanes + l into lane l of block b, its stiffness into entry b of the table
// (each block its own entry until dedupe_stiffness shares them).
inline void set_lane(BeamBlock* blocks, BeamRotations* rotations, BeamStiffnessBlock* stiffness,
                     std::size_t b, std::size_t l, const BeamData& data) {
  BeamBlock& blk = blocks[b];
  blk.dof_i[l] = kDofsPerNode * data.node_i;
  blk.dof_j[l] = kDofsPerNode * data.node_j;
  // From the rotation: the one rule, whatever data.axes says.
  blk.axes[l] = axis_map(data.rotation);
  blk.stiffness = static_cast<std::int32_t>(b);
  for (std::size_t k = 0; k < 9; ++k)
    rotations[b].rotation[k][l] = data.rotation[k];
  BeamStiffnessBlock& st = stiffness[b];
  st.axial[l] = data.k.axial;
  st.torsion[l] = data.k.torsion;
  for (std::size_t k = 0; k < 4; ++k) {
    st.xy[k][l] = data.k.xy[k];
    st.xz[k][l] = data.k.xz[k];
  }
}

inline BeamData lane(const BeamArrays& a, std::size_t b, std::size_t l) {
  const BeamBlock& blk = a.blocks[b];
  const BeamStiffnessBlock& st = a.stiffness[blk.stiffness];
  BeamData data;
  data.node_i = blk.dof_i[l] / kDofsPerNode;
  data.node_j = blk.dof_j[l] / kDofsPerNode;
  data.axes = blk.axes[l];
  for (std::size_t k = 0; k < 9; ++k)
    data.rotation[k] = a.rotations[b].rotation[k][l];
  data.k.axial = st.axial[l];
  data.k.torsion = st.torsion[l];
  for (std::size_t k = 0; k < 4; ++k) {
    data.k.xy[k] = st.xy[k][l];
    data.k.xz[k] = st.xz[k][l];
  }
  return data;
}

// Shares the stiffness table's equal entries after set_lane has given every block its own: block
// b's entry becomes the one share_entry() finds for its bytes (shared_table.hpp), the table
// compacted to the distinct entries in block order. Returns their number; the entries past it are
// zeroed.
inline std::size_t dedupe_stiffness(BeamBlock* blocks, BeamStiffnessBlock* stiffness,
                                    std::size_t num_blocks) {
  std::size_t distinct = 0;
  for (std::size_t b = 0; b < num_blocks; ++b) {
    const BeamStiffnessBlock st = stiffness[b];
    blocks[b].stiffness = static_cast<std::int32_t>(share_entry(stiffness, distinct, st));
  }
  for (std::size_t k = distinct; k < num_blocks; ++k)
    stiffness[k] = BeamStiffnessBlock{};
  return distinct;
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

// Sets each block's `first` bits: lane l's end e is its node's first end in the model's order
// (`elements` of them, in blocks). `touched` is scratch of `nodes` bytes. Returns true when every
// node has an element end, so that the SIMD pass's first writes cover all of F.
inline bool mark_first_ends(BeamBlock* blocks, std::size_t elements, std::size_t nodes,
                            std::uint8_t* touched) {
  for (std::size_t n = 0; n < nodes; ++n)
    touched[n] = 0;
  for (std::size_t e = 0; e < elements; ++e) {
    BeamBlock& blk = blocks[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    if (l == 0) blk.first = 0;
    const std::int32_t dof[2] = {blk.dof_i[l], blk.dof_j[l]};
    for (std::size_t end = 0; end < 2; ++end) {
      const auto n = static_cast<std::size_t>(dof[end] / kDofsPerNode);
      if (touched[n] == 0) blk.first = static_cast<std::uint8_t>(blk.first | direct_bit(l, end));
      touched[n] = 1;
    }
  }
  bool every = true;
  for (std::size_t n = 0; n < nodes; ++n)
    every = every && touched[n] != 0;
  return every;
}

namespace detail {

// An end's force y onto F's value x: x + y, or 0.0 + y where the end is its node's first
// (BeamBlock::first): F is then not read, and 0.0 + y is what a zeroed F plus y gives, bit for bit.
constexpr double onto(bool first, double x, double y) {
  return (first ? 0.0 : x) + y;
}

// Element l of a block: its global end forces fi (on node i), fj at u (+ beta v when beta != 0).
inline void lane_force(const BeamArrays& a, std::size_t blk, std::size_t l, const double* u,
                       const double* v, double beta, double* fi, double* fj) {
  const BeamData b = lane(a, blk, l);
  const auto i = static_cast<std::size_t>(a.blocks[blk].dof_i[l]);
  const auto j = static_cast<std::size_t>(a.blocks[blk].dof_j[l]);
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
inline void element_forces_scalar(const BeamArrays& a, std::size_t elements, const double* u,
                                  const double* v, double beta, double* f) {
  for (std::size_t e = 0; e < elements; ++e) {
    const BeamBlock& blk = a.blocks[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    double fi[6], fj[6];
    lane_force(a, e / kBeamLanes, l, u, v, beta, fi, fj);
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
// direct[block] has the end's bit (direct_end; written as 0.0 + the force where the end is its
// node's first, BeamBlock::first: F is not zeroed first), else stored into fe[12 e + 6 end + c]
// (the lanes past the model's last element have no bit: stored, never read).
inline void element_forces_split_scalar(const BeamArrays& a, std::size_t first, std::size_t last,
                                        const std::uint8_t* direct, const double* u,
                                        const double* v, double beta, double* f, double* fe) {
  for (std::size_t e = first * kBeamLanes; e < last * kBeamLanes; ++e) {
    const BeamBlock& blk = a.blocks[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    double fij[12];
    lane_force(a, e / kBeamLanes, l, u, v, beta, fij, fij + 6);
    const std::int32_t node_dof[2] = {blk.dof_i[l], blk.dof_j[l]};
    for (std::size_t end = 0; end < 2; ++end) {
      if (direct_end(direct[e / kBeamLanes], l, end)) {
        const bool first_end = direct_end(blk.first, l, end);
        for (std::size_t d = 0; d < kDofsPerNode; ++d) {
          double& x = f[static_cast<std::size_t>(node_dof[end]) + d];
          x = onto(first_end, x, fij[6 * end + d]);
        }
      } else {
        for (std::size_t d = 0; d < kDofsPerNode; ++d)
          fe[12 * e + 6 * end + d] = fij[6 * end + d];
      }
    }
  }
}

#if defined(NTN_SIMD)
// kernel/src/element_pass.cpp: the same, kBeamLanes elements at a time.
void element_forces_simd(const BeamArrays& a, std::size_t elements, const double* u,
                         const double* v, double beta, double* f);
// f = the forces: each node's first end (BeamBlock::first) written as 0.0 + its force, the others
// added; every node must have an end (mark_first_ends).
void element_forces_first_simd(const BeamArrays& a, std::size_t elements, const double* u,
                               const double* v, double beta, double* f);
void element_forces_split_simd(const BeamArrays& a, std::size_t first, std::size_t last,
                               const std::uint8_t* direct, const double* u, const double* v,
                               double beta, double* f, double* fe);
#endif

}  // namespace detail

// The instruction set the SIMD path runs on here ("AVX2", "SSE4", "NEON", ...), or "scalar" in a
// build without NTN_SIMD. Not for step(): for reports.
const char* element_pass_target();

// f += the elements' forces at u (+ beta v), by the chosen path.
inline void element_forces(ElementPass path, const BeamArrays& a, std::size_t elements,
                           const double* u, const double* v, double beta, double* f) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd) {
    detail::element_forces_simd(a, elements, u, v, beta, f);
    return;
  }
#else
  (void)path;
#endif
  detail::element_forces_scalar(a, elements, u, v, beta, f);
}

// F = the elements' forces at u (+ beta v) over `dofs` DOFs: zeroed, then added to, by the chosen
// path; the SIMD path writes each node's first end instead of zeroing F first (the same bits: it
// writes 0.0 + f, which is what the zeroed F plus f gives) where every node has an element end
// (`every_node`: mark_first_ends), and zeroes F otherwise.
inline void element_forces_into(ElementPass path, const BeamArrays& a, std::size_t elements,
                                bool every_node, std::size_t dofs, const double* u, const double* v,
                                double beta, double* f) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd && every_node) {
    detail::element_forces_first_simd(a, elements, u, v, beta, f);
    return;
  }
#else
  (void)every_node;
#endif
  for (std::size_t j = 0; j < dofs; ++j)
    f[j] = 0.0;
  element_forces(path, a, elements, u, v, beta, f);
}

// The multi-core pass over blocks [first, last) (element_forces_split_scalar), by the chosen path.
inline void element_forces_split(ElementPass path, const BeamArrays& a, std::size_t first,
                                 std::size_t last, const std::uint8_t* direct, const double* u,
                                 const double* v, double beta, double* f, double* fe) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd) {
    detail::element_forces_split_simd(a, first, last, direct, u, v, beta, f, fe);
    return;
  }
#else
  (void)path;
#endif
  detail::element_forces_split_scalar(a, first, last, direct, u, v, beta, f, fe);
}

}  // namespace ntn
