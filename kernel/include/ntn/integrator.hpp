// Fixed-step central difference (DESIGN §5, seed S 1-8) as a fixed pipeline of stages, step():
// inputs -> loads -> element forces -> hinge springs -> residual -> NTN coupling -> dashpots ->
// outputs -> update -> stops -> constraint projection. The hinge method's stages are
// hinge_methods.hpp's. A model without hinges fuses the residual and the update into one pass after
// the outputs (dof_pass.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

#include "ntn/beam.hpp"
#include "ntn/dashpot.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/hysteresis.hpp"
#include "ntn/loads.hpp"
#include "ntn/model.hpp"
#include "ntn/residual.hpp"
#include "ntn/slip.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"
#include "ntn/team.hpp"

namespace ntn {

namespace detail {

// True for finite x. No libm: x - x is 0 for finite x, NaN for NaN and +-Inf.
inline bool finite(double x) {
  return x - x == 0.0;
}

template <Sizes S>
using Inputs = StepInputs<S>;

// Bad inputs never reach the state (§8): a non-finite value or one outside the channel's
// [min, max] is replaced by the channel's last good value, counted and flagged.
template <Sizes S>
bool accept_inputs(const Model<S>& m, State<S>& s, Inputs<S> in) {
  if constexpr (S.runtime) {  // a span of another length: every channel held
    if (in.size() != m.sizes.inputs) {
      s.inputs_held += m.sizes.inputs;
      s.faults |= kFaultInputHeld;
      return false;
    }
  }
  bool held = false;
  for (std::size_t k = 0; k < m.sizes.inputs; ++k) {
    const double x = in[k];
    if (!finite(x)) {
      held = true;
      ++s.inputs_held;
      s.faults |= kFaultInputHeld;
    } else if (!(x >= m.inputs[k].min && x <= m.inputs[k].max)) {
      held = true;
      ++s.inputs_out_of_range;
      s.faults |= kFaultInputRange;
    } else {
      s.held_inputs[k] = x;
    }
  }
  return !held;
}

// P_n (§5): gravity M g and base excitation -M iota a_g on translations, nodal loads and force
// inputs. M g needs only the vector g - a_g (w.load_g), which the residual pass multiplies by
// each DOF's mass; the load slots (DOFs with nodal loads or force inputs) get their whole P_n,
// in the order of the model's loads, then its inputs.
template <Sizes S>
void apply_loads(const Model<S>& m, const State<S>& s, Scratch<S>& w, double t) {
  const double fg = load_factor(m.time_points, m.time_functions, m.gravity_function, t);
  w.ground = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < m.sizes.inputs; ++i) {
    const InputSpec& in = m.inputs[i];
    if (in.kind == InputKind::kGroundAcceleration) {
      w.ground[static_cast<std::size_t>(in.dof)] += s.held_inputs[i] * in.scale * in.factor;
    }
  }
  w.load_g = {m.gravity[0] * fg - w.ground[0],
              m.gravity[1] * fg - w.ground[1],
              m.gravity[2] * fg - w.ground[2],
              0.0,
              0.0,
              0.0};
  for (int k = 0; k < m.num_slots; ++k) {
    const auto j = static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]);
    w.p_slot[static_cast<std::size_t>(k)] = m.mass[j] * w.load_g[j % kDofsPerNode];
  }
  for (std::size_t i = 0; i < m.sizes.loads; ++i) {
    const LoadSpec& l = m.loads[i];
    w.p_slot[static_cast<std::size_t>(m.load_slot[i])] +=
        l.value * load_factor(m.time_points, m.time_functions, l.time_function, t);
  }
  for (std::size_t i = 0; i < m.sizes.inputs; ++i) {
    const InputSpec& in = m.inputs[i];
    if (in.kind == InputKind::kNodalForce) {
      w.p_slot[static_cast<std::size_t>(m.input_slot[i])] += s.held_inputs[i] * in.scale;
    }
  }
}

// F_n = sum over elements of T^T K_L T u_n, scattered in element order (S 2). With stiffness-
// proportional damping (beta > 0, C = alpha M + beta K_el) the elements' dashpots join in the
// same pass: F_n = sum T^T K_L T (u_n + beta v_{n-1/2}), the velocity lagged (S 3) whatever
// Model::damping_velocity says of alpha M. So the reactions and the NTN constraint forces, which
// come from F_n, include the elements' damping forces; the element-force output channels (K_L T
// u_n) do not. beta = 0 runs the elastic loop alone, unchanged (the same bits). The path, scalar or
// SIMD, is the model's (Model::element_pass): the same bits either way (element_pass.hpp).
template <Sizes S>
void element_forces(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  ntn::element_forces_into(m.element_pass, m.beam_arrays(), m.sizes.elements,
                           m.every_node_in_element, m.dofs(), s.u.data(), s.v.data(), m.beta,
                           w.f.data());
}

