// The members of Model, State, Scratch (with its ClampWork), InitWorkspace and TeamWork, in
// declaration order, each array with its length at sizes `s`: the one list of what each struct
// holds. Two things read it:
//  - the footprint: sizeof of each struct at sizes known only at run time (the model compiler
//    prints it for a model it has not emitted yet), the members laid out as the compiler does
//    it (each at the next multiple of its alignment, the struct padded to its largest
//    alignment);
//  - run-time storage (runtime_storage.hpp), which binds each array to its part of one block.
// The static_asserts below check the list against sizeof at compile time: a member added to a
// struct without its line here does not build.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "ntn/model.hpp"
#include "ntn/state.hpp"
#include "ntn/team.hpp"

namespace ntn {

// Each list calls v(&M::array, length) for an array member and v(&M::member) for any other, M
// the struct in run-time storage (its arrays are Slices: the element type is the Slice's).

template <class V>
constexpr void model_members(const Sizes& s, V&& v) {
  using M = Model<kRunTime>;
  const std::size_t dofs = kDofsPerNode * s.nodes;
  const std::size_t hinge_nodes = s.hinges > 0 ? s.nodes : 0;  // Model::kHingeNodes
  const std::size_t blocks = beam_blocks(s.elements);
  v(&M::beams, blocks);
  v(&M::rotations, blocks);
  v(&M::stiffness, blocks);
  v(&M::num_stiffness);
  v(&M::every_node_in_element);
  v(&M::element_slot, s.elements);
  v(&M::geometric, s.geometric);
  v(&M::geometric_blocks, beam_blocks(s.geometric));
  v(&M::geometric_rotations, beam_blocks(s.geometric));
  v(&M::corotational, s.corotational);
  v(&M::mass, dofs);
  v(&M::inv_mass, dofs);
  v(&M::mass_table, mass_groups(s.nodes));
  v(&M::mass_entry, mass_groups(s.nodes));
  v(&M::num_mass_entries);
  v(&M::damping, dofs);
  v(&M::alpha);
  v(&M::beta);
  v(&M::damping_velocity);
  v(&M::mass_factor);
  v(&M::u0, dofs);
  v(&M::v0, dofs);
  v(&M::fixed, s.nodes);
  v(&M::supported_nodes, s.nodes);
  v(&M::num_supported);
  v(&M::time_points, s.time_points);
  v(&M::time_functions, s.time_functions);
  v(&M::loads, s.loads);
  v(&M::element_loads, s.element_loads);
  v(&M::hystereses, s.hystereses);
  v(&M::slot_dof, s.loads + s.inputs);
  v(&M::load_slot, s.loads);
  v(&M::input_slot, s.inputs);
  v(&M::num_slots);
  v(&M::inputs, s.inputs);
  v(&M::outputs, s.outputs);
  v(&M::gravity);
  v(&M::gravity_function);
  v(&M::dt);
  v(&M::stable);
  v(&M::hinges, s.hinges);
  v(&M::curve_points, s.curve_points);
  v(&M::edges, s.hinges);
  v(&M::edge_matrices, s.hinges);
  v(&M::roots, s.hinges);
  v(&M::hinge_edge, s.hinges);
  v(&M::node_tree, hinge_nodes);
  v(&M::held, hinge_nodes);
  v(&M::residual_scale, kDofsPerNode * hinge_nodes);
  v(&M::spring_hinges, s.hinges);
  v(&M::branch_hinges, s.hinges);
  v(&M::project_edges, s.hinges);
  v(&M::trees, s.hinges);
  v(&M::tree_stops, s.hinges);
  v(&M::slip_hinges, s.hinges);
  v(&M::slip_mobility, s.hystereses * kSlipBlock);
  v(&M::slip_factor, s.hystereses * kSlipBlock);
  v(&M::num_edges);
  v(&M::num_roots);
  v(&M::num_spring_hinges);
  v(&M::num_branch_hinges);
  v(&M::num_project_edges);
  v(&M::num_trees);
  v(&M::num_slip_hinges);
  v(&M::num_slip_normals);
  v(&M::held_dofs);
  v(&M::hinge_method);
  v(&M::clamp);
  v(&M::inv_dt);
  v(&M::substeps);
  v(&M::element_pass);
  v(&M::books);
}

template <class V>
constexpr void state_members(const Sizes& s, V&& v) {
  using M = State<kRunTime>;
  const std::size_t dofs = kDofsPerNode * s.nodes;
  v(&M::u, dofs);
  v(&M::v, dofs);
  v(&M::held_inputs, s.inputs);
  v(&M::tick);
  v(&M::inputs_held);
  v(&M::inputs_out_of_range);
  v(&M::faults);
  v(&M::geometry_bound);
  v(&M::plastic, s.hystereses);
  v(&M::dissipated, s.hystereses);
  v(&M::plastic_peak, s.hystereses);
  v(&M::law_state, s.hystereses);
  v(&M::first_slip, s.hystereses);
  v(&M::slip_state, s.hystereses);
  v(&M::rotation, s.corotational > 0 ? s.nodes : 0);
}

template <class V>
constexpr void clamp_work_members(const Sizes& s, V&& v) {
  using M = ClampWork<kRunTime>;
  const std::size_t dofs = s.hinges > 0 ? kDofsPerNode * s.nodes : 0;
  v(&M::impulse, dofs);
  v(&M::response, dofs);
  v(&M::moved, s.hinges > 0 ? s.nodes : 0);
  v(&M::checked, s.hinges);
  v(&M::events);
  v(&M::step_events);
  v(&M::h2);
  v(&M::v_rate);
  v(&M::a_scale);
  v(&M::start_u, dofs);
}

template <class V>
constexpr void scratch_members(const Sizes& s, V&& v) {
  using M = Scratch<kRunTime>;
  const std::size_t dofs = kDofsPerNode * s.nodes;
  v(&M::load_g);
  v(&M::p_slot, s.loads + s.inputs);
  v(&M::f, dofs);
  v(&M::geometric_rows, 4 * s.geometric);
  v(&M::a, dofs);
  v(&M::r, s.hinges > 0 ? dofs : 0);
  v(&M::outputs, s.outputs);
  v(&M::slip_force, s.hystereses);
  v(&M::slip_normal, s.hystereses);
  v(&M::stop_force, s.hinges);
  v(&M::group_books, book_groups(s.nodes));
  v(&M::books);
  v(&M::dashpot_force, s.hinges);
  v(&M::clamp);  // a ClampWork: clamp_work_members
  v(&M::ground);
  v(&M::time);
}

template <class V>
constexpr void init_workspace_members(const Sizes& s, V&& v) {
  using M = InitWorkspace<kRunTime>;
  const std::size_t dofs = kDofsPerNode * s.nodes;
  v(&M::divided_mass, dofs);
  v(&M::forest, s.hinges);
  v(&M::slip_impulse, s.hystereses > 0 ? dofs : 0);
  v(&M::slip_response, s.hystereses > 0 ? dofs : 0);
  v(&M::slot_used, s.hystereses);
  v(&M::order_elements, s.elements);
  v(&M::order, s.elements);
  v(&M::touched, s.nodes);
}

template <class V>
constexpr void team_work_members(const Sizes& s, V&& v) {
  using M = TeamWork<kRunTime>;
  const std::size_t blocks = beam_blocks(s.elements);
  v(&M::end_forces, 12 * kBeamLanes * blocks);
  v(&M::node_start, s.nodes + 1);
  v(&M::incidence, 2 * s.elements);
  v(&M::block_split);
  v(&M::node_split);
  v(&M::direct, blocks);
  v(&M::shared, s.nodes);
  v(&M::shared_split);
  v(&M::bad);
  v(&M::size);
}

namespace detail {

class Layout {
 public:
  constexpr void add(std::size_t size, std::size_t align) {
    offset_ = (offset_ + align - 1) / align * align + size;
    align_ = std::max(align_, align);
  }
  constexpr std::size_t size() const { return (offset_ + align_ - 1) / align_ * align_; }
  constexpr std::size_t align() const { return align_; }

