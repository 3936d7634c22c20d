// Fixed-step central difference (DESIGN §5, seed S 1-8) as a fixed pipeline of stages:
// inputs -> loads -> element forces -> accelerations -> outputs -> update.
#pragma once

#include <algorithm>
#include <array>
#include <bit>

#include "ntn/beam.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"
#include "ntn/loads.hpp"
#include "ntn/model.hpp"
#include "ntn/ntn_paper.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"

namespace ntn {

// P_n at DOF j as the last forces_and_accelerations (start or step) made it: the load slot's
// value, else m g_d. The step never stores P_n as a whole (see residual()).
template <Sizes S>
double external_load(const Model<S>& m, const Scratch<S>& w, std::size_t j) {
  for (int k = 0; k < m.num_slots; ++k) {
    if (static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]) == j)
      return w.p_slot[static_cast<std::size_t>(k)];
  }
  return m.mass[j] * w.load_g[j % kDofsPerNode];
}

namespace detail {

// True for finite x. No libm: x - x is 0 for finite x, NaN for NaN and +-Inf.
inline bool finite(double x) {
  return x - x == 0.0;
}

template <Sizes S>
using Inputs = std::array<double, S.inputs>;

// Bad inputs never reach the state (§8): a non-finite value or one outside the channel's
// [min, max] is replaced by the channel's last good value, counted and flagged.
template <Sizes S>
bool accept_inputs(const Model<S>& m, State<S>& s, const Inputs<S>& in) {
  bool held = false;
  for (int i = 0; i < S.inputs; ++i) {
    const auto k = static_cast<std::size_t>(i);
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
  for (int i = 0; i < S.inputs; ++i) {
    const InputSpec& in = m.inputs[static_cast<std::size_t>(i)];
    if (in.kind == InputKind::kGroundAcceleration) {
      w.ground[static_cast<std::size_t>(in.dof)] +=
          s.held_inputs[static_cast<std::size_t>(i)] * in.scale;
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
  for (int i = 0; i < S.loads; ++i) {
    const LoadSpec& l = m.loads[static_cast<std::size_t>(i)];
    w.p_slot[static_cast<std::size_t>(m.load_slot[static_cast<std::size_t>(i)])] +=
        l.value * load_factor(m.time_points, m.time_functions, l.time_function, t);
  }
  for (int i = 0; i < S.inputs; ++i) {
    const InputSpec& in = m.inputs[static_cast<std::size_t>(i)];
    if (in.kind == InputKind::kNodalForce) {
      w.p_slot[static_cast<std::size_t>(m.input_slot[static_cast<std::size_t>(i)])] +=
          s.held_inputs[static_cast<std::size_t>(i)] * in.scale;
    }
  }
}

// F_n = sum over elements of T^T K_L T u_n, scattered in element order (S 2).
template <Sizes S>
void element_forces(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  w.f.fill(0.0);
  for (const BeamData& b : m.beams) {
    double fi[6], fj[6];
    const auto i = static_cast<std::size_t>(kDofsPerNode * b.node_i);
    const auto j = static_cast<std::size_t>(kDofsPerNode * b.node_j);
    beam_force(b, &s.u[i], &s.u[j], fi, fj);
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      w.f[i + d] += fi[d];
      w.f[j + d] += fj[d];
    }
  }
}

// Spring and dashpot force f_L of one hinge (force on node 1, hinge frame): from d_L = B u and
// its rate from v_{n-1/2} (DESIGN §7).
template <Sizes S>
void hinge_spring_local(const Model<S>& m, const State<S>& s, const HingeData& h, double* f) {
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const bool ground = h.node2 == kGround;
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  double d[6], d_dot[6];
  hinge_relative(h, &s.u[i1], ground ? nullptr : &s.u[i2], d);
  hinge_relative(h, &s.v[i1], ground ? nullptr : &s.v[i2], d_dot);
  hinge_spring_force(h, m.curve_points, d, d_dot, f);
}

// Hinge springs and dashpots (linear, curve, and rigid directions under `penalty`) added to F_n
// as B^T f_L (DESIGN §7).
template <Sizes S>
void hinge_forces(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  for (int i = 0; i < m.num_spring_hinges; ++i) {
    const HingeData& h =
        m.hinges[static_cast<std::size_t>(m.spring_hinges[static_cast<std::size_t>(i)])];
    double f[6];
    hinge_spring_local(m, s, h, f);
    const bool ground = h.node2 == kGround;
    hinge_scatter(h, f, &w.f[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                  ground ? nullptr : &w.f[static_cast<std::size_t>(kDofsPerNode * h.node2)]);
  }
}

// R_n - C v_{n-1/2} = P_n - F_n - alpha M v_{n-1/2} (S 2-3) into out[j] for every DOF, times
// scale[j] (or not, for ntn_paper), in one pass: P_n = m g_d on the fly (C = alpha M likewise:
// the same products as Model::damping), then the load slots again with their whole P_n.
template <Sizes S, bool kScaled = true>
void residual(const Model<S>& m, const State<S>& s, const Scratch<S>& w, const double* scale,
              double* out) {
  const double alpha = m.alpha;
  double g[kDofsPerNode];  // locals: the stores to `out` may alias the model and the scratch
  for (std::size_t d = 0; d < kDofsPerNode; ++d)
    g[d] = w.load_g[d];
  for (std::size_t n = 0; n < static_cast<std::size_t>(Model<S>::kDofs); n += kDofsPerNode) {
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      const std::size_t j = n + d;
      const double r = (m.mass[j] * g[d] - w.f[j]) - (alpha * m.mass[j]) * s.v[j];
      if constexpr (kScaled) {
        out[j] = r * scale[j];
      } else {
        out[j] = r;
      }
    }
  }
  for (int k = 0; k < m.num_slots; ++k) {
    const auto j = static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]);
    const double r =
        (w.p_slot[static_cast<std::size_t>(k)] - w.f[j]) - (alpha * m.mass[j]) * s.v[j];
    if constexpr (kScaled) {
      out[j] = r * scale[j];
    } else {
      out[j] = r;
    }
  }
}

// a_n = (R_n - C v_{n-1/2}) / m per DOF, R_n = P_n - F_n (S 2-4); zero at supported DOFs.
// ntn_paper sums R_n over the rigid directions first (S 17-21, in w.r). ntn_exact hands R_n up
// the constraint forest, then the roots and the downward pass give the trees' accelerations
// (DESIGN §7.1); to spare a second store per DOF, its residual pass leaves R_n itself (scale 1)
// in w.a at tree DOFs and a_n elsewhere, and the forest works in place there (a hinge force
// output recomputes its tree's coupled R). Penalty springs are in F_n already.
template <Sizes S>
void accelerations(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  if constexpr (S.hinges > 0) {
    if (m.hinge_method == HingeMethod::kNtnPaper) {
      residual<S, false>(m, s, w, nullptr, w.r.data());
      paper_forces(m.hinges, w.r.data());
      for (std::size_t j = 0; j < static_cast<std::size_t>(Model<S>::kDofs); ++j) {
        w.a[j] = w.r[j] * m.inv_mass[j];
      }
      return;
    }
    if (m.hinge_method == HingeMethod::kNtnExact) {
      residual(m, s, w, m.residual_scale.data(), w.a.data());
      forest_up(m.edges, m.edge_matrices, m.num_edges, w.a.data());
      forest_down(m.roots, m.num_roots, m.edges, m.edge_matrices, m.num_edges, w.a.data(),
                  w.a.data());
      return;
    }
  }
  residual(m, s, w, m.inv_mass.data(), w.a.data());
}

// The nodes an impulse at `node` moves (the clamp): the node's rigid tree (ntn_exact), or the
// node alone.
struct ClampPart {
  int tree = -1;  // index into Model::trees, or -1
  int node = -1;  // the node when it is in no tree, or -1 (also for the ground)
};

template <Sizes S>
ClampPart clamp_part(const Model<S>& m, int node) {
  if (node == kGround) return {};
  const int t = m.node_tree[static_cast<std::size_t>(node)];
  return t >= 0 ? ClampPart{t, -1} : ClampPart{-1, node};
}

// Calls fn(node) for every node of the part.
template <Sizes S, class Fn>
void for_each_node(const Model<S>& m, const ClampPart& p, Fn&& fn) {
  if (p.node >= 0) fn(p.node);
  if (p.tree < 0) return;
  const ForestTree& t = m.trees[static_cast<std::size_t>(p.tree)];
  if (t.root >= 0) fn(m.roots[static_cast<std::size_t>(t.root)].node);
  for (int k = t.first_edge; k < t.end_edge; ++k)
    fn(m.edges[static_cast<std::size_t>(k)].child);
}

// The coupled R_n of one rigid tree in w.r, as the step's upward pass makes it (the same
// expressions in the same order, so the same bits): the step itself keeps only accelerations.
template <Sizes S>
void tree_coupled_residual(const Model<S>& m, const State<S>& s, Scratch<S>& w, int tree) {
  for_each_node(m, ClampPart{tree, -1}, [&](int n) {
    for (std::size_t c = 0; c < 6; ++c) {
      const auto j = static_cast<std::size_t>(kDofsPerNode * n) + c;
      w.r[j] = (external_load(m, w, j) - w.f[j]) - m.damping[j] * s.v[j];
    }
  });
  const ForestTree& t = m.trees[static_cast<std::size_t>(tree)];
  const auto first = static_cast<std::size_t>(t.first_edge);
  forest_up(std::span(m.edges).subspan(first), std::span(m.edge_matrices).subspan(first),
            t.end_edge - t.first_edge, w.r.data());
}

// Hinge force on node 1 in the hinge frame, direction k: the constraint force of a rigid
// direction (ntn_exact: lambda of the forest; ntn_paper: T (m_1 a_1 - R_1) from node 1's own
// mass and force, which holds every hinge on node 1 together), else the spring force.
// `coupled_tree`: the tree whose coupled R w.r holds for this step's outputs (-1: none yet), so
// that several channels of one tree compute it once.
template <Sizes S>
double hinge_force(const Model<S>& m, const State<S>& s, Scratch<S>& w, int hinge, int k,
                   int& coupled_tree) {
  const HingeData& h = m.hinges[static_cast<std::size_t>(hinge)];
  const auto kk = static_cast<std::size_t>(k);
  if ((h.rigid >> k) & 1U) {
    double lambda[6];
    if (m.hinge_method == HingeMethod::kNtnExact) {
      const auto edge = static_cast<std::size_t>(m.hinge_edge[static_cast<std::size_t>(hinge)]);
      const ForestEdge& e = m.edges[edge];
      const int tree = m.node_tree[static_cast<std::size_t>(e.child)];
      if (tree != coupled_tree) tree_coupled_residual(m, s, w, tree);
      coupled_tree = tree;
      forest_hinge_force(e, m.edge_matrices[edge], w.a.data(), w.r.data(), lambda);
      return lambda[k];
    }
    const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
    double g[6], l[6];
    for (std::size_t c = 0; c < 6; ++c) {
      const double own =
          (external_load(m, w, i1 + c) - w.f[i1 + c]) - m.damping[i1 + c] * s.v[i1 + c];
      g[c] = m.mass[i1 + c] * w.a[i1 + c] - own;
    }
    detail::to_hinge(h, g + (k < 3 ? 0 : 3), l);
    return l[k % 3];
  }
  if (!((h.springs >> k) & 1U)) return 0.0;
  double f[6];
  hinge_spring_local(m, s, h, f);
  return f[kk];
}

template <Sizes S>
double hinge_displacement(const Model<S>& m, const State<S>& s, int hinge, int k) {
  const HingeData& h = m.hinges[static_cast<std::size_t>(hinge)];
  const bool ground = h.node2 == kGround;
  double d[6];
  hinge_relative(h, &s.u[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                 ground ? nullptr : &s.u[static_cast<std::size_t>(kDofsPerNode * h.node2)], d);
  return d[k];
}

// Rigid branches with the momentum-conserving clamp (DESIGN §7.1): when a curve direction d
// passes its branch start, the model moves by the response of the whole constrained system to
// an impulse along that hinge direction (b = the direction's row of B), scaled so that d lands
// on d_lim: dx = -excess M_c^-1 b / (b^T M_c^-1 b), where M_c^-1 is the lumped inverse mass
// with the rigid trees applied (the forest's up and down passes). Momentum is kept because the
// impulse pair is equal and opposite, and the rigid directions stay exact because the response
// is a constrained motion. Without trees this is each node moving by its share of b^T M^-1 b.
// Only the trees of the hinge's two nodes (or the nodes themselves) respond, so an event costs
// the size of those trees, not of the model. Then S 35-37. Uses w.f and w.r there as workspace
// (the outputs were taken before the update).

// The parts that respond to an impulse on stop hinge h: its nodes' trees or the lone nodes.
template <Sizes S>
void clamp_parts(const Model<S>& m, const HingeData& h, ClampPart (&parts)[2]) {
  parts[0] = clamp_part(m, h.node1);
  parts[1] = clamp_part(m, h.node2);
  if (parts[1].tree >= 0 && parts[1].tree == parts[0].tree) parts[1] = {};  // one tree
}

// d_k - its branch limit when d_k is past it, else 0; `size` gets |excess| relative to the limit
// (absolute where the branch starts at zero).
inline double branch_excess(const HingeData& h, const double* d, std::size_t k, double& size) {
  const double excess = d[k] > h.branch_upper[k]   ? d[k] - h.branch_upper[k]
                        : d[k] < h.branch_lower[k] ? d[k] - h.branch_lower[k]
                                                   : 0.0;
  const double limit = excess > 0 ? h.branch_upper[k] : h.branch_lower[k];
  const double a = excess > 0 ? excess : -excess;
  size = limit != 0 ? a / (limit > 0 ? limit : -limit) : a;
  return excess;
}

// y = M_c^-1 b into w.f over the parts' nodes, b the impulse along direction k of hinge h.
template <Sizes S>
void clamp_response(const Model<S>& m, Scratch<S>& w, const HingeData& h, std::size_t k,
                    const ClampPart (&parts)[2]) {
  double b1[6], b2[6];
  hinge_direction(h, k, b1, b2);
  const bool ground = h.node2 == kGround;
  for (const ClampPart& p : parts) {
    for_each_node(m, p, [&](int n) {
      for (std::size_t c = 0; c < 6; ++c)
        w.r[static_cast<std::size_t>(kDofsPerNode * n) + c] = 0.0;
    });
  }
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  for (std::size_t c = 0; c < 6; ++c) {
    w.r[i1 + c] += b1[c];
    if (!ground) w.r[i2 + c] += b2[c];
  }
  // Each part's response: M^-1 r for a lone node, the forest's passes over a tree.
  for (const ClampPart& p : parts) {
    if (p.node >= 0) {
      for (std::size_t c = 0; c < 6; ++c) {
        const auto j = static_cast<std::size_t>(kDofsPerNode * p.node) + c;
        w.f[j] = w.r[j] * m.inv_mass[j];
      }
    }
    if (p.tree < 0) continue;
    forest_tree_accelerations(m.trees[static_cast<std::size_t>(p.tree)], m.roots, m.edges,
                              m.edge_matrices, w.r.data(), w.f.data());
  }
}

// b^T y for the impulse along direction k of hinge h and the response y in w.f.
template <Sizes S>
double clamp_projection(const Scratch<S>& w, const HingeData& h, std::size_t k) {
  double b1[6], b2[6];
  hinge_direction(h, k, b1, b2);
  const bool ground = h.node2 == kGround;
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  double sum = 0;
  for (std::size_t c = 0; c < 6; ++c) {
    sum += b1[c] * w.f[i1 + c];
    if (!ground) sum += b2[c] * w.f[i2 + c];
  }
  return sum;
}

// The parts move by scale y (y in w.f): u, and v and a after it (S 35-37 as increments).
template <Sizes S>
void clamp_move(const Model<S>& m, State<S>& s, Scratch<S>& w, const ClampPart (&parts)[2],
                double scale, std::int64_t event) {
  for (const ClampPart& p : parts) {
    for_each_node(m, p, [&](int n) {
      w.clamp_moved[static_cast<std::size_t>(n)] = event;
      for (std::size_t c = 0; c < 6; ++c) {
        const auto j = static_cast<std::size_t>(kDofsPerNode * n) + c;
        const double du = scale * w.f[j];
        s.u[j] += du;
        s.v[j] += du * m.inv_dt;
        w.a[j] += du * m.inv_dt * m.inv_dt;
      }
    });
  }
}

// True when stop hinge `i` (index into Model::branch_hinges) needs a look in this sweep: the
// first sweep of a step looks at every one (the update moved every node), a later one only at
// those with a node that a clamp moved since the hinge was last looked at.
template <Sizes S>
bool clamp_due(const Scratch<S>& w, const HingeData& h, std::int64_t checked, bool first) {
  if (first) return true;
  if (w.clamp_moved[static_cast<std::size_t>(h.node1)] > checked) return true;
  return h.node2 != kGround && w.clamp_moved[static_cast<std::size_t>(h.node2)] > checked;
}

// One stop hinge on its own, direction after direction (projected Gauss-Seidel); returns the
// largest relative excess it found.
template <Sizes S>
double clamp_hinge(const Model<S>& m, State<S>& s, Scratch<S>& w, const HingeData& h) {
  double largest = 0;
  ClampPart parts[2];
  clamp_parts(m, h, parts);
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const bool ground = h.node2 == kGround;
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  for (std::size_t k = 0; k < kDofsPerNode; ++k) {
    if (!((h.branches >> k) & 1U)) continue;
    double d[6], size = 0;
    hinge_relative(h, &s.u[i1], ground ? nullptr : &s.u[i2], d);
    const double excess = branch_excess(h, d, k, size);
    if (excess == 0) continue;
    if (size > largest) largest = size;
    clamp_response(m, w, h, k, parts);
    const double mobility = clamp_projection(w, h, k);  // b^T M_c^-1 b
    if (!(mobility > 0)) continue;                      // both sides held: nothing can move
    clamp_move(m, s, w, parts, -excess / mobility, ++w.clamp_events);
  }
  return largest;
}

// The stops of one rigid tree together (DESIGN §7.1). When any branch of the tree's stop hinges
// is past its limit, every stop direction of those hinges takes part (the nearer limit of each):
// with W_ij = b_i^T M_c^-1 b_j (the constrained system's mobility between them), side s_i = +1
// at an upper and -1 at a lower limit, A_ij = s_i W_ij s_j and v_i = s_i (d_i - limit_i) (> 0:
// past it), the pushes p >= 0 solve the small complementarity problem v - A p <= 0, p_i (v - A
// p)_i = 0: an active set, started from the violated stops, solved by L D L^T (no square root),
// a stop that would pull left out, a stop that the others would push past its limit taken in,
// until neither happens. The model then moves by -sum s_j p_j M_c^-1 b_j. Where stops squeeze
// one joint from two sides, clamping them one at a time reopens the other and converges slowly
// (each clamp moves the joint); the joint solve lands every one at once. Momentum is kept (a
// sum of equal and opposite impulse pairs) and the rigid directions stay exact (a sum of
// constrained motions). Returns the largest relative excess found; `solved` is false when the
// stops are dependent (a singular A) and the caller clamps them one by one.
inline constexpr int kClampSweeps = 32;           // sweeps of the clamps per step, at most
inline constexpr double kClampTolerance = 1e-12;  // relative excess a sweep may leave
inline constexpr int kClampBlock = 8;  // the most stop directions of one tree solved together

template <Sizes S>
double clamp_tree(const Model<S>& m, State<S>& s, Scratch<S>& w, const ForestTree& t, bool first,
                  bool& solved) {
  solved = true;
  struct Stop {
    int hinge;
    std::size_t k;
    double side;       // +1: the upper limit, -1: the lower
    double violation;  // side (d - limit): > 0 past it
    double tolerance;  // what counts as past it when the others move it
  };
  Stop c[kClampBlock];
  int n = 0;
  for (int q = t.first_stop; q < t.end_stop; ++q) {
    const HingeData& h = m.hinges[static_cast<std::size_t>(
        m.branch_hinges[static_cast<std::size_t>(m.tree_stops[static_cast<std::size_t>(q)])])];
    n += std::popcount(static_cast<unsigned>(h.branches));
  }
  if (n > kClampBlock) {  // more stop directions than a joint has: one by one
    solved = false;
    return 0.0;
  }
  n = 0;
  double largest = 0;
  bool any = false;
  for (int q = t.first_stop; q < t.end_stop; ++q) {
    const int i = m.tree_stops[static_cast<std::size_t>(q)];
    const int hi = m.branch_hinges[static_cast<std::size_t>(i)];
    const HingeData& h = m.hinges[static_cast<std::size_t>(hi)];
    const bool due = clamp_due(w, h, w.clamp_checked[static_cast<std::size_t>(i)], first);
    double d[6];
    hinge_relative(h, &s.u[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                   &s.u[static_cast<std::size_t>(kDofsPerNode * h.node2)], d);
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((h.branches >> k) & 1U)) continue;
      double size = 0;
      (void)branch_excess(h, d, k, size);
      if (due && size > kClampTolerance) {  // rounding past a limit is left as it is
        any = true;
        if (size > largest) largest = size;
      }
      const bool upper = d[k] > 0.5 * (h.branch_upper[k] + h.branch_lower[k]);
      const double limit = upper ? h.branch_upper[k] : h.branch_lower[k];
      const double side = upper ? 1.0 : -1.0;
      c[n++] = {hi, k, side, side * (d[k] - limit),
                kClampTolerance * (limit != 0 ? (limit > 0 ? limit : -limit) : 1.0)};
    }
  }
  if (!any) {
    for (int q = t.first_stop; q < t.end_stop; ++q)
      w.clamp_checked[static_cast<std::size_t>(m.tree_stops[static_cast<std::size_t>(q)])] =
          w.clamp_events;
    return largest;
  }
  const ClampPart parts[2] = {ClampPart{static_cast<int>(&t - m.trees.data()), -1}, {}};
  double A[kClampBlock][kClampBlock];
  for (int j = 0; j < n; ++j) {
    clamp_response(m, w, m.hinges[static_cast<std::size_t>(c[j].hinge)], c[j].k, parts);
    for (int i = 0; i < n; ++i) {
      A[i][j] = c[i].side *
                clamp_projection(w, m.hinges[static_cast<std::size_t>(c[i].hinge)], c[i].k) *
                c[j].side;
    }
  }
  bool active[kClampBlock];
  for (int j = 0; j < n; ++j)
    active[j] = c[j].violation > 0 && A[j][j] > 0;
  double p[kClampBlock] = {};
  for (int round = 0; round <= 2 * kClampBlock; ++round) {
    // A = L D L^T on the active set, then p = A^-1 v there.
    double L[kClampBlock][kClampBlock] = {}, D[kClampBlock] = {};
    double scale = 0;
    for (int j = 0; j < n; ++j) {
      if (active[j] && A[j][j] > scale) scale = A[j][j];
    }
    for (int j = 0; j < n; ++j) {
      if (!active[j]) continue;
      double djj = A[j][j];
      for (int q = 0; q < j; ++q) {
        if (active[q]) djj -= L[j][q] * L[j][q] * D[q];
      }
      if (!(djj > 1e-12 * scale)) {  // dependent stops: clamp them one by one
        solved = false;
        return largest;
      }
      D[j] = djj;
      for (int i = j + 1; i < n; ++i) {
        if (!active[i]) continue;
        double sum = 0.5 * (A[i][j] + A[j][i]);  // symmetric up to rounding
        for (int q = 0; q < j; ++q) {
          if (active[q]) sum -= L[i][q] * L[j][q] * D[q];
        }
        L[i][j] = sum / djj;
      }
    }
    double z[kClampBlock] = {};
    for (int i = 0; i < n; ++i) {
      if (!active[i]) continue;
      double sum = c[i].violation;
      for (int q = 0; q < i; ++q) {
        if (active[q]) sum -= L[i][q] * z[q];
      }
      z[i] = sum;
    }
    for (int i = n - 1; i >= 0; --i) {
      p[i] = 0;
      if (!active[i]) continue;
      double sum = z[i] / D[i];
      for (int q = i + 1; q < n; ++q) {
        if (active[q]) sum -= L[q][i] * p[q];
      }
      p[i] = sum;
    }
    // A stop that would pull leaves the set; else the stop the move pushes furthest past its
    // limit joins it; else done.
    int out = -1, in = -1;
    double most_negative = 0, most_past = 0;
    for (int i = 0; i < n; ++i) {
      if (active[i]) {
        if (p[i] < most_negative) most_negative = p[i], out = i;
        continue;
      }
      double after = c[i].violation;
      for (int j = 0; j < n; ++j) {
        if (active[j]) after -= A[i][j] * p[j];
      }
      if (after > c[i].tolerance && after > most_past && A[i][i] > 0) most_past = after, in = i;
    }
    if (out >= 0) {
      active[out] = false;
    } else if (in >= 0) {
      active[in] = true;
    } else {
      break;
    }
  }
  // Looked at now; the joint move changes every stop's d, so each is looked at again next sweep.
  for (int q = t.first_stop; q < t.end_stop; ++q)
    w.clamp_checked[static_cast<std::size_t>(m.tree_stops[static_cast<std::size_t>(q)])] =
        w.clamp_events;
  const std::int64_t event = ++w.clamp_events;
  for (int j = 0; j < n; ++j) {
    if (!active[j] || !(p[j] > 0)) continue;
    clamp_response(m, w, m.hinges[static_cast<std::size_t>(c[j].hinge)], c[j].k, parts);
    clamp_move(m, s, w, parts, -c[j].side * p[j], event);
  }
  return largest;
}

// One sweep over the hinges with rigid branches; returns the largest excess it found, relative
// to the branch start. The stops whose two nodes lie in one rigid tree are solved tree by tree
// (clamp_tree); the others, and a tree whose stops are dependent, one by one (clamp_hinge).
template <Sizes S>
double momentum_clamp_sweep(const Model<S>& m, State<S>& s, Scratch<S>& w, bool first) {
  double largest = 0;
  for (int t = 0; t < m.num_trees; ++t) {
    const ForestTree& tree = m.trees[static_cast<std::size_t>(t)];
    if (tree.first_stop == tree.end_stop) continue;
    bool solved = true;
    largest = std::max(largest, clamp_tree(m, s, w, tree, first, solved));
    if (solved) continue;
    for (int q = tree.first_stop; q < tree.end_stop; ++q) {
      const int i = m.tree_stops[static_cast<std::size_t>(q)];
      const HingeData& h =
          m.hinges[static_cast<std::size_t>(m.branch_hinges[static_cast<std::size_t>(i)])];
      if (!clamp_due(w, h, w.clamp_checked[static_cast<std::size_t>(i)], first)) continue;
      largest = std::max(largest, clamp_hinge(m, s, w, h));
      w.clamp_checked[static_cast<std::size_t>(i)] = w.clamp_events;
    }
  }
  // node_tree is -1 everywhere but under ntn_exact, so every part is then a lone node.
  for (int i = 0; i < m.num_branch_hinges; ++i) {
    if (stop_tree(m, i) >= 0) continue;  // clamp_tree's
    const HingeData& h =
        m.hinges[static_cast<std::size_t>(m.branch_hinges[static_cast<std::size_t>(i)])];
    std::int64_t& checked = w.clamp_checked[static_cast<std::size_t>(i)];
    if (!clamp_due(w, h, checked, first)) continue;
    largest = std::max(largest, clamp_hinge(m, s, w, h));
    checked = w.clamp_events;
  }
  return largest;
}

// Sweeps until no branch is passed by more than kClampTolerance (relative), at most
// kClampSweeps times. One sweep is not enough where several stops act on one joint (two beams
// at their stops on either side of a column) and are clamped one at a time: each clamp moves
// the joint and reopens the others, and turning the leftover into velocity every step pumps
// energy into the model. Such stops in one rigid tree are solved together (clamp_tree), which
// takes one sweep and a second that finds nothing; stops between two parts are clamped one by
// one, sequential projections onto the (convex) admissible set in the mass metric, which
// converge; the bound keeps the step's cost bounded (DESIGN §7.1).
template <Sizes S>
void momentum_clamp(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  for (int sweep = 0; sweep < kClampSweeps; ++sweep) {
    if (!(momentum_clamp_sweep(m, s, w, sweep == 0) > kClampTolerance)) break;
  }
}

// After the update: rigid branches are clamped (momentum-conserving, or S 33), then ntn_paper's
// S 27-37 or ntn_exact's projection keep the rigid directions exact (DESIGN §7, §7.1): the trees
// that round (rotated or eccentric hinges) are re-projected; in aligned trees the forest keeps
// them exact by itself (select_projected_edges).
template <Sizes S>
void hinge_constraints(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  const bool paper = m.hinge_method == HingeMethod::kNtnPaper;
  if (!paper) {
    if (m.clamp == ClampRule::kMomentum) {
      momentum_clamp(m, s, w);
    } else {
      paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, false);
    }
  } else {
    paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, true);
  }
  if (m.hinge_method == HingeMethod::kNtnExact) {
    forest_project(m.edges, m.edge_matrices, m.project_edges, m.num_project_edges, s.u.data(),
                   s.v.data(), w.a.data(), m.inv_dt);
  }
}