// Adds the second-order part of element e's local end force `dof` at `end` (0: node i, 1: node j)
// to `value`, as beam_local_end_forces gives the linear part: -g at node i, g at node j
// (geometry.hpp); nothing for a linear element (not even 0.0: a -0.0 stays what it is). The
// geometric elements are in element order: found by bisection.
template <class E>
std::size_t find_element(const E* elements, std::size_t count, int element) {
  std::size_t lo = 0, hi = count;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (elements[mid].element < element) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo < count && elements[lo].element == element ? lo : count;
}

template <Sizes S>
void add_geometric_end_force(const Model<S>& m, const State<S>& s, int element, int end, int dof,
                             double& value) {
  if (m.sizes.geometric == 0 || dof >= 3) return;
  const std::size_t k = find_element(m.geometric.data(), m.sizes.geometric, element);
  if (k == m.sizes.geometric) return;
  const double g = geometric_force(m.geometric[k], s.u.data()).g[dof];
  value += end == 0 ? -g : g;
}

// A corotational element's end force `dof` at `end` in its corotated frame (the element pass
// gives it none), into `value`; false for another element.
template <Sizes S>
bool corotational_end_force(const Model<S>& m, const State<S>& s, int element, int end, int dof,
                            double& value) {
  if (m.sizes.corotational == 0) return false;
  const std::size_t k = find_element(m.corotational.data(), m.sizes.corotational, element);
  if (k == m.sizes.corotational) return false;
  double f[12];
  corotational_local_end_forces(m.corotational[k], s.u.data(), s.rotation.data(), f);
  value = f[static_cast<std::size_t>(6 * end + dof)];
  return true;
}

// F_n += the second-order forces of the elements with nonlinear geometry (geometry.hpp), in their
// order after the element pass (so the same bits for any team), by the element pass's path (the
// same bits either way), each element past its stable-step bound counted in State::geometry_bound
// and flagged (kFaultGeometryBound). Nothing in a model of linear elements.
template <Sizes S>
void geometric_stage(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if (m.sizes.geometric == 0) return;
  const GeometricArrays a{m.geometric_blocks.data(), m.geometric_rotations.data()};
  const std::size_t over =
      geometric_forces(m.element_pass, a, m.geometric.data(), m.sizes.geometric, s.u.data(),
                       w.f.data(), w.geometric_rows.data());
  if (over == 0) return;
  s.geometry_bound += over;
  s.faults |= kFaultGeometryBound;
}

// F_n += the corotational elements' internal forces at (u_n, Q_n), with their stiffness-
// proportional damping of v_{n-1/2} (corotational.hpp), in element order after the element pass;
// each past its bound counted as geometric_stage counts. Nothing without corotational elements.
template <Sizes S>
void corotational_stage(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if (m.sizes.corotational == 0) return;
  const std::size_t over =
      corotational_forces(m.corotational.data(), m.sizes.corotational, s.u.data(), s.v.data(),
                          s.rotation.data(), m.beta, w.f.data());
  if (over == 0) return;
  s.geometry_bound += over;
  s.faults |= kFaultGeometryBound;
}

// Q_{n+1} = exp(dt w_{n+1/2}) Q_n at every node, with the spin the step's constraint stages left
// in v (corotational.hpp's advance_rotation). Nothing without corotational elements.
template <Sizes S>
void update_rotations(const Model<S>& m, State<S>& s) {
  if (m.sizes.corotational == 0) return;
  for (std::size_t n = 0; n < m.sizes.nodes; ++n)
    s.rotation[n] = advance_rotation(s.rotation[n], &s.v[kNodeDofs * n + 3], m.dt);
}

// Q_0 = exp(theta_0) from the rotational DOFs of u_0 (start()).
template <Sizes S>
void start_rotations(const Model<S>& m, State<S>& s) {
  if (m.sizes.corotational == 0) return;
  for (std::size_t n = 0; n < m.sizes.nodes; ++n) {
    const std::size_t r = kNodeDofs * n + 3;
    s.rotation[n] = exp_rotation({s.u[r], s.u[r + 1], s.u[r + 2]});
  }
}

// A hinge's pose at t_n (hinge.hpp) and its relative displacement d_L = B u_n: a hinge that
// turns with its nodes from their translations and rotations Q_n (hinge_turned), any other from
// its constant rows (DESIGN §7).
template <Sizes S>
HingePose hinge_pose_at(const State<S>& s, const HingeData& h, double* d) {
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const bool ground = h.node2 == kGround;
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  if constexpr (kMayTurnHinges<S>) {
    if (h.turns) {
      return hinge_turned(h, s.rotation[static_cast<std::size_t>(h.node1)],
                          s.rotation[static_cast<std::size_t>(h.node2)], &s.u[i1], &s.u[i2], d);
    }
  }
  hinge_relative(h, &s.u[i1], ground ? nullptr : &s.u[i2], d);
  return hinge_pose(h);
}

