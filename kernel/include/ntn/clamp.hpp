// Rigid branches ("stops") under clamp = "momentum" (DESIGN §7.1): the momentum-conserving clamp,
// one stop at a time or, for the stops inside one rigid tree, together by a small active-set
// L D L^T solve (clamp_tree); and the stops stage that picks it or the seed's S 33 clamp.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/ntn_paper.hpp"
#include "ntn/state.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp

// The rigid tree that holds both nodes of hinge h, or -1 (a ground hinge, or one between two
// parts).
template <Sizes S>
int hinge_tree(const Model<S>& m, const HingeData& h) {
  if (h.node2 == kGround) return -1;
  const std::int32_t t = m.node_tree[static_cast<std::size_t>(h.node1)];
  return t >= 0 && t == m.node_tree[static_cast<std::size_t>(h.node2)] ? t : -1;
}

// The rigid tree of stop hinge `i` (index into Model::branch_hinges), or -1: its stops are then
// solved with that tree's (clamp_tree).
template <Sizes S>
int stop_tree(const Model<S>& m, int i) {
  return hinge_tree(
      m, m.hinges[static_cast<std::size_t>(m.branch_hinges[static_cast<std::size_t>(i)])]);
}

// At init, after the forest's trees: the stop hinges of each tree, tree by tree
// (Model::tree_stops, ForestTree::first_stop, end_stop; a counting sort: count, ranges, place).
// Nothing without trees. The counts start from zero: init() into a Model that held another
// model counted on top of the old ones, wrote past tree_stops and corrupted what follows.
template <Sizes S>
void init_tree_stops(Model<S>& model) {
  for (int t = 0; t < model.num_trees; ++t)  // a Model built before holds the old counts
    model.trees[static_cast<std::size_t>(t)].first_stop =
        model.trees[static_cast<std::size_t>(t)].end_stop = 0;
  for (int i = 0; i < model.num_branch_hinges; ++i) {
    const int t = stop_tree(model, i);
    if (t >= 0) ++model.trees[static_cast<std::size_t>(t)].end_stop;
  }
  int placed = 0;
  for (int t = 0; t < model.num_trees; ++t) {
    ForestTree& tree = model.trees[static_cast<std::size_t>(t)];
    tree.first_stop = placed;
    placed += tree.end_stop;
    tree.end_stop = tree.first_stop;
  }
  for (int i = 0; i < model.num_branch_hinges; ++i) {
    const int t = stop_tree(model, i);
    if (t >= 0)
      model.tree_stops[static_cast<std::size_t>(
          model.trees[static_cast<std::size_t>(t)].end_stop++)] = i;
  }
}