// Every force and the accelerations at the current state: P_n, F_n, hinge springs, a_n.
template <Sizes S>
void forces_and_accelerations(const Model<S>& m, const State<S>& s, Scratch<S>& w, double t) {
  apply_loads(m, s, w, t);                            // P_n (§5)
  element_forces(m, s, w);                            // F_n (S 2)
  if constexpr (S.hinges > 0) hinge_forces(m, s, w);  // springs B^T f_L (§7)
  accelerations(m, s, w);                             // a_n (S 3-4, S 17-26, §7.1)
}

// Output channels at t_n: u_n, v_n = v_{n-1/2} + dt/2 a_n, a_n, end forces from u_n.
template <Sizes S>
void sample_outputs(const Model<S>& m, const State<S>& s, Scratch<S>& w, double t) {
  w.time = t;
  [[maybe_unused]] int coupled_tree = -1;  // hinge_force: the tree whose coupled R is in w.r
  for (int c = 0; c < S.outputs; ++c) {
    const OutputSpec& o = m.outputs[static_cast<std::size_t>(c)];
    const auto j = static_cast<std::size_t>(kDofsPerNode * o.node + o.dof);
    double value = 0;
    switch (o.kind) {
      case OutputKind::kDisplacement:
        value = s.u[j];
        break;
      case OutputKind::kVelocity:
        value = s.v[j] + 0.5 * m.dt * w.a[j];
        break;
      case OutputKind::kAcceleration:
        value = w.a[j];
        break;
      case OutputKind::kHingeForce:
        if constexpr (S.hinges > 0) value = hinge_force(m, s, w, o.hinge, o.dof, coupled_tree);
        break;
      case OutputKind::kHingeDisplacement:
        if constexpr (S.hinges > 0) value = hinge_displacement(m, s, o.hinge, o.dof);
        break;
      case OutputKind::kAbsoluteAcceleration:
        value = o.dof < 3 ? w.a[j] + w.ground[static_cast<std::size_t>(o.dof)] : w.a[j];
        break;
      case OutputKind::kElementForce: {
        const BeamData& b = m.beams[static_cast<std::size_t>(o.element)];
        const auto f = beam_local_end_forces(b, &s.u[static_cast<std::size_t>(6 * b.node_i)],
                                             &s.u[static_cast<std::size_t>(6 * b.node_j)]);
        value = f[static_cast<std::size_t>(6 * o.end + o.dof)];
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
        break;
    }
    w.outputs[static_cast<std::size_t>(c)] = value * o.scale;
  }
}

// v_{n+1/2} = v_{n-1/2} + dt a_n, u_{n+1} = u_n + dt v_{n+1/2} (S 5-7, constant dt).
// Returns false when a velocity is non-finite.
template <Sizes S>
bool update(const Model<S>& m, State<S>& s, const Scratch<S>& w) {
  const double dt = m.dt;  // a local: stores to s.v, s.u may alias m.dt, which blocks vectorizing
  // The check is a select into a double, not `ok &= finite(v)`: GCC vectorizes no loop with a
  // bool reduction, and this is a pass over every DOF.
  double bad = 0;
  for (std::size_t j = 0; j < static_cast<std::size_t>(Model<S>::kDofs); ++j) {
    const double v = s.v[j] + dt * w.a[j];
    s.v[j] = v;
    s.u[j] += dt * v;
    bad = finite(v) ? bad : 1.0;
  }
  return bad == 0;
}

}  // namespace detail