// A hinge's relative displacement d_L = B u_n and its rate from v_{n-1/2} (DESIGN §7), and its
// pose.
template <Sizes S>
HingePose hinge_deformation(const State<S>& s, const HingeData& h, double* d, double* d_dot) {
  const HingePose p = hinge_pose_at(s, h, d);
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const bool ground = h.node2 == kGround;
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  hinge_relative(p, &s.v[i1], ground ? nullptr : &s.v[i2], d_dot);
  return p;
}

// Spring and dashpot force f_L of one hinge (force on node 1, hinge frame), with the plastic
// directions' history as it stands.
template <Sizes S>
void hinge_spring_local(const Model<S>& m, const State<S>& s, const HingeData& h, double* f) {
  double d[6], d_dot[6];
  hinge_deformation(s, h, d, d_dot);
  hinge_spring_force(h, m.curve_points, s.plastic, d, d_dot, f);
}

// Hinge springs and dashpots (linear, curve, plastic, and rigid directions under `penalty`) added
// to F_n as B^T f_L (DESIGN §7). The plastic directions' history is brought to d_n first (the
// return mapping, hysteresis.hpp): this stage is the one place that writes it.
template <Sizes S>
void hinge_springs(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    for (int i = 0; i < m.num_spring_hinges; ++i) {
      const HingeData& h =
          m.hinges[static_cast<std::size_t>(m.spring_hinges[static_cast<std::size_t>(i)])];
      double d[6], d_dot[6], f[6];
      const HingePose pose = hinge_deformation(s, h, d, d_dot);
      if constexpr (S.runtime || S.hystereses > 0) {
        for (std::size_t k = 0; h.plastic != 0 && k < kDofsPerNode; ++k) {
          if (!((h.plastic >> k) & 1U)) continue;
          const auto slot = static_cast<std::size_t>(h.history[k]);
          if (hysteresis_update(m.hystereses[slot], d[k], s.plastic[slot], s.dissipated[slot],
                                s.plastic_peak[slot], s.law_state[slot]))
            s.first_slip[slot] = s.tick + 1;  // it broke (a law with kBreaks)
        }
      }
      hinge_spring_force(h, m.curve_points, s.plastic, d, d_dot, f);
      const bool ground = h.node2 == kGround;
      hinge_scatter(pose, f, &w.f[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                    ground ? nullptr : &w.f[static_cast<std::size_t>(kDofsPerNode * h.node2)]);
    }
  }
}

// Hinge force on node 1 in the hinge frame, direction k: the constraint force of a coupled
// direction (the method's: ntn_exact's lambda, ntn_paper's T (m_1 a_1 - R_1)), else the spring
// force. `coupled_tree`: what the method remembers between the channels of one step (ntn_exact:
// the tree whose coupled R w.r holds, -1: none yet).
template <Sizes S>
double hinge_force(const Model<S>& m, const State<S>& s, Scratch<S>& w, int hinge, int k,
                   int& coupled_tree) {
  const HingeData& h = m.hinges[static_cast<std::size_t>(hinge)];
  if ((h.rigid >> k) & 1U) return constraint_force(m, s, w, hinge, k, coupled_tree);
  if (!((h.springs >> k) & 1U)) return 0.0;
  double f[6];
  hinge_spring_local(m, s, h, f);
  if (m.damping_velocity != DampingVelocity::kCentral) return f[static_cast<std::size_t>(k)];
  return f[static_cast<std::size_t>(k)] +
         w.dashpot_force[static_cast<std::size_t>(hinge)][static_cast<std::size_t>(k)];
}

// The friction directions' normal forces N at t_n (slip.hpp), before the update moves u: the
// force of the normal direction as its channel gives it (a rigid one's lambda, a spring's force).
template <Sizes S>
void slip_normals(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHystereses<S>) {
    if (m.num_slip_normals == 0) return;
    int coupled_tree = -1;
    for (int i = 0; i < m.num_slip_hinges; ++i) {
      const int hi = m.slip_hinges[static_cast<std::size_t>(i)];
      const HingeData& h = m.hinges[static_cast<std::size_t>(hi)];
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!((h.slip >> k) & 1U)) continue;
        const auto slot = static_cast<std::size_t>(h.history[k]);
        const int normal = m.hystereses[slot].normal;
        if (normal >= 0) w.slip_normal[slot] = hinge_force(m, s, w, hi, normal, coupled_tree);
      }
    }
  }
}

template <Sizes S>
double hinge_displacement(const Model<S>& m, const State<S>& s, int hinge, int k) {
  double d[6];
  hinge_pose_at(s, m.hinges[static_cast<std::size_t>(hinge)], d);
  return d[k];
}

// The velocity of DOF j at t_n, v_n = v_{n-1/2} + dt/2 a_n: the velocity channels' and the hinge
// velocity's.
template <Sizes S>
double velocity_at_tn(const Model<S>& m, const State<S>& s, const Scratch<S>& w, std::size_t j) {
  return s.v[j] + 0.5 * m.dt * w.a[j];
}

