// The multi-core step: step(m, s, w, in, team, work) does what step(m, s, w, in)
// does, with the element pass and (in models without hinges) the DOF pass spread over a team of
// workers that the caller made before the run (hil_sim's WorkerTeam: threads, pinned where
// permitted). The kernel creates no thread and takes no lock: it hands the team a job and a
// fixed partition.
//
// The same bits for any number of workers. The single-core pass adds each element's end forces
// to its nodes in element order, starting from +0.0 (element_pass.hpp). Worker k owns a fixed
// range of element blocks; a node all of whose elements are in one worker's range is that
// worker's ("interior"), the others are shared (a storey's nodes where two ranges meet, in a
// frame). The team's pass:
//   A. each worker computes the end forces of its blocks in element order: an end at an interior
//      node is added to F_n there and then, the node's first end (BeamBlock::first, which falls
//      in the blocks of the worker that holds all of the node's elements) written as 0.0 + its
//      force (the single-core sums from +0.0, operation for operation, with no pass to zero F:
//      no cache line of F crosses to another core to be cleared); an end at a shared node is
//      stored (TeamWork::end_forces);
//   B. each worker sums, for its part of the shared nodes, the stored end forces of every
//      element at that node in element order (TeamWork::incidence) from +0.0: again the
//      single-core sums (F_n written, not added to: every node is interior to one worker or
//      shared, so no F_n is left from the last step);
//   C. (no hinges) after the outputs, each worker runs the DOF pass (residual, a_n and update:
//      residual_update(), dof_pass.hpp) over a fixed range of nodes.
// Between the phases the team's run() returns only when every worker has finished. Everything
// else stays on the caller's thread, in the single-core order.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "ntn/element_pass.hpp"
#include "ntn/model.hpp"

