// init(): the constant Model built from its spec, as a list of named stages (DESIGN §2). No
// heap: `model` and `work` are caller-owned (usually static); `work` is scratch for the call.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "ntn/beam.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/dof_pass.hpp"
#include "ntn/element_order.hpp"
#include "ntn/element_pass.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/hysteresis.hpp"
#include "ntn/model.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/status.hpp"
#include "ntn/time_step.hpp"

namespace ntn {

// The model's element order of a spec (element_order.hpp): order[k] = the file index of the k-th
// element; `elements` holds one OrderElement per element (an element whose geometry is invalid,
// which init() refuses, counts as a general rotation). init() and every tool take the order here.
inline void spec_element_order(const SpecView& spec, std::span<OrderElement> elements,
                               std::span<std::int32_t> order) {
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const ElementSpec& e = spec.elements[i];
    const BeamGeometry g = beam_geometry(spec.nodes[static_cast<std::size_t>(e.node_i)],
                                         spec.nodes[static_cast<std::size_t>(e.node_j)], e);
    elements[i] = {e.node_i, e.node_j,
                   g.check == ElementCheck::kOk ? axis_map(g.rotation) : kGeneralAxes};
  }
  element_order(std::span<const OrderElement>(elements.data(), spec.elements.size()), order);
}

// Lumped masses of a model of any size: out[6 n + d] (HRZ element ends plus point masses), the
// element ends summed at each node in the model's element order (`order`, spec_element_order), so
// that the masses, like the element blocks, do not depend on the order the file lists the
// elements in. A node that a corotational element reaches takes the largest of its three rotary
// inertias about all three axes: lumped in global axes, an element's small torsional inertia would
// otherwise pair with its bending stiffness once the element has turned (and the stable step,
// taken in the reference orientation, would no longer hold); an isotropic inertia turns with
// nothing, and makes the node's spin equation J w' = M exact (no gyroscopic term).
inline void assemble_lumped_mass(const SpecView& spec, std::span<const std::int32_t> order,
                                 std::span<double> out) {
  for (double& m : out)
    m = 0;
  for (std::size_t k = 0; k < spec.elements.size(); ++k) {
    const ElementSpec& e = spec.elements[static_cast<std::size_t>(order[k])];
    const NodeSpec& a = spec.nodes[static_cast<std::size_t>(e.node_i)];
    const NodeSpec& b = spec.nodes[static_cast<std::size_t>(e.node_j)];
    const BeamGeometry g = beam_geometry(a, b, e);
    if (g.check != ElementCheck::kOk) continue;
    const auto m = beam_end_mass(e, g, spec.settings.rotary_inertia);
    for (int d = 0; d < kDofsPerNode; ++d) {
      out[static_cast<std::size_t>(kDofsPerNode * e.node_i + d)] += m[static_cast<std::size_t>(d)];
      out[static_cast<std::size_t>(kDofsPerNode * e.node_j + d)] += m[static_cast<std::size_t>(d)];
    }
  }
  for (std::size_t n = 0; n < spec.nodes.size(); ++n) {
    for (int d = 0; d < kDofsPerNode; ++d) {
      out[n * kDofsPerNode + static_cast<std::size_t>(d)] +=
          spec.nodes[n].added[static_cast<std::size_t>(d)];
    }
  }
  for (const ElementSpec& e : spec.elements) {
    if (e.geometry != Geometry::kCorotational) continue;
    for (const int n : {e.node_i, e.node_j}) {
      double* j = &out[static_cast<std::size_t>(kDofsPerNode * n + 3)];
      const double largest = std::max(j[0], std::max(j[1], j[2]));
      j[0] = j[1] = j[2] = largest;
    }
  }
}