// The relative velocity of hinge direction k at t_n, from v_n at its nodes.
template <Sizes S>
double hinge_velocity(const Model<S>& m, const State<S>& s, const Scratch<S>& w, int hinge, int k) {
  const HingeData& h = m.hinges[static_cast<std::size_t>(hinge)];
  const bool ground = h.node2 == kGround;
  double v1[6], v2[6], d_dot[6];
  for (std::size_t c = 0; c < kDofsPerNode; ++c) {
    v1[c] = velocity_at_tn(m, s, w, static_cast<std::size_t>(kDofsPerNode * h.node1) + c);
    v2[c] = ground ? 0.0
                   : velocity_at_tn(m, s, w, static_cast<std::size_t>(kDofsPerNode * h.node2) + c);
  }
  double d[6];
  hinge_relative(hinge_pose_at(s, h, d), v1, ground ? nullptr : v2, d_dot);
  return d_dot[k];
}

// The force that hinges to the ground apply to the structure along global DOF `dof` (x ... rz),
// from their springs and coupled directions at t_n: what the ground takes, as a fixed support's
// F - P (node 2's share of B^T f_L). The slip and stop forces join after their stages
// (constraint_outputs).
template <Sizes S>
double ground_hinge_reaction(const Model<S>& m, const State<S>& s, Scratch<S>& w, int dof,
                             int& coupled_tree) {
  double sum = 0;
  for (std::size_t i = 0; i < m.sizes.hinges; ++i) {
    const HingeData& h = m.hinges[i];
    if (h.node2 != kGround || (h.rigid | h.springs) == 0) continue;
    double f[6] = {}, node1[6] = {}, ground[6] = {};
    if (h.springs != 0) hinge_spring_local(m, s, h, f);
    const bool central = m.damping_velocity == DampingVelocity::kCentral;
    for (std::size_t k = 0; central && h.springs != 0 && k < kDofsPerNode; ++k)
      f[k] += w.dashpot_force[i][k];  // the dashpots at t_n (dashpot.hpp)
    for (int k = 0; k < 6; ++k) {
      if ((h.rigid >> k) & 1U)
        f[k] = constraint_force(m, s, w, static_cast<int>(i), k, coupled_tree);
    }
    hinge_scatter(h, f, node1, ground);
    sum += ground[dof];
  }
  return sum;
}

// A model without hinges: a_n at the DOFs whose channels read it (velocity, acceleration), before
// residual_update() computes it everywhere with u and v: the outputs come first.
template <Sizes S>
void output_accelerations(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  for (std::size_t c = 0; c < m.sizes.outputs; ++c) {
    const OutputSpec& o = m.outputs[c];
    if (o.kind != OutputKind::kVelocity && o.kind != OutputKind::kAcceleration &&
        o.kind != OutputKind::kAbsoluteAcceleration)
      continue;
    const auto j = static_cast<std::size_t>(kDofsPerNode * o.node + o.dof);
    w.a[j] = acceleration_at(m, s, w, j);
  }
}

