// Model<S>, State<S>, Scratch<S> laid out member by member, in declaration order, as the
// compiler does it (each member at the next multiple of its alignment, the struct padded to its
// largest alignment). The member lists below mirror kernel/include/ntn/model.hpp and state.hpp;
// tests/modelc compare the result with sizeof for several sizes, so a kernel change that this
// file does not follow fails a test instead of printing a wrong figure.
#include "ntn/modelc/model_bytes.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

#include "ntn/beam.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"
#include "ntn/time_step.hpp"

namespace ntn::modelc {
namespace {

// std::array<T, N> is a T[N] for N > 0; std::array<T, 0> is an empty struct of its own size.
static_assert(sizeof(std::array<double, 3>) == 3 * sizeof(double));
static_assert(sizeof(std::array<BeamData, 2>) == 2 * sizeof(BeamData));

class Layout {
 public:
  void add(std::size_t size, std::size_t align) {
    offset_ = (offset_ + align - 1) / align * align + size;
    align_ = std::max(align_, align);
  }
  template <class T>
  void scalar() {
    add(sizeof(T), alignof(T));
  }
  template <class T>
  void array(int n) {
    if (n > 0) {
      add(static_cast<std::size_t>(n) * sizeof(T), alignof(T));
    } else {
      add(sizeof(std::array<T, 0>), alignof(std::array<T, 0>));
    }
  }
  std::size_t size() const { return (offset_ + align_ - 1) / align_ * align_; }
  std::size_t align() const { return align_; }