// Every index in the spec is in range, so step() can index without checks.
template <Sizes S>
[[nodiscard]] InitStatus check_references(const ModelSpec<S>& spec, InitWorkspace<S>& work) {
  const Sizes& sz = work.sizes;
  auto node_ok = [&](int n) { return n >= 0 && std::cmp_less(n, sz.nodes); };
  auto dof_ok = [](int d, int n) { return d >= 0 && d < n; };
  auto function_ok = [&](int f) {
    return f == kConstant || (f >= 0 && std::cmp_less(f, sz.time_functions));
  };
  for (std::size_t i = 0; i < sz.elements; ++i) {
    const ElementSpec& e = spec.elements[i];
    if (!node_ok(e.node_i) || !node_ok(e.node_j))
      return {InitError::kBadReference, static_cast<int>(i)};
  }
  for (std::size_t f = 0; f < sz.time_functions; ++f) {
    const TimeFunctionSpec& tf = spec.time_functions[f];
    if (tf.count < 1 || tf.first < 0 || std::cmp_greater(tf.first + tf.count, sz.time_points))
      return {InitError::kBadTimeFunction, static_cast<int>(f)};
    for (int k = tf.first + 1; k < tf.first + tf.count; ++k) {
      if (!(spec.time_points[static_cast<std::size_t>(k)].t >
            spec.time_points[static_cast<std::size_t>(k - 1)].t))
        return {InitError::kBadTimeFunction, static_cast<int>(f)};
    }
  }
  for (std::size_t i = 0; i < sz.loads; ++i) {
    const LoadSpec& l = spec.loads[i];
    if (!node_ok(l.node) || !dof_ok(l.dof, kDofsPerNode) || !function_ok(l.time_function))
      return {InitError::kBadReference, static_cast<int>(i)};
  }
  for (std::size_t i = 0; i < sz.element_loads; ++i) {
    const ElementLoadSpec& l = spec.element_loads[i];
    if (l.element < 0 || !std::cmp_less(l.element, sz.elements) || !function_ok(l.time_function))
      return {InitError::kBadReference, static_cast<int>(i)};
  }
  if (!function_ok(spec.settings.gravity_function)) return {InitError::kBadReference, -1};
  auto& slot_used = work.slot_used;  // each history slot has one direction
  slot_used.fill(0);
  for (std::size_t i = 0; i < sz.hinges; ++i) {
    HingeData h;
    if (!make_hinge_data(spec.hinges[i], spec.settings, sz.nodes, spec.curves, spec.curve_points,
                         h))
      return {InitError::kBadHinge, static_cast<int>(i)};
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!(((h.plastic | h.slip) >> k) & 1U)) continue;
      const auto slot = static_cast<std::size_t>(h.history[k]);
      if (slot >= sz.hystereses ||
          !hysteresis_valid(spec.hystereses[slot], h.stiffness[k], h.dashpot[k]) ||
          slot_used[slot] != 0)
        return {InitError::kBadHinge, static_cast<int>(i)};
      // A rigid-plastic direction's law: bilinear, perfectly plastic (slip.hpp), hardening with
      // the slip only as its parallel spring (HingeSpec::stiffness, plain yields), or brittle.
      // Friction and fixed_if only on a slip direction (ntn_exact) whose normal is another
      // direction of the hinge that is not a slip direction itself and not a stop (its force at
      // t_n is known before the slip stage; a stop's comes after it).
      const HysteresisSpec& law = spec.hystereses[slot];
      if (h.behaviour[k] == HingeBehaviour::kRigidPlastic &&
          (!law_slips(law.rule) || law.hardening != 0 ||
           (spec.hinges[i].stiffness[k] != 0 &&
            (law.rule != HysteresisRule::kBilinear || law.normal >= 0))))
        return {InitError::kBadHinge, static_cast<int>(i)};
      if (law.normal >= 0 && (!((h.slip >> k) & 1U) || law.normal == static_cast<int>(k) ||
                              (((h.slip | h.branches) >> law.normal) & 1U)))
        return {InitError::kBadHinge, static_cast<int>(i)};
      if (law.circle >= 0) {  // the partner: a friction direction of the hinge, the same law
        const auto c = static_cast<std::size_t>(law.circle);
        if (c == k || c / 3 != k / 3 || !((h.slip >> c) & 1U) ||
            static_cast<std::size_t>(h.history[c]) >= sz.hystereses)
          return {InitError::kBadHinge, static_cast<int>(i)};
        const HysteresisSpec& other = spec.hystereses[static_cast<std::size_t>(h.history[c])];
        if (other.circle != static_cast<int>(k) || other.normal != law.normal ||
            other.mu != law.mu || other.cohesion != law.cohesion)
          return {InitError::kBadHinge, static_cast<int>(i)};
      }
      slot_used[slot] = 1;
    }
  }
  for (std::size_t i = 0; i < sz.inputs; ++i) {
    const InputSpec& in = spec.inputs[i];
    const bool ok = in.kind == InputKind::kGroundAcceleration
                        ? dof_ok(in.dof, 3)
                        : node_ok(in.node) && dof_ok(in.dof, kDofsPerNode);
    if (!ok || !(in.min <= in.max)) return {InitError::kBadInput, static_cast<int>(i)};
  }
  for (std::size_t i = 0; i < sz.outputs; ++i) {
    const OutputSpec& o = spec.outputs[i];
    bool ok = dof_ok(o.dof, kDofsPerNode);
    switch (o.kind) {
      case OutputKind::kElementForce:
        ok = ok && o.element >= 0 && std::cmp_less(o.element, sz.elements) &&
             (o.end == 0 || o.end == 1);
        break;
      case OutputKind::kDrift:
        ok = ok && node_ok(o.node) && node_ok(o.node2);
        break;
      case OutputKind::kReaction:
        break;
      case OutputKind::kHingeForce:
      case OutputKind::kHingeDisplacement:
      case OutputKind::kHingePlastic:
      case OutputKind::kHingeDissipated:
      case OutputKind::kHingeLevel:
      case OutputKind::kHingeVelocity:
      case OutputKind::kHingeSlipState:
        ok = ok && o.hinge >= 0 && std::cmp_less(o.hinge, sz.hinges);
        break;
      default:
        ok = ok && node_ok(o.node);
        break;
    }
    if (!ok) return {InitError::kBadOutput, static_cast<int>(i)};
  }
  return {};
}