// Output channels at t_n: u_n, v_n = v_{n-1/2} + dt/2 a_n, a_n, end forces from u_n.
template <Sizes S>
void sample_outputs(const Model<S>& m, const State<S>& s, Scratch<S>& w, double t) {
  w.time = t;
  [[maybe_unused]] int coupled_tree = -1;  // hinge_force: the tree whose coupled R is in w.r
  for (std::size_t c = 0; c < m.sizes.outputs; ++c) {
    const OutputSpec& o = m.outputs[c];
    const auto j = static_cast<std::size_t>(kDofsPerNode * o.node + o.dof);
    double value = 0;
    switch (o.kind) {
      case OutputKind::kDisplacement:
        value = s.u[j];
        break;
      case OutputKind::kVelocity:
        value = velocity_at_tn(m, s, w, j);
        break;
      case OutputKind::kAcceleration:
        value = w.a[j];
        break;
      case OutputKind::kHingeForce:
        if constexpr (kMayHaveHinges<S>) value = hinge_force(m, s, w, o.hinge, o.dof, coupled_tree);
        break;
      case OutputKind::kHingeDisplacement:
        if constexpr (kMayHaveHinges<S>) value = hinge_displacement(m, s, o.hinge, o.dof);
        break;
      case OutputKind::kHingeVelocity:
        if constexpr (kMayHaveHinges<S>) value = hinge_velocity(m, s, w, o.hinge, o.dof);
        break;
      case OutputKind::kHingeSlipState:  // written by the slip stage (slip_outputs)
        break;
      case OutputKind::kHingePlastic:
      case OutputKind::kHingeDissipated:
      case OutputKind::kHingeLevel:
        if constexpr (kMayHaveHystereses<S>) {
          const HingeData& h = m.hinges[static_cast<std::size_t>(o.hinge)];
          if (((h.plastic | h.slip) >> o.dof) & 1U) {
            const auto slot = static_cast<std::size_t>(h.history[static_cast<std::size_t>(o.dof)]);
            value = o.kind == OutputKind::kHingePlastic ? s.plastic[slot]
                    : o.kind == OutputKind::kHingeDissipated
                        ? s.dissipated[slot]
                        : static_cast<double>(
                              performance_level(m.hystereses[slot].limits, s.plastic_peak[slot]));
          }
        }
        break;
      case OutputKind::kAbsoluteAcceleration:
        value = o.dof < 3 ? w.a[j] + w.ground[static_cast<std::size_t>(o.dof)] : w.a[j];
        break;
      case OutputKind::kElementForce: {
        const BeamData b = m.beam(static_cast<std::size_t>(o.element));
        const auto f = beam_local_end_forces(b, &s.u[static_cast<std::size_t>(6 * b.node_i)],
                                             &s.u[static_cast<std::size_t>(6 * b.node_j)]);
        value = f[static_cast<std::size_t>(6 * o.end + o.dof)];
        if (!corotational_end_force(m, s, o.element, o.end, o.dof, value))
          add_geometric_end_force(m, s, o.element, o.end, o.dof, value);
        for (const ElementLoadSpec& l : m.element_loads) {  // the element's own load
          if (l.element != o.element) continue;
          value -= l.local[static_cast<std::size_t>(6 * o.end + o.dof)] *
                   load_factor(m.time_points, m.time_functions, l.time_function, t);
        }
        break;
      }
      case OutputKind::kDrift:
        value = s.u[static_cast<std::size_t>(kDofsPerNode * o.node2 + o.dof)] - s.u[j];
        break;
      case OutputKind::kReaction:
        for (int k = 0; k < m.num_supported; ++k) {
          const int n = m.supported_nodes[static_cast<std::size_t>(k)];
          if ((m.fixed[static_cast<std::size_t>(n)] >> o.dof) & 1U) {
            const auto q = static_cast<std::size_t>(kDofsPerNode * n + o.dof);
            value += w.f[q] - external_load(m, w, q);
          }
        }
        if constexpr (kMayHaveHinges<S>)
          value += ground_hinge_reaction(m, s, w, o.dof, coupled_tree);
        break;
    }
    w.outputs[c] = value * o.scale;
  }
}

// True when a constraint stage of this step (stops, slips, projection) moved node n: its a_n
// and v_n are then what those stages made of them.
template <Sizes S>
bool moved_this_step(const Scratch<S>& w, int n) {
  return n != kGround && w.clamp.moved[static_cast<std::size_t>(n)] > w.clamp.step_events;
}

// The velocity of DOF j at t_n after the constraint stages: (v_{n-1/2} + v_{n+1/2}) / 2 =
// v_{n+1/2} - dt/2 a_n, the a_n they corrected (S 35-37).
template <Sizes S>
double corrected_velocity(const Model<S>& m, const State<S>& s, const Scratch<S>& w,
                          std::size_t j) {
  return s.v[j] - 0.5 * m.dt * w.a[j];
}

// Outputs after the constraint stages (stops, slips, projection): the channels at t_n that they
// change. The acceleration and velocity channels of a node they moved are the step's own,
// a_n = (v_{n+1/2} - v_{n-1/2}) / dt with every force of the step in it (S 35-37); a stop
// direction's hinge-force channel adds the clamp's force (Scratch::stop_force), and a reaction
// the slip and stop forces of the hinges to the ground. Channels of nodes nothing moved keep
// their bits.
template <Sizes S>
void constraint_outputs(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S> && (S.runtime || S.outputs > 0)) {
    if (m.sizes.hinges == 0) return;
    for (std::size_t c = 0; c < m.sizes.outputs; ++c) {
      const OutputSpec& o = m.outputs[c];
      const auto j = static_cast<std::size_t>(kDofsPerNode * o.node + o.dof);
      switch (o.kind) {
        case OutputKind::kVelocity:
          if (moved_this_step(w, o.node)) w.outputs[c] = corrected_velocity(m, s, w, j) * o.scale;
          break;
        case OutputKind::kAcceleration:
          if (moved_this_step(w, o.node)) w.outputs[c] = w.a[j] * o.scale;
          break;
        case OutputKind::kAbsoluteAcceleration:
          if (moved_this_step(w, o.node))
            w.outputs[c] =
                (o.dof < 3 ? w.a[j] + w.ground[static_cast<std::size_t>(o.dof)] : w.a[j]) * o.scale;
          break;
        case OutputKind::kHingeVelocity: {
          const HingeData& h = m.hinges[static_cast<std::size_t>(o.hinge)];
          if (!moved_this_step(w, h.node1) && !moved_this_step(w, h.node2)) break;
          const bool ground = h.node2 == kGround;
          double v1[6], v2[6], d_dot[6];
          for (std::size_t q = 0; q < kDofsPerNode; ++q) {
            v1[q] =
                corrected_velocity(m, s, w, static_cast<std::size_t>(kDofsPerNode * h.node1) + q);
            v2[q] = ground ? 0.0
                           : corrected_velocity(
                                 m, s, w, static_cast<std::size_t>(kDofsPerNode * h.node2) + q);
          }
          double d[6];
          hinge_relative(hinge_pose_at(s, h, d), v1, ground ? nullptr : v2, d_dot);
          w.outputs[c] = d_dot[o.dof] * o.scale;
          break;
        }
        case OutputKind::kHingeForce: {
          const HingeData& h = m.hinges[static_cast<std::size_t>(o.hinge)];
          if ((h.branches >> o.dof) & 1U)
            w.outputs[c] +=
                w.stop_force[static_cast<std::size_t>(o.hinge)][static_cast<std::size_t>(o.dof)] *
                o.scale;
          break;
        }
        case OutputKind::kReaction: {
          double sum = 0;
          for (std::size_t i = 0; i < m.sizes.hinges; ++i) {
            const HingeData& h = m.hinges[i];
            if (h.node2 != kGround || (h.branches | h.slip) == 0) continue;
            double f[6] = {}, node1[6] = {}, ground[6] = {};
            for (std::size_t k = 0; k < kDofsPerNode; ++k) {
              if ((h.branches >> k) & 1U) f[k] += w.stop_force[i][k];
              if constexpr (kMayHaveHystereses<S>) {
                if ((h.slip >> k) & 1U)
                  f[k] += w.slip_force[static_cast<std::size_t>(h.history[k])];
              }
            }
            hinge_scatter(h, f, node1, ground);
            sum += ground[o.dof];
          }
          w.outputs[c] += sum * o.scale;
          break;
        }
        default:
          break;
      }
    }
  }
}