// Starts a run from the caller's u_0 and v_0 in `s` (zero by default): with ntn_exact, u_0 and
// v_0 first take the rigid components of their tree parents (the constraints hold from t_0);
// v_{-1/2} = v_0 - dt/2 a_0 (DESIGN §5), tick = 0.
template <Sizes S>
[[nodiscard]] StepStatus start(const Model<S>& m, State<S>& s, Scratch<S>& w,
                               const std::array<double, S.inputs>& in) {
  s.tick = 0;
  for (auto& h : s.held_inputs)
    h = 0.0;
  if constexpr (S.hinges > 0) {
    if (m.hinge_method == HingeMethod::kNtnExact)
      forest_project_initial(m.edges, m.edge_matrices, m.num_edges, s.u.data(), s.v.data());
  }
  const bool accepted = detail::accept_inputs(m, s, in);
  detail::forces_and_accelerations(m, s, w, 0.0);  // with C v_0
  for (std::size_t j = 0; j < static_cast<std::size_t>(Model<S>::kDofs); ++j) {
    s.v[j] -= 0.5 * m.dt * w.a[j];
  }
  return accepted ? StepStatus::kOk : StepStatus::kInputHeld;
}

// One step t_n -> t_{n+1}. Outputs in `w` are the channels at t_n.
template <Sizes S>
[[nodiscard]] StepStatus step(const Model<S>& m, State<S>& s, Scratch<S>& w,
                              const std::array<double, S.inputs>& in) {
  const bool accepted = detail::accept_inputs(m, s, in);  // hold non-finite inputs (§8)
  const double t = static_cast<double>(s.tick) * m.dt;
  detail::forces_and_accelerations(m, s, w, t);                    // P_n, F_n, hinge springs, a_n
  detail::sample_outputs(m, s, w, t);                              // channels at t_n
  const bool finite = detail::update(m, s, w);                     // v_{n+1/2}, u_{n+1} (S 5-7)
  if constexpr (S.hinges > 0) detail::hinge_constraints(m, s, w);  // clamps, S 27-37, §7.1
  ++s.tick;
  if (!finite) {
    s.faults |= kFaultDiverged;
    return StepStatus::kDiverged;
  }
  return accepted ? StepStatus::kOk : StepStatus::kInputHeld;
}

}  // namespace ntn