 private:
  std::size_t offset_ = 0;
  std::size_t align_ = 1;
};

std::size_t model_size(const Sizes& s) {
  const int dofs = kDofsPerNode * s.nodes;
  Layout l;
  l.array<BeamData>(s.elements);      // beams
  l.array<double>(dofs);              // mass
  l.array<double>(dofs);              // inv_mass
  l.array<double>(dofs);              // damping
  l.scalar<double>();                 // alpha
  l.array<std::uint8_t>(s.nodes);     // fixed
  l.array<std::int32_t>(s.nodes);     // supported_nodes
  l.scalar<int>();                    // num_supported
  l.array<TimePoint>(s.time_points);  // time_points
  l.array<TimeFunctionSpec>(s.time_functions);
  l.array<LoadSpec>(s.loads);
  l.array<std::int32_t>(s.loads + s.inputs);  // slot_dof
  l.array<std::int32_t>(s.loads);             // load_slot
  l.array<std::int32_t>(s.inputs);            // input_slot
  l.scalar<int>();                            // num_slots
  l.array<InputSpec>(s.inputs);
  l.array<OutputSpec>(s.outputs);
  l.add(sizeof(std::array<double, 3>), alignof(std::array<double, 3>));  // gravity
  l.scalar<int>();                                                       // gravity_function
  l.scalar<double>();                                                    // dt
  l.scalar<StableStepReport>();                                          // stable
  const int hinge_nodes = s.hinges > 0 ? s.nodes : 0;                    // kHingeNodes
  l.array<HingeData>(s.hinges);                                          // hinges
  l.array<CurvePoint>(s.curve_points);                                   // curve_points
  l.array<ForestEdge>(s.hinges);                                         // edges
  l.array<ForestEdgeMatrices>(s.hinges);                                 // edge_matrices
  l.array<ForestRoot>(s.hinges);                                         // roots
  l.array<std::int32_t>(s.hinges);                                       // hinge_edge
  l.array<std::int32_t>(hinge_nodes);                                    // node_tree
  l.array<std::uint8_t>(hinge_nodes);                                    // held
  l.array<double>(kDofsPerNode * hinge_nodes);                           // residual_scale
  l.array<std::int32_t>(s.hinges);                                       // spring_hinges
  l.array<std::int32_t>(s.hinges);                                       // branch_hinges
  l.array<std::int32_t>(s.hinges);                                       // project_edges
  l.array<ForestTree>(s.hinges);                                         // trees
  l.array<std::int32_t>(s.hinges);                                       // tree_stops
  l.scalar<int>();                                                       // num_edges
  l.scalar<int>();                                                       // num_roots
  l.scalar<int>();                                                       // num_spring_hinges
  l.scalar<int>();                                                       // num_branch_hinges
  l.scalar<int>();                                                       // num_project_edges
  l.scalar<int>();                                                       // num_trees
  l.scalar<int>();                                                       // held_dofs
  l.scalar<HingeMethod>();                                               // hinge_method
  l.scalar<ClampRule>();                                                 // clamp
  l.scalar<double>();                                                    // inv_dt
  return l.size();
}

std::size_t state_size(const Sizes& s) {
  const int dofs = kDofsPerNode * s.nodes;
  Layout l;
  l.array<double>(dofs);      // u
  l.array<double>(dofs);      // v
  l.array<double>(s.inputs);  // held_inputs
  l.scalar<std::int64_t>();   // tick
  l.scalar<std::uint64_t>();  // inputs_held
  l.scalar<std::uint64_t>();  // inputs_out_of_range
  l.scalar<std::uint32_t>();  // faults
  return l.size();
}

Layout clamp_work_layout(const Sizes& s) {
  const int dofs = s.hinges > 0 ? kDofsPerNode * s.nodes : 0;
  Layout l;
  l.array<double>(dofs);                              // impulse
  l.array<double>(dofs);                              // response
  l.array<std::int64_t>(s.hinges > 0 ? s.nodes : 0);  // moved
  l.array<std::int64_t>(s.hinges);                    // checked
  l.scalar<std::int64_t>();                           // events
  return l;
}

std::size_t clamp_work_size(const Sizes& s) {
  return clamp_work_layout(s).size();
}

std::size_t clamp_work_align(const Sizes& s) {
  return clamp_work_layout(s).align();
}

std::size_t scratch_size(const Sizes& s) {
  const int dofs = kDofsPerNode * s.nodes;
  Layout l;
  l.array<double>(kDofsPerNode);                 // load_g
  l.array<double>(s.loads + s.inputs);           // p_slot
  l.array<double>(dofs);                         // f
  l.array<double>(dofs);                         // a
  l.array<double>(s.hinges > 0 ? dofs : 0);      // r (models with hinges)
  l.array<double>(s.outputs);                    // outputs
  const std::size_t clamp = clamp_work_size(s);  // clamp (ClampWork)
  l.add(clamp, clamp_work_align(s));
  l.array<double>(3);  // ground
  l.scalar<double>();  // time
  return l.size();
}

}  // namespace

MemoryFootprint memory_footprint(const Sizes& s) {
  MemoryFootprint f;
  f.model = model_size(s);
  f.state = state_size(s);
  f.scratch = scratch_size(s);
  f.total = f.model + f.state + f.scratch;
  f.per_element = sizeof(BeamData);
  // Per node: 6 DOFs x 7 per-DOF double arrays (Model: mass, inv_mass, damping; State: u, v;
  // Scratch: f, a), plus Model::fixed (1 byte) and Model::supported_nodes (4 bytes).
  f.per_node = kDofsPerNode * 7 * sizeof(double) + sizeof(std::uint8_t) + sizeof(std::int32_t);
  // Per hinge: its data, its forest slots (edge, root, hinge -> edge) and its
  // places in the lists of hinges with springs, with branches, of projected edges and of the
  // trees' stops, a
  // tree slot (a forest has at most one tree per hinge) and its clamp check mark (Scratch).
  f.per_hinge = sizeof(HingeData) + sizeof(ForestEdge) + sizeof(ForestEdgeMatrices) +
                sizeof(ForestRoot) + 5 * sizeof(std::int32_t) + sizeof(ForestTree) +
                sizeof(std::int64_t);
  // A model with hinges also has per node a tree index and mechanism bits (Model::node_tree,
  // held), the residual scale of its 6 DOFs (Model::residual_scale), their coupled force
  // (Scratch::r), the clamp's impulse and response (Scratch::clamp) and its clamp move mark.
  f.per_node_with_hinges = sizeof(std::int32_t) + sizeof(std::uint8_t) +
                           4 * kDofsPerNode * sizeof(double) + sizeof(std::int64_t);
  f.per_curve_point = sizeof(CurvePoint);
  return f;
}

std::size_t model_bytes(const Sizes& s) {
  return memory_footprint(s).total;
}

}  // namespace ntn::modelc