// v_{n+1/2} = v_{n-1/2} + dt a_n, u_{n+1} = u_n + dt v_{n+1/2} (S 5-7, constant dt) for every
// DOF, after the NTN coupling (a model without hinges: residual_update). Returns false when a
// velocity is non-finite.
template <Sizes S>
bool update(const Model<S>& m, State<S>& s, const Scratch<S>& w) {
  const double dt = m.dt;  // a local: stores to s.v, s.u may alias m.dt, which blocks vectorizing
  // The check is a select into a double, not `ok &= finite(v)`: GCC vectorizes no loop with a
  // bool reduction, and this is a pass over every DOF.
  double bad = 0;
  for (std::size_t j = 0; j < m.dofs(); ++j) {
    const double v = advance(dt, w.a[j], s.v[j], s.u[j]);
    bad = finite(v) ? bad : 1.0;
  }
  return bad == 0;
}

// The team's phases (team.hpp): what one worker k does of the step.
template <Sizes S>
struct TeamStep {
  const Model<S>* m;
  State<S>* s;
  Scratch<S>* w;
  TeamWork<S>* t;
};

// A: worker k's element blocks, their ends added to F_n at its interior nodes (a node's first end
// written, not added: F_n is not zeroed first), stored for the shared ones.
template <Sizes S>
void team_element_forces(void* arg, int k) {
  const TeamStep<S>& c = *static_cast<const TeamStep<S>*>(arg);
  const auto first = static_cast<std::size_t>(c.t->block_split[static_cast<std::size_t>(k)]);
  const auto last = static_cast<std::size_t>(c.t->block_split[static_cast<std::size_t>(k) + 1]);
  element_forces_split(c.m->element_pass, c.m->beam_arrays(), first, last, c.t->direct.data(),
                       c.s->u.data(), c.s->v.data(), c.m->beta, c.w->f.data(),
                       c.t->end_forces.data());
}

// B: F_n at worker k's part of the shared nodes.
template <Sizes S>
void team_shared_forces(void* arg, int k) {
  const TeamStep<S>& c = *static_cast<const TeamStep<S>*>(arg);
  const auto first = static_cast<std::size_t>(c.t->shared_split[static_cast<std::size_t>(k)]);
  const auto last = static_cast<std::size_t>(c.t->shared_split[static_cast<std::size_t>(k) + 1]);
  for (std::size_t i = first; i < last; ++i)
    gather_node(*c.t, static_cast<std::size_t>(c.t->shared[i]), c.w->f.data());
}

// C (no hinges): the residual, accelerations and update of worker k's nodes (the DOF pass).
template <Sizes S>
void team_update(void* arg, int k) {
  const TeamStep<S>& c = *static_cast<const TeamStep<S>*>(arg);
  const auto n = static_cast<std::size_t>(k);
  const auto first = static_cast<std::size_t>(c.t->node_split[n]);
  const auto last = static_cast<std::size_t>(c.t->node_split[n + 1]);
  c.t->bad[n] = residual_update(*c.m, *c.s, *c.w, first, last) ? 0.0 : 1.0;
}