// The elements of `v` in the model's order (`order`, element_order.hpp) into their blocks (zeroed
// by the caller), each block's stiffness into the table, then the blocks of equal stiffness made to
// share one entry (dedupe_stiffness); element_slot[e] is element e's place in the order. Returns
// the number of distinct stiffness entries. init() builds the model with it, and the model
// compiler reports what it gives (ntn-model info).
inline std::size_t fill_beam_blocks(const SpecView& v, std::span<const std::int32_t> order,
                                    BeamBlock* blocks, BeamRotations* rotations,
                                    BeamStiffnessBlock* stiffness, std::int32_t* element_slot) {
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto i = static_cast<std::size_t>(order[k]);
    const ElementSpec& e = v.elements[i];
    const BeamGeometry g = beam_geometry(v.nodes[static_cast<std::size_t>(e.node_i)],
                                         v.nodes[static_cast<std::size_t>(e.node_j)], e);
    BeamData b;
    b.node_i = e.node_i, b.node_j = e.node_j;
    b.rotation = g.rotation;
    // A corotational element's force is the corotational stage's: none in the element pass.
    if (e.geometry != Geometry::kCorotational) b.k = beam_stiffness(e, g.length);
    set_lane(blocks, rotations, stiffness, k / kBeamLanes, k % kBeamLanes, b);
    element_slot[i] = static_cast<std::int32_t>(k);
  }
  return dedupe_stiffness(blocks, stiffness, beam_blocks(order.size()));
}