 private:
  std::size_t offset_ = 0;
  std::size_t align_ = 1;
};

constexpr Layout clamp_work_layout(const Sizes& s);

// A member list's visitor that lays the members out as compiled storage holds them.
class LayoutOf {
 public:
  explicit constexpr LayoutOf(const Sizes& s) : sizes_(s) {}
  // std::array<T, N> is a T[N] for N > 0; std::array<T, 0> is an empty struct of its own size.
  template <class C, class T>
  constexpr void operator()(Slice<T> C::*, std::size_t n) {
    if (n > 0) {
      l_.add(n * sizeof(T), alignof(T));
    } else {
      l_.add(sizeof(std::array<T, 0>), alignof(std::array<T, 0>));
    }
  }
  template <class C, class T>
  constexpr void operator()(T C::*) {
    if constexpr (std::is_same_v<T, ClampWork<kRunTime>>) {
      const Layout c = clamp_work_layout(sizes_);
      l_.add(c.size(), c.align());
    } else {
      l_.add(sizeof(T), alignof(T));
    }
  }
  constexpr const Layout& layout() const { return l_; }

 private:
  Sizes sizes_;
  Layout l_;
};

constexpr Layout clamp_work_layout(const Sizes& s) {
  LayoutOf l(s);
  clamp_work_members(s, l);
  return l.layout();
}

}  // namespace detail

// sizeof(Model<S>), sizeof(State<S>) ... at sizes s.
constexpr std::size_t model_footprint(const Sizes& s) {
  detail::LayoutOf l(s);
  model_members(s, l);
  return l.layout().size();
}
constexpr std::size_t state_footprint(const Sizes& s) {
  detail::LayoutOf l(s);
  state_members(s, l);
  return l.layout().size();
}
constexpr std::size_t clamp_work_footprint(const Sizes& s) {
  return detail::clamp_work_layout(s).size();
}
constexpr std::size_t clamp_work_align(const Sizes& s) {
  return detail::clamp_work_layout(s).align();
}
constexpr std::size_t scratch_footprint(const Sizes& s) {
  detail::LayoutOf l(s);
  scratch_members(s, l);
  return l.layout().size();
}
constexpr std::size_t init_workspace_footprint(const Sizes& s) {
  detail::LayoutOf l(s);
  init_workspace_members(s, l);
  return l.layout().size();
}
constexpr std::size_t team_work_footprint(const Sizes& s) {
  detail::LayoutOf l(s);
  team_work_members(s, l);
  return l.layout().size();
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
         clamp_work_align(S) == alignof(ClampWork<S>) &&
         scratch_footprint(S) == sizeof(Scratch<S>) &&
         init_workspace_footprint(S) == sizeof(InitWorkspace<S>) &&
         team_work_footprint(S) == sizeof(TeamWork<S>);
}

// Every optional array empty; odd counts (padding); hinges, curves, curve points, one by one.
static_assert(footprint_exact<Sizes{2, 1, 0, 0, 0, 0, 0}>());
static_assert(footprint_exact<Sizes{3, 2, 1, 1, 1, 1, 1}>());
static_assert(footprint_exact<Sizes{5, 4, 3, 7, 3, 2, 5}>());
static_assert(footprint_exact<Sizes{3, 2, 0, 0, 0, 0, 0, 1, 0, 0}>());
static_assert(footprint_exact<Sizes{9, 7, 1, 2, 1, 1, 5, 5, 1, 4}>());
static_assert(footprint_exact<Sizes{5, 4, 0, 0, 0, 0, 1, 3, 2, 7}>());
static_assert(footprint_exact<Sizes{7, 3, 0, 0, 0, 0, 0, 0, 1, 2}>());
static_assert(footprint_exact<Sizes{4, 3, 0, 0, 0, 2, 3, 2, 0, 0, 1, 3}>());  // hystereses
static_assert(
    footprint_exact<Sizes{.nodes = 5, .elements = 4, .geometric = 1, .corotational = 3}>());

}  // namespace detail

}  // namespace ntn