// The stages of step(): on the caller's thread alone (team == nullptr), or with the team's
// phases in place of the element pass and, without hinges, of the DOF pass. A model without
// hinges has no coupled DOF: its residual, accelerations and update are one pass over the DOFs
// (residual_update), after the outputs, which compute the few a_n they read themselves.
template <Sizes S>
[[nodiscard]] StepStatus step_on(const Model<S>& m, State<S>& s, Scratch<S>& w, StepInputs<S> in,
                                 const Team* team, TeamWork<S>* work) {
  const bool fused = m.sizes.hinges == 0;  // the DOF pass (dof_pass.hpp); compiled: a constant
  // A team whose partition is for another size runs nothing: the step is the caller's alone (the
  // same bits).
  if (team != nullptr && (work == nullptr || team->size != work->size)) team = nullptr;
  TeamStep<S> c{&m, &s, &w, work};
  const bool accepted = accept_inputs(m, s, in);  // inputs: hold bad values (§8)
  const double t = static_cast<double>(s.tick) * m.dt;
  apply_loads(m, s, w, t);  // loads P_n: M g, -M iota a_g, nodal loads, inputs (§5)
  if (team == nullptr) {
    element_forces(m, s, w);  // element forces F_n = sum T^T K_L T u_n (+ beta v) (§4)
  } else {                    // F_n: zeroed and summed by the team (team.hpp)
    team->run(team->self, team_element_forces<S>, &c);
    team->run(team->self, team_shared_forces<S>, &c);
  }
  geometric_stage(m, s, w);     // second-order geometry: F_n += the chords' P-Delta (§4)
  corotational_stage(m, s, w);  // corotational elements: F_n += their forces (§4)
  hinge_springs(m, s, w);       // hinge springs: F_n += B^T f_L (§7)
  if (fused) {
    output_accelerations(m, s, w);  // a_n where the outputs read it (S 2-4)
  } else {
    residual_stage(m, s, w);  // residual R_n - C v_{n-1/2}, a_n where uncoupled (S 2-4)
    ntn_coupling(m, s, w);    // NTN coupling: a_n at coupled DOFs (S 17-26, §7.1)
    dashpots_at_tn(m, w);     // central damping: the hinge dashpots at v_n (dashpot.hpp)
  }
  slip_normals(m, s, w);       // friction: the normal forces N at t_n (slip.hpp)
  sample_outputs(m, s, w, t);  // outputs: the channels at t_n
  bool finite = true;
  if (fused) {  // residual, a_n and update: v_{n+1/2}, u_{n+1} (S 2-7)
    if (team != nullptr) {
      team->run(team->self, team_update<S>, &c);
      for (int k = 0; k < work->size; ++k)
        finite = finite && work->bad[static_cast<std::size_t>(k)] == 0.0;
    } else {
      finite = residual_update(m, s, w, 0, m.sizes.nodes);
    }
  } else {
    finite = update(m, s, w);  // update: v_{n+1/2}, u_{n+1} (S 5-7)
  }
  hinge_stops(m, s, w);   // stops: slip directions held or slid, rigid branches clamped
  slip_outputs(m, s, w);  // the slip directions' forces at t_n and states into their channels
  constraint_projection(m, s, w);  // constraint projection: S 27-37, §7.1
  constraint_outputs(m, s, w);     // outputs the constraint stages change: a_n, contact forces
  if (m.books) {                   // the energy books over the DOFs (books.hpp)
    if (!fused) book_dofs(m, s, w);
    w.books = books_total(w.group_books.data(), book_groups(m.sizes.nodes));
  }
  update_rotations(m, s);  // corotational: Q_{n+1} from the spin v_{n+1/2}
  ++s.tick;
  if (!finite) {
    s.faults |= kFaultDiverged;
    return StepStatus::kDiverged;
  }
  return accepted ? StepStatus::kOk : StepStatus::kInputHeld;
}

}  // namespace detail

// Resets `s` to the model's initial state: u_0 and v_0 as the model gives them (NodeSpec::u0, v0:
// the model compiler's static preload and [initial] values, zero by default), everything else as
// a new State. A run from the model file is initial_state() then start().
template <Sizes S>
void initial_state(const Model<S>& m, State<S>& s) {
  s.u = m.u0;  // field by field: a State{} temporary of a large model would not fit the stack
  s.v = m.v0;
  s.held_inputs.fill(0.0);
  s.tick = 0;
  s.inputs_held = s.inputs_out_of_range = 0;
  s.faults = 0;
  s.geometry_bound = 0;
  s.plastic.fill(0.0);  // no plastic history at the start of a run
  s.dissipated.fill(0.0);
  s.plastic_peak.fill(0.0);
  for (auto& x : s.law_state)
    x.fill(0.0);
  s.first_slip.fill(0);
  s.slip_state.fill(0);
  s.rotation.fill(Quaternion{});
}