namespace detail {

// The storage was bound for this model (runtime_storage.hpp), with at least one node.
template <Sizes S>
InitStatus init_sizes(const ModelSpec<S>& spec, const Model<S>& model,
                      const InitWorkspace<S>& work) {
  const Sizes& sz = model.sizes;
  if constexpr (S.runtime) {
    if (sizes_of(view(spec)) != sz || work.sizes != sz) return {InitError::kStorageSizes, -1};
    if (sz.nodes < 1) return {InitError::kStorageSizes, -1};
  } else {
    static_assert(S.nodes >= 1, "a model needs at least one node");  // elements: none or more
  }
  return {};
}

// Each element's properties and geometry.
template <Sizes S>
InitStatus init_check_elements(const ModelSpec<S>& spec, const Sizes& sz) {
  for (std::size_t i = 0; i < sz.elements; ++i) {
    const ElementSpec& e = spec.elements[i];
    const int where = static_cast<int>(i);
    if (!beam_properties_valid(e)) return {InitError::kBadProperty, where};
    const BeamGeometry g = beam_geometry(spec.nodes[static_cast<std::size_t>(e.node_i)],
                                         spec.nodes[static_cast<std::size_t>(e.node_j)], e);
    if (g.check == ElementCheck::kZeroLength) return {InitError::kZeroLength, where};
    if (g.check == ElementCheck::kOrientationParallel) return {InitError::kOrientation, where};
  }
  return {};
}

// The elements in their order and blocks, the shared stiffness table, the lumped mass.
template <Sizes S>
void init_elements(const SpecView& v, std::span<const std::int32_t> order, Model<S>& model,
                   InitWorkspace<S>& work) {
  const Sizes& sz = model.sizes;
  // The model's order (element_order.hpp), then each element into its lane, then the blocks of
  // equal stiffness made to share one entry of the table.
  spec_element_order(v, std::span<OrderElement>(work.order_elements.data(), sz.elements),
                     std::span<std::int32_t>(work.order.data(), sz.elements));
  model.beams.fill(BeamBlock{});
  model.rotations.fill(BeamRotations{});
  model.stiffness.fill(BeamStiffnessBlock{});
  model.num_stiffness = fill_beam_blocks(v, order, model.beams.data(), model.rotations.data(),
                                         model.stiffness.data(), model.element_slot.data());
  model.every_node_in_element =
      mark_first_ends(model.beams.data(), sz.elements, sz.nodes, work.touched.data());

  model.num_supported = 0;
  assemble_lumped_mass(v, order, model.mass);
}

// Hinges (DESIGN §7), with the step mass the accelerations divide by (work.divided_mass).
template <Sizes S>
InitStatus init_hinges(const ModelSpec<S>& spec, Model<S>& model, InitWorkspace<S>& work) {
  const Sizes& sz = model.sizes;
  // Hinges (DESIGN §7): each hinge resolved for the method, the lists the step visits, then
  // what the method precomputes (the forest, or the S 22-26 masses in work.divided_mass).
  model.hinge_method = spec.settings.hinge_method;
  model.clamp = spec.settings.clamp;
  work.divided_mass = model.mass;
  // The step mass M_e = (1 + alpha dt/2) M of damping_velocity = "central" (Model::mass_factor):
  // 1 without alpha, and for a dt that is refused below (not positive, NaN).
  model.damping_velocity = spec.settings.damping_velocity;
  model.mass_factor = model.damping_velocity == DampingVelocity::kCentral &&
                              spec.settings.alpha > 0 && spec.settings.dt > 0
                          ? 1.0 + spec.settings.alpha * (0.5 * spec.settings.dt)
                          : 1.0;
  if (model.mass_factor != 1.0) {
    for (double& x : work.divided_mass)
      x *= model.mass_factor;
  }
  if constexpr (kMayHaveHinges<S>) {
    if (sz.hinges > 0) {
      const std::span<const ElementSpec> elements(spec.elements.data(), sz.elements);
      for (std::size_t i = 0; i < sz.hinges; ++i) {
        HingeData& h = model.hinges[i];
        (void)make_hinge_data(spec.hinges[i], spec.settings, sz.nodes, spec.curves,
                              spec.curve_points, h);
        h.turns = sz.corotational > 0 && corotational_hinge_node(spec.hinges[i], elements) >= 0;
        if (h.turns && !turning_hinge_check(h, spec.settings).ok())
          return {InitError::kCorotationalHinge, static_cast<int>(i)};
      }
      model.curve_points = spec.curve_points;
      model.num_edges = model.num_roots = model.held_dofs = 0;
      model.num_spring_hinges = model.num_branch_hinges = model.num_project_edges = 0;
      model.num_slip_hinges = model.num_slip_normals = 0;
      model.num_trees = 0;
      for (std::size_t i = 0; i < sz.hinges; ++i) {
        const HingeData& h = model.hinges[i];
        const auto hinge = static_cast<std::int32_t>(i);
        if (h.springs != 0)
          model.spring_hinges[static_cast<std::size_t>(model.num_spring_hinges++)] = hinge;
        if (h.branches != 0)
          model.branch_hinges[static_cast<std::size_t>(model.num_branch_hinges++)] = hinge;
        if (h.slip != 0)
          model.slip_hinges[static_cast<std::size_t>(model.num_slip_hinges++)] = hinge;
        for (std::size_t k = 0; h.slip != 0 && k < kDofsPerNode; ++k) {
          if ((h.slip >> k) & 1U)
            model.num_slip_normals +=
                spec.hystereses[static_cast<std::size_t>(h.history[k])].normal >= 0 ? 1 : 0;
        }
      }
      for (auto& e : model.hinge_edge)
        e = -1;
      for (auto& t : model.node_tree)
        t = -1;
      for (auto& h : model.held)
        h = 0;
      if (const InitStatus st = hinge_method_init(spec, model, work); !st.ok()) return st;
    }
  }

  return {};
}

// Per node and DOF: supports, damping, the initial state, the inverse mass (or a held
// mechanism DOF).
template <Sizes S>
InitStatus init_nodes(const ModelSpec<S>& spec, Model<S>& model, const InitWorkspace<S>& work) {
  const Sizes& sz = model.sizes;
  for (std::size_t n = 0; n < sz.nodes; ++n) {
    const std::uint8_t fixed = spec.nodes[n].fixed;
    model.fixed[n] = fixed;
    if (fixed != 0)
      model.supported_nodes[static_cast<std::size_t>(model.num_supported++)] =
          static_cast<std::int32_t>(n);
    bool in_tree = false;
    if constexpr (kMayHaveHinges<S>) in_tree = sz.hinges > 0 && model.node_tree[n] >= 0;
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      const std::size_t j = kDofsPerNode * n + d;
      model.damping[j] = spec.settings.alpha * model.mass[j];  // residual() recomputes it so
      model.u0[j] = spec.nodes[n].u0[d];
      model.v0[j] = spec.nodes[n].v0[d];
      double inv = 0.0;
      if (((fixed >> d) & 1U) || in_tree) {  // a tree's accelerations come from the forest
      } else if (!(work.divided_mass[j] > 0)) {
        // No mass: without hinges the node has no element and no point mass, which the model
        // compiler refuses; with hinges it is a mechanism (DESIGN §7.1), held at zero. A spring
        // on it makes the stable step zero, which is refused below.
        if (!kMayHaveHinges<S> || sz.hinges == 0) {
          return {InitError::kMassless, static_cast<int>(j)};
        } else {
          model.held[n] |= static_cast<std::uint8_t>(1U << d);
          ++model.held_dofs;
        }
      } else {
        inv = 1.0 / work.divided_mass[j];
      }
      model.inv_mass[j] = inv;
      if constexpr (kMayHaveHinges<S>) {
        if (sz.hinges > 0) model.residual_scale[j] = in_tree ? 1.0 : inv;
      }
    }
  }