namespace detail {

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

// Rigid branches with the momentum-conserving clamp (DESIGN §7.1): when a curve direction d
// passes its branch start, the model moves by the response of the whole constrained system to
// an impulse along that hinge direction (b = the direction's row of B), scaled so that d lands
// on d_lim: dx = -excess M_c^-1 b / (b^T M_c^-1 b), where M_c^-1 is the lumped inverse mass
// with the rigid trees applied (the forest's up and down passes). Momentum is kept because the
// impulse pair is equal and opposite, and the rigid directions stay exact because the response
// is a constrained motion. Without trees this is each node moving by its share of b^T M^-1 b.
// Only the trees of the hinge's two nodes (or the nodes themselves) respond, so an event costs
// the size of those trees, not of the model. Then S 35-37. Works in Scratch::clamp (ClampWork).

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

// An impulse r (per DOF, `impulse`) and the constrained system's response y = M_c^-1 r
// (`response`), over the parts' nodes: Scratch::clamp's in the step, InitWorkspace's at init
// (the slip directions' mobility, slip.hpp).
// The impulse set to zero over the parts' nodes.
template <Sizes S>
void clear_impulse(const Model<S>& m, const ClampPart (&parts)[2], double* impulse) {
  for (const ClampPart& p : parts) {
    for_each_node(m, p, [&](int n) {
      for (std::size_t c = 0; c < 6; ++c)
        impulse[static_cast<std::size_t>(kDofsPerNode * n) + c] = 0.0;
    });
  }
}

// impulse += scale b, b the row of B of direction k of hinge h.
inline void add_impulse(const HingeData& h, std::size_t k, double scale, double* impulse) {
  double b1[6], b2[6];
  hinge_direction(h, k, b1, b2);
  const bool ground = h.node2 == kGround;
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  for (std::size_t c = 0; c < 6; ++c) {
    impulse[i1 + c] += scale * b1[c];
    if (!ground) impulse[i2 + c] += scale * b2[c];
  }
}

// Each part's response: M^-1 r for a lone node, the forest's passes over a tree.
template <Sizes S>
void parts_response(const Model<S>& m, const ClampPart (&parts)[2], double* impulse,
                    double* response) {
  for (const ClampPart& p : parts) {
    if (p.node >= 0) {
      for (std::size_t c = 0; c < 6; ++c) {
        const auto j = static_cast<std::size_t>(kDofsPerNode * p.node) + c;
        response[j] = impulse[j] * m.inv_mass[j];
      }
    }
    if (p.tree < 0) continue;
    forest_tree_accelerations(m.trees[static_cast<std::size_t>(p.tree)], m.roots, m.edges,
                              m.edge_matrices, impulse, response);
  }
}

// b^T y for direction k of hinge h and the response y.
inline double response_along(const HingeData& h, std::size_t k, const double* response) {
  double b1[6], b2[6];
  hinge_direction(h, k, b1, b2);
  const bool ground = h.node2 == kGround;
  const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
  const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
  double sum = 0;
  for (std::size_t c = 0; c < 6; ++c) {
    sum += b1[c] * response[i1 + c];
    if (!ground) sum += b2[c] * response[i2 + c];
  }
  return sum;
}

// y = M_c^-1 b into w.clamp.response over the parts' nodes, b the impulse along direction k of
// hinge h.
template <Sizes S>
void clamp_response(const Model<S>& m, Scratch<S>& w, const HingeData& h, std::size_t k,
                    const ClampPart (&parts)[2]) {
  clear_impulse(m, parts, w.clamp.impulse.data());
  add_impulse(h, k, 1.0, w.clamp.impulse.data());
  parts_response(m, parts, w.clamp.impulse.data(), w.clamp.response.data());
}

// b^T y for the impulse along direction k of hinge h and the response y in w.clamp.response.
template <Sizes S>
double clamp_projection(const Scratch<S>& w, const HingeData& h, std::size_t k) {
  return response_along(h, k, w.clamp.response.data());
}

// The parts move by scale y (y in w.clamp.response): u, and v and a after it (S 35-37 as
// increments, with the weights of ClampWork: the step's, or start()'s trial).
template <Sizes S>
void clamp_move(const Model<S>& m, State<S>& s, Scratch<S>& w, const ClampPart (&parts)[2],
                double scale, std::int64_t event) {
  for (const ClampPart& p : parts) {
    for_each_node(m, p, [&](int n) {
      w.clamp.moved[static_cast<std::size_t>(n)] = event;
      for (std::size_t c = 0; c < 6; ++c) {
        const auto j = static_cast<std::size_t>(kDofsPerNode * n) + c;
        const double du = scale * w.clamp.response[j];
        s.u[j] += du;
        s.v[j] += du * w.clamp.v_rate;
        w.a[j] += du * m.inv_dt * m.inv_dt * w.clamp.a_scale;
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
  if (w.clamp.moved[static_cast<std::size_t>(h.node1)] > checked) return true;
  return h.node2 != kGround && w.clamp.moved[static_cast<std::size_t>(h.node2)] > checked;
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
    clamp_move(m, s, w, parts, -excess / mobility, ++w.clamp.events);
    w.stop_force[static_cast<std::size_t>(&h - m.hinges.data())][k] +=
        excess / (mobility * w.clamp.h2);  // the move's force: du = -f h2 M_c^-1 b
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
    const bool due = clamp_due(w, h, w.clamp.checked[static_cast<std::size_t>(i)], first);
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
      w.clamp.checked[static_cast<std::size_t>(m.tree_stops[static_cast<std::size_t>(q)])] =
          w.clamp.events;
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
    w.clamp.checked[static_cast<std::size_t>(m.tree_stops[static_cast<std::size_t>(q)])] =
        w.clamp.events;
  const std::int64_t event = ++w.clamp.events;
  for (int j = 0; j < n; ++j) {
    if (!active[j] || !(p[j] > 0)) continue;
    clamp_response(m, w, m.hinges[static_cast<std::size_t>(c[j].hinge)], c[j].k, parts);
    clamp_move(m, s, w, parts, -c[j].side * p[j], event);
    w.stop_force[static_cast<std::size_t>(c[j].hinge)][c[j].k] += c[j].side * p[j] / w.clamp.h2;
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
      if (!clamp_due(w, h, w.clamp.checked[static_cast<std::size_t>(i)], first)) continue;
      largest = std::max(largest, clamp_hinge(m, s, w, h));
      w.clamp.checked[static_cast<std::size_t>(i)] = w.clamp.events;
    }
  }
  // node_tree is -1 everywhere but under ntn_exact, so every part is then a lone node.
  for (int i = 0; i < m.num_branch_hinges; ++i) {
    if (stop_tree(m, i) >= 0) continue;  // clamp_tree's
    const HingeData& h =
        m.hinges[static_cast<std::size_t>(m.branch_hinges[static_cast<std::size_t>(i)])];
    std::int64_t& checked = w.clamp.checked[static_cast<std::size_t>(i)];
    if (!clamp_due(w, h, checked, first)) continue;
    largest = std::max(largest, clamp_hinge(m, s, w, h));
    checked = w.clamp.events;
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

}  // namespace detail

// The stops stage of ntn_exact and penalty (ntn_paper's S 33 runs inside its S 27-37 pass): the
// momentum-conserving clamp, or with clamp = "paper" the seed's S 33 alone (DESIGN §7.1).
namespace detail {
// Every stop direction's force (Scratch::stop_force) at zero, before a clamp adds its moves'.
template <Sizes S>
void clear_stop_forces(const Model<S>& m, Scratch<S>& w) {
  for (int i = 0; i < m.num_branch_hinges; ++i)
    w.stop_force[static_cast<std::size_t>(m.branch_hinges[static_cast<std::size_t>(i)])].fill(0.0);
}
}  // namespace detail

// The stops' forces (Scratch::stop_force) start at zero: the clamp adds its moves' forces; S 33
// scales displacements and reports none.
template <Sizes S>
void clamp_stops(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  detail::clear_stop_forces(m, w);
  if (m.clamp == ClampRule::kMomentum) {
    detail::momentum_clamp(m, s, w);
  } else {
    paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, false,
                       {w.clamp.moved.data(), ++w.clamp.events});
  }
}

// start(): the stops' forces at t_0, on start()'s trial (the momentum clamp or S 33, with its
// ClampWork weights).
template <Sizes S>
void clamp_start_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  detail::clear_stop_forces(m, w);
  if (m.clamp == ClampRule::kMomentum) {
    detail::momentum_clamp(m, s, w);
  } else {
    paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, false,
                       {nullptr, 0, true, w.clamp.a_scale});
  }
}

}  // namespace ntn