namespace detail {

// start(): the slip and stop forces at t_0 into a_0. The step applies them after its update, as
// moves of u_{n+1}; at the start the same forces must act over the first half step alone, so
// they are found on the trial u_1 = u_0 + dt v_0 + dt^2/2 a_0 (what the first step gives without
// them) with the move weight dt^2/2 (ClampWork): a sticking direction's force holds it there, a
// sliding one's is its limit, and a_0 takes -f M_c^-1 b. A u_0 past a stop is not a force: the
// stops first move u_0 onto their limits with a_0 untouched (a_scale 0), and the trial starts
// from there (the first step then clamps u_0's excess, as it would without this). u_0 and v_0
// are kept as they were.
//
// With damping_velocity = "central" the stages before solve M_e a = R_0 (the step mass,
// Model::mass_factor), while at t_0 v_0 is known and C v_0 is already in R_0: a_0 = M^-1 R_0 is
// that a times mass_factor (every stage is linear in a uniform scale of the mass). The normal
// forces are taken before, from M_e and its a (the same forces); the trial's move weight
// h2 = mass_factor dt^2/2 makes the clamp's and the slips' forces those of M (their moves
// -f h2 M_e^-1 b = -f dt^2/2 M^-1 b).
template <Sizes S>
void start_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  bool forces = false;
  if constexpr (kMayHaveHinges<S>) {
    forces = m.sizes.hinges > 0 && (m.num_branch_hinges > 0 || m.num_slip_hinges > 0);
    if (forces) slip_normals(m, s, w);  // friction: N at t_0
  }
  if (m.mass_factor != 1.0) {  // a_0 = M^-1 R_0
    for (std::size_t j = 0; j < m.dofs(); ++j)
      w.a[j] *= m.mass_factor;
  }
  if constexpr (kMayHaveHinges<S>) {
    if (!forces) return;
    const double dt = m.dt;
    for (std::size_t j = 0; j < m.dofs(); ++j)
      w.clamp.start_u[j] = s.u[j];
    w.clamp.h2 = 0.5 * dt * dt * m.mass_factor, w.clamp.v_rate = 0.0, w.clamp.a_scale = 0.0;
    hinge_start_forces(m, s, w);  // u_0 onto the stops, a_0 as it is
    for (std::size_t j = 0; j < m.dofs(); ++j)
      s.u[j] += dt * s.v[j] + 0.5 * dt * dt * w.a[j];
    w.clamp.a_scale = 2.0;
    hinge_start_forces(m, s, w);  // the trial: the forces into a_0
    for (std::size_t j = 0; j < m.dofs(); ++j)
      s.u[j] = w.clamp.start_u[j];
  }
}

}  // namespace detail

// Starts a run from the caller's u_0 and v_0 in `s` (initial_state(), or the caller's own): with
// ntn_exact, u_0 and v_0 first take the rigid components of their tree parents (the constraints
// hold from t_0); a_0 = M^-1 (P_0 - F_0 - C v_0) with the slip and stop forces at t_0
// (start_forces); v_{-1/2} = v_0 - dt/2
// a_0 (DESIGN §5), tick = 0.
template <Sizes S>
[[nodiscard]] StepStatus start(const Model<S>& m, State<S>& s, Scratch<S>& w, StepInputs<S> in) {
  s.tick = 0;
  for (auto& h : s.held_inputs)
    h = 0.0;
  detail::project_initial(m, s);  // u_0, v_0 onto the constraints
  detail::start_rotations(m, s);  // corotational: Q_0 from u_0
  const bool accepted = detail::accept_inputs(m, s, in);
  // step()'s stages up to a_0, at t = 0 and with C v_0
  detail::apply_loads(m, s, w, 0.0);
  detail::element_forces(m, s, w);
  detail::geometric_stage(m, s, w);
  detail::corotational_stage(m, s, w);
  detail::hinge_springs(m, s, w);
  detail::residual_stage(m, s, w);
  detail::ntn_coupling(m, s, w);
  if constexpr (kMayHaveHinges<S>) {  // the dashpots at t_0 take v_0 itself: no correction
    for (auto& f : w.dashpot_force)
      f.fill(0.0);
  }
  detail::start_forces(m, s, w);
  for (std::size_t j = 0; j < m.dofs(); ++j) {
    s.v[j] -= 0.5 * m.dt * w.a[j];
  }
  return accepted ? StepStatus::kOk : StepStatus::kInputHeld;
}

// One step t_n -> t_{n+1}. Outputs in `w` are the channels at t_n.
template <Sizes S>
[[nodiscard]] StepStatus step(const Model<S>& m, State<S>& s, Scratch<S>& w, StepInputs<S> in) {
  return detail::step_on<S>(m, s, w, in, nullptr, nullptr);
}

// The same step with a team of workers (team.hpp): the same bits for any team size. `work` was
// built by prepare_team() for this model and team.size workers.
template <Sizes S>
[[nodiscard]] StepStatus step(const Model<S>& m, State<S>& s, Scratch<S>& w, StepInputs<S> in,
                              const Team& team, TeamWork<S>& work) {
  return detail::step_on<S>(m, s, w, in, &team, &work);
}

}  // namespace ntn