  return {};
}

// Damping coefficients and the load slots of loads and force inputs.
template <Sizes S>
void init_slots(const ModelSpec<S>& spec, Model<S>& model) {
  const Sizes& sz = model.sizes;
  model.alpha = spec.settings.alpha;
  model.beta = spec.settings.beta;
  // Load slots: each DOF with a nodal load or a force input once, in increasing DOF order (the DOF
  // pass meets them node by node: residual_update). A slot sums its loads, then its inputs, in
  // the model's order whatever its number.
  model.num_slots = 0;
  auto add_slot = [&](int dof) {
    int k = 0;
    while (k < model.num_slots && model.slot_dof[static_cast<std::size_t>(k)] < dof)
      ++k;
    if (k < model.num_slots && model.slot_dof[static_cast<std::size_t>(k)] == dof) return;
    for (int i = model.num_slots; i > k; --i)
      model.slot_dof[static_cast<std::size_t>(i)] = model.slot_dof[static_cast<std::size_t>(i - 1)];
    model.slot_dof[static_cast<std::size_t>(k)] = dof;
    ++model.num_slots;
  };
  auto slot_of = [&](int dof) {
    int k = 0;
    while (model.slot_dof[static_cast<std::size_t>(k)] != dof)
      ++k;
    return k;
  };
  for (const LoadSpec& l : spec.loads)
    add_slot(kDofsPerNode * l.node + l.dof);
  for (const InputSpec& in : spec.inputs) {
    if (in.kind == InputKind::kNodalForce) add_slot(kDofsPerNode * in.node + in.dof);
  }
  for (std::size_t i = 0; i < sz.loads; ++i) {
    const LoadSpec& l = spec.loads[i];
    model.load_slot[i] = slot_of(kDofsPerNode * l.node + l.dof);
  }
  for (std::size_t i = 0; i < sz.inputs; ++i) {
    const InputSpec& in = spec.inputs[i];
    model.input_slot[i] =
        in.kind == InputKind::kNodalForce ? slot_of(kDofsPerNode * in.node + in.dof) : -1;
  }

  model.time_points = spec.time_points;
  model.time_functions = spec.time_functions;
  model.loads = spec.loads;
  model.element_loads = spec.element_loads;
}

