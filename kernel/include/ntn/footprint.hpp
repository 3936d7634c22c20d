// The memory of Model<S>, State<S> and Scratch<S> for sizes known only at run time (the model
// compiler prints it for a model it has not emitted yet): the structs' members laid out in
// declaration order as the compiler does it (each at the next multiple of its alignment, the
// struct padded to its largest alignment). This list sits next to the structs it describes and
// is checked against sizeof at compile time (the static_asserts below): a member added to
// model.hpp or state.hpp without its line here does not build.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "ntn/model.hpp"
#include "ntn/state.hpp"

namespace ntn {

namespace detail {

class Layout {
 public:
  constexpr void add(std::size_t size, std::size_t align) {
    offset_ = (offset_ + align - 1) / align * align + size;
    align_ = std::max(align_, align);
  }
  template <class T>
  constexpr void scalar() {
    add(sizeof(T), alignof(T));
  }
  // std::array<T, N> is a T[N] for N > 0; std::array<T, 0> is an empty struct of its own size.
  template <class T>
  constexpr void array(std::size_t n) {
    if (n > 0) {
      add(n * sizeof(T), alignof(T));
    } else {
      add(sizeof(std::array<T, 0>), alignof(std::array<T, 0>));
    }
  }
  constexpr std::size_t size() const { return (offset_ + align_ - 1) / align_ * align_; }
  constexpr std::size_t align() const { return align_; }