namespace ntn {

inline constexpr int kMaxTeam = 16;  // workers, the caller's thread included

// A team of workers made by the caller. run(self, job, arg) calls job(arg, k) once for every
// worker k = 0 .. size - 1 (k = 0 may be the caller's own thread) and returns when all have
// returned. No allocation, no lock in run() (hil_sim's WorkerTeam: atomics).
struct Team {
  int size = 1;
  void (*run)(void* self, void (*job)(void* arg, int worker), void* arg) = nullptr;
  void* self = nullptr;
};

// What the team's step needs besides the model: the end forces of every element, the elements at
// every node (in element order) and the fixed partition. Caller-owned (static), built once by
// prepare_team().
template <Sizes S>
struct TeamWork : SizesOf<S> {
  static constexpr std::size_t kBlocks = beam_blocks(S.elements);
  // fe[12 e + c]: element e's force on node i's DOF c (c < 6), then on node j's; whole blocks.
  Array<double, S, 12 * kBeamLanes * kBlocks> end_forces{};
  // The elements at node n: incidence[node_start[n] .. node_start[n + 1]), each the offset
  // 12 e + 6 end into end_forces, in element order.
  Array<std::int32_t, S, S.nodes + 1> node_start{};
  Array<std::int32_t, S, 2 * S.elements> incidence{};
  // Worker k: element blocks [block_split[k], block_split[k + 1]), nodes [node_split[k], ...).
  std::array<std::int32_t, kMaxTeam + 1> block_split{};
  std::array<std::int32_t, kMaxTeam + 1> node_split{};
  // Per block, bit 2 l + end (direct_end): that end's node is interior to the block's worker.
  Array<std::uint8_t, S, kBlocks> direct{};
  // The shared nodes, in node order (the nodes with no element too: their F_n is +0.0), and
  // worker k's part of them: shared[shared_split[k] .. shared_split[k + 1]).
  Array<std::int32_t, S, S.nodes> shared{};
  std::array<std::int32_t, kMaxTeam + 1> shared_split{};
  std::array<double, kMaxTeam> bad{};  // per worker: 1 when a velocity of its DOFs is not finite
  int size = 0;                        // workers the partition is for
};

// Builds the incidence lists, the partition (element blocks, nodes and shared nodes in equal
// contiguous ranges) and which ends are added directly for a team of `size` workers
// (1..kMaxTeam). False for a size out of range.
template <Sizes S>
[[nodiscard]] bool prepare_team(const Model<S>& m, int size, TeamWork<S>& t) {
  if (size < 1 || size > kMaxTeam) return false;
  if constexpr (S.runtime) {
    if (t.sizes != m.sizes) return false;  // not bound for this model (runtime_storage.hpp)
  }
  t.size = size;
  t.node_start.fill(0);
  for (std::size_t e = 0; e < m.sizes.elements; ++e) {
    const BeamBlock& blk = m.beams[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    ++t.node_start[static_cast<std::size_t>(blk.dof_i[l] / kDofsPerNode) + 1];
    ++t.node_start[static_cast<std::size_t>(blk.dof_j[l] / kDofsPerNode) + 1];
  }
  for (std::size_t n = 0; n < m.sizes.nodes; ++n)
    t.node_start[n + 1] += t.node_start[n];  // node_start[n + 1]: the end of node n's list
  // Filled from the back, elements last to first: each list ends up in element order, and
  // node_start[n + 1] moves down to the start of node n's list (no second array).
  for (std::size_t e = m.sizes.elements; e-- > 0;) {
    const BeamBlock& blk = m.beams[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    const std::int32_t ends[2] = {blk.dof_i[l] / kDofsPerNode, blk.dof_j[l] / kDofsPerNode};
    for (std::size_t end = 2; end-- > 0;) {
      const auto n = static_cast<std::size_t>(ends[end]);
      t.incidence[static_cast<std::size_t>(--t.node_start[n + 1])] =
          static_cast<std::int32_t>(12 * e + 6 * end);
    }
  }
  for (std::size_t n = 0; n < m.sizes.nodes; ++n)
    t.node_start[n] = t.node_start[n + 1];
  t.node_start[m.sizes.nodes] = static_cast<std::int32_t>(2 * m.sizes.elements);
  const auto blocks = static_cast<std::int64_t>(beam_blocks(m.sizes.elements));
  const auto nodes = static_cast<std::int64_t>(m.sizes.nodes);
  constexpr auto kGroup = static_cast<std::int64_t>(kBookNodes);
  for (int k = 0; k <= size; ++k) {
    t.block_split[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(blocks * k / size);
    // whole book groups (books.hpp), so that each group's energy books are one worker's
    const std::int64_t split = k == size ? nodes : nodes * k / size / kGroup * kGroup;
    t.node_split[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(split);
  }
  // Interior nodes: the first and the last of their elements (in element order) are in the same
  // worker's blocks, so all are.
  auto worker_of = [&](std::int32_t element) {
    const std::int32_t block = element / static_cast<std::int32_t>(kBeamLanes);
    int k = 0;
    while (t.block_split[static_cast<std::size_t>(k) + 1] <= block)
      ++k;
    return k;
  };
  auto interior = [&](std::size_t n) {
    const auto first = static_cast<std::size_t>(t.node_start[n]);
    const auto last = static_cast<std::size_t>(t.node_start[n + 1]);
    return first < last &&
           worker_of(t.incidence[first] / 12) == worker_of(t.incidence[last - 1] / 12);
  };
  t.direct.fill(0);
  for (std::size_t e = 0; e < m.sizes.elements; ++e) {
    const BeamBlock& blk = m.beams[e / kBeamLanes];
    const std::size_t l = e % kBeamLanes;
    const std::int32_t node_dof[2] = {blk.dof_i[l], blk.dof_j[l]};
    for (std::size_t end = 0; end < 2; ++end) {
      if (interior(static_cast<std::size_t>(node_dof[end] / kDofsPerNode)))
        t.direct[e / kBeamLanes] |= direct_bit(l, end);
    }
  }
  std::int64_t num_shared = 0;
  for (std::size_t n = 0; n < m.sizes.nodes; ++n) {
    if (!interior(n))
      t.shared[static_cast<std::size_t>(num_shared++)] = static_cast<std::int32_t>(n);
  }
  for (int k = 0; k <= size; ++k)
    t.shared_split[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(num_shared * k / size);
  return true;
}

namespace detail {

// Node n's internal force F_n from the stored end forces, in element order from +0.0: the
// single-core pass's sums.
template <Sizes S>
void gather_node(const TeamWork<S>& t, std::size_t n, double* f) {
  double x[kDofsPerNode] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const auto first = static_cast<std::size_t>(t.node_start[n]);
  const auto last = static_cast<std::size_t>(t.node_start[n + 1]);
  for (std::size_t k = first; k < last; ++k) {
    const double* fe = &t.end_forces[static_cast<std::size_t>(t.incidence[k])];
    for (std::size_t d = 0; d < kDofsPerNode; ++d)
      x[d] += fe[d];
  }
  for (std::size_t d = 0; d < kDofsPerNode; ++d)
    f[kDofsPerNode * n + d] = x[d];
}

}  // namespace detail
}  // namespace ntn