// Each history slot's law (laws/table.hpp) with its direction's elastic stiffness.
template <Sizes S>
void init_laws(const ModelSpec<S>& spec, Model<S>& model) {
  const Sizes& sz = model.sizes;
  if constexpr (S.runtime || S.hystereses > 0) {
    // Each slot's law with its direction's elastic k (a rigid-plastic direction: the penalty
    // stiffness under penalty, 1 under ntn_exact, where the slip stage uses the yields alone and
    // its hardening is a spring of its own).
    for (std::size_t i = 0; i < sz.hinges; ++i) {
      const HingeSpec& hs = spec.hinges[i];
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (hs.behaviour[k] != HingeBehaviour::kPlastic &&
            hs.behaviour[k] != HingeBehaviour::kRigidPlastic)
          continue;
        const auto slot = static_cast<std::size_t>(hs.hysteresis[k]);
        const double k_el = hs.behaviour[k] == HingeBehaviour::kPlastic ? hs.stiffness[k]
                            : (model.hinges[i].plastic >> k) & 1U ? model.hinges[i].stiffness[k]
                                                                  : 1.0;
        HysteresisData& law = model.hystereses[slot];
        law = make_hysteresis(spec.hystereses[slot], k_el);
        if (hs.behaviour[k] == HingeBehaviour::kRigidPlastic &&
            ((model.hinges[i].plastic >> k) & 1U)) {
          // Under penalty, hardening with the slip H in series with the penalty spring k is the
          // bilinear law's back modulus H: its tangent after yield is k H / (k + H).
          law.H = hs.stiffness[k];
          law.inv_kH = 1.0 / (k_el + law.H);
        }
      }
    }
  }
}

// Inputs, outputs, gravity.
template <Sizes S>
void init_channels(const ModelSpec<S>& spec, Model<S>& model) {
  model.inputs = spec.inputs;
  model.outputs = spec.outputs;
  model.gravity = spec.settings.gravity;
  model.gravity_function = spec.settings.gravity_function;
}