 private:
  std::size_t offset_ = 0;
  std::size_t align_ = 1;
};

}  // namespace detail

// sizeof(Model<S>), member by member (model.hpp).
constexpr std::size_t model_footprint(const Sizes& s) {
  const std::size_t dofs = kDofsPerNode * s.nodes;
  const std::size_t hinge_nodes = s.hinges > 0 ? s.nodes : 0;  // Model::kHingeNodes
  const std::size_t blocks = beam_blocks(s.elements);
  detail::Layout l;
  l.array<BeamBlock>(blocks);                   // beams
  l.array<BeamRotations>(blocks);               // rotations
  l.array<double>(dofs);                        // mass
  l.array<double>(dofs);                        // inv_mass
  l.array<double>(dofs);                        // damping
  l.scalar<double>();                           // alpha
  l.scalar<double>();                           // beta
  l.array<double>(dofs);                        // u0
  l.array<double>(dofs);                        // v0
  l.array<std::uint8_t>(s.nodes);               // fixed
  l.array<std::int32_t>(s.nodes);               // supported_nodes
  l.scalar<int>();                              // num_supported
  l.array<TimePoint>(s.time_points);            // time_points
  l.array<TimeFunctionSpec>(s.time_functions);  // time_functions
  l.array<LoadSpec>(s.loads);                   // loads
  l.array<ElementLoadSpec>(s.element_loads);    // element_loads
  l.array<HysteresisData>(s.hystereses);        // hystereses
  l.array<std::int32_t>(s.loads + s.inputs);    // slot_dof
  l.array<std::int32_t>(s.loads);               // load_slot
  l.array<std::int32_t>(s.inputs);              // input_slot
  l.scalar<int>();                              // num_slots
  l.array<InputSpec>(s.inputs);                 // inputs
  l.array<OutputSpec>(s.outputs);               // outputs
  l.scalar<std::array<double, 3>>();            // gravity
  l.scalar<int>();                              // gravity_function
  l.scalar<double>();                           // dt
  l.scalar<StableStepReport>();                 // stable
  l.array<HingeData>(s.hinges);                 // hinges
  l.array<CurvePoint>(s.curve_points);          // curve_points
  l.array<ForestEdge>(s.hinges);                // edges
  l.array<ForestEdgeMatrices>(s.hinges);        // edge_matrices
  l.array<ForestRoot>(s.hinges);                // roots
  l.array<std::int32_t>(s.hinges);              // hinge_edge
  l.array<std::int32_t>(hinge_nodes);           // node_tree
  l.array<std::uint8_t>(hinge_nodes);           // held
  l.array<double>(kDofsPerNode * hinge_nodes);  // residual_scale
  l.array<std::int32_t>(s.hinges);              // spring_hinges
  l.array<std::int32_t>(s.hinges);              // branch_hinges
  l.array<std::int32_t>(s.hinges);              // project_edges
  l.array<ForestTree>(s.hinges);                // trees
  l.array<std::int32_t>(s.hinges);              // tree_stops
  l.array<std::int32_t>(s.hinges);              // slip_hinges
  l.array<double>(s.hystereses * kSlipBlock);   // slip_mobility
  l.array<double>(s.hystereses * kSlipBlock);   // slip_factor
  l.scalar<int>();                              // num_edges
  l.scalar<int>();                              // num_roots
  l.scalar<int>();                              // num_spring_hinges
  l.scalar<int>();                              // num_branch_hinges
  l.scalar<int>();                              // num_project_edges
  l.scalar<int>();                              // num_trees
  l.scalar<int>();                              // num_slip_hinges
  l.scalar<int>();                              // num_slip_normals
  l.scalar<int>();                              // held_dofs
  l.scalar<HingeMethod>();                      // hinge_method
  l.scalar<ClampRule>();                        // clamp
  l.scalar<double>();                           // inv_dt
  l.scalar<Substeps>();                         // substeps
  l.scalar<ElementPass>();                      // element_pass
  return l.size();
}

// sizeof(State<S>) (state.hpp).
constexpr std::size_t state_footprint(const Sizes& s) {
  const std::size_t dofs = kDofsPerNode * s.nodes;
  detail::Layout l;
  l.array<double>(dofs);                         // u
  l.array<double>(dofs);                         // v
  l.array<double>(s.inputs);                     // held_inputs
  l.scalar<std::int64_t>();                      // tick
  l.scalar<std::uint64_t>();                     // inputs_held
  l.scalar<std::uint64_t>();                     // inputs_out_of_range
  l.scalar<std::uint32_t>();                     // faults
  l.array<double>(s.hystereses);                 // plastic
  l.array<double>(s.hystereses);                 // dissipated
  l.array<double>(s.hystereses);                 // plastic_peak
  l.array<std::array<double, 4>>(s.hystereses);  // excursion
  l.array<std::int64_t>(s.hystereses);           // first_slip
  l.array<std::int8_t>(s.hystereses);            // slip_state
  return l.size();
}

// sizeof(ClampWork<S>) and its alignment (state.hpp): the momentum clamp's workspace.
constexpr detail::Layout clamp_work_layout(const Sizes& s) {
  const std::size_t dofs = s.hinges > 0 ? kDofsPerNode * s.nodes : 0;
  detail::Layout l;
  l.array<double>(dofs);                              // impulse
  l.array<double>(dofs);                              // response
  l.array<std::int64_t>(s.hinges > 0 ? s.nodes : 0);  // moved
  l.array<std::int64_t>(s.hinges);                    // checked
  l.scalar<std::int64_t>();                           // events
  return l;
}
constexpr std::size_t clamp_work_footprint(const Sizes& s) {
  return clamp_work_layout(s).size();
}
constexpr std::size_t clamp_work_align(const Sizes& s) {
  return clamp_work_layout(s).align();
}

// sizeof(Scratch<S>) (state.hpp).
constexpr std::size_t scratch_footprint(const Sizes& s) {
  const std::size_t dofs = kDofsPerNode * s.nodes;
  detail::Layout l;
  l.array<double>(kDofsPerNode);                        // load_g
  l.array<double>(s.loads + s.inputs);                  // p_slot
  l.array<double>(dofs);                                // f
  l.array<double>(dofs);                                // a
  l.array<double>(s.hinges > 0 ? dofs : 0);             // r
  l.array<double>(s.outputs);                           // outputs
  l.array<double>(s.hystereses);                        // slip_force
  l.array<double>(s.hystereses);                        // slip_normal
  l.add(clamp_work_footprint(s), clamp_work_align(s));  // clamp (ClampWork)
  l.scalar<std::array<double, 3>>();                    // ground
  l.scalar<double>();                                   // time
  return l.size();
}

// Model + State + Scratch: what a model of these sizes takes in memory.
constexpr std::size_t footprint(const Sizes& s) {
  return model_footprint(s) + state_footprint(s) + scratch_footprint(s);
}

namespace detail {

template <Sizes S>
constexpr bool footprint_exact() {
  return model_footprint(S) == sizeof(Model<S>) && state_footprint(S) == sizeof(State<S>) &&
         clamp_work_footprint(S) == sizeof(ClampWork<S>) &&
         clamp_work_align(S) == alignof(ClampWork<S>) && scratch_footprint(S) == sizeof(Scratch<S>);
}

// Every optional array empty; odd counts (padding); hinges, curves, curve points, one by one.
static_assert(footprint_exact<Sizes{2, 1, 0, 0, 0, 0, 0}>());
static_assert(footprint_exact<Sizes{3, 2, 1, 1, 1, 1, 1}>());
static_assert(footprint_exact<Sizes{5, 4, 3, 7, 3, 2, 5}>());
static_assert(footprint_exact<Sizes{3, 2, 0, 0, 0, 0, 0, 1, 0, 0}>());
static_assert(footprint_exact<Sizes{9, 7, 1, 2, 1, 1, 5, 5, 1, 4}>());
static_assert(footprint_exact<Sizes{5, 4, 0, 0, 0, 0, 1, 3, 2, 7}>());
static_assert(footprint_exact<Sizes{7, 3, 0, 0, 0, 0, 0, 0, 1, 2}>());

}  // namespace detail

}  // namespace ntn