// The mass table, the stable step and the step the run takes.
template <Sizes S>
InitStatus init_time_step(const ModelSpec<S>& spec, const SpecView& v, Model<S>& model) {
  const Sizes& sz = model.sizes;
  model.num_mass_entries = fill_mass_table(model.mass.data(), model.inv_mass.data(), sz.nodes,
                                           model.mass_table.data(), model.mass_entry.data());
  model.stable = stable_time_step(v, model.mass);
  model.dt = spec.settings.dt;
  if (!(model.dt > 0)) return {InitError::kBadTimeStep, -1};
  model.inv_dt = 1.0 / model.dt;
  model.substeps = frame_substeps(model.dt, spec.settings.frame_period);
  if (model.dt > model.stable.dt_stable && !spec.settings.allow_unstable) {
    const bool hinge = model.stable.governing_hinge >= 0;
    return {InitError::kTimeStepAboveStable,
            hinge ? model.stable.governing_hinge : model.stable.governing_element};
  }
  return {};
}

// The elements with second-order geometry (p_delta, leaning) and the corotational ones, each
// kind in element order, each element with its stable-step bound (geometric_force_limit,
// geometry.hpp) for the step the run takes; the SIMD pass's blocks of them in the model's order.
template <Sizes S>
void init_geometry(const SpecView& v, std::span<const std::int32_t> order, Model<S>& model) {
  std::size_t k = 0, c = 0;
  for (std::size_t i = 0; i < v.elements.size(); ++i) {
    const ElementSpec& e = v.elements[i];
    if (e.geometry == Geometry::kLinear) continue;
    const NodeSpec& a = v.nodes[static_cast<std::size_t>(e.node_i)];
    const NodeSpec& b = v.nodes[static_cast<std::size_t>(e.node_j)];
    const double length = beam_geometry(a, b, e).length;
    const double limit =
        geometric_force_limit(element_omega_max(e, a, b, v.settings.rotary_inertia), e.rho, e.A,
                              length, model.stable.dt_stable, model.dt);
    const auto index = static_cast<std::int32_t>(i);
    if (e.geometry == Geometry::kCorotational) {
      CorotationalElement& ce = model.corotational[c++];
      (void)corotational_beam(a, b, e, ce.beam);  // init_check_elements passed it
      ce.node_i = e.node_i, ce.node_j = e.node_j, ce.element = index, ce.limit = limit;
      continue;
    }
    GeometricElement& ge = model.geometric[k++];
    ge = geometric_element(e, index, a, b);
    ge.limit = limit;
  }
  fill_geometric_blocks(model.geometric.data(), k, order, model.geometric_blocks.data(),
                        model.geometric_rotations.data());
}

}  // namespace detail

// Builds the constant model from its spec, stage by stage.
template <Sizes S>
[[nodiscard]] InitStatus init(const ModelSpec<S>& spec, Model<S>& model, InitWorkspace<S>& work) {
  using namespace detail;
  if (const InitStatus st = init_sizes(spec, model, work); !st.ok()) return st;
  if (const InitStatus st = check_references(spec, work); !st.ok()) return st;
  if (const InitStatus st = init_check_elements(spec, model.sizes); !st.ok()) return st;
  const SpecView v = view(spec);
  const std::span<const std::int32_t> order(work.order.data(), model.sizes.elements);
  init_elements(v, order, model, work);
  if (const InitStatus st = init_hinges(spec, model, work); !st.ok()) return st;
  if (const InitStatus st = init_nodes(spec, model, work); !st.ok()) return st;
  init_slots(spec, model);
  init_laws(spec, model);
  init_channels(spec, model);
  if (const InitStatus st = init_time_step(spec, v, model); !st.ok()) return st;
  init_geometry(v, order, model);
  return {};
}

}  // namespace ntn
