// ntn_exact: the constraint forest of DESIGN §7.1. Rigid hinge directions join nodes into trees,
// rooted at the ground (a hinge to the ground), at a supported node, or at the node with the
// most rigid connections. Every matrix is constant (linear kinematics) and built once at init;
// a step is an upward pass (leaves to root: each child hands its parent a force), the roots'
// accelerations, and a downward pass (root to leaves: each child's acceleration from its
// parent's), then a projection that keeps the rigid directions exact to rounding.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/status.hpp"

namespace ntn {

// A 6x6 matrix (row-major) that knows which of its four 3x3 blocks are zero, so that the step
// skips them: an aligned pinned hinge costs a few 3x3 products, not 6x6 ones.
struct Mat6 {
  std::array<double, 36> a{};
  std::uint8_t blocks = 0;  // bit 2 * row_block + col_block: that block has a nonzero entry
};

// y += m x, rows in order, columns in order within each nonzero block (fixed summation order).
inline void mat6_madd(const Mat6& m, const double* x, double* y) {
  for (int br = 0; br < 2; ++br) {
    for (int bc = 0; bc < 2; ++bc) {
      if (!((m.blocks >> (2 * br + bc)) & 1U)) continue;
      for (int i = 0; i < 3; ++i) {
        const double* row = &m.a[static_cast<std::size_t>((3 * br + i) * 6 + 3 * bc)];
        const double* xs = x + 3 * bc;
        y[3 * br + i] += row[0] * xs[0] + row[1] * xs[1] + row[2] * xs[2];
      }
    }
  }
}

// The diagonal of a Mat6 when every entry off it is zero, and y += m x on it. Adding the products
// of the zero entries (+-0) never changes a nonzero sum, so this equals mat6_madd up to the sign
// of an exactly zero result.
struct Diag6 {
  std::array<double, 6> d{};
};

inline void diag6_madd(const Diag6& m, const double* x, double* y) {
  double t[6];  // all loads before the stores: the compiler need not assume y aliases x or m
  for (int i = 0; i < 6; ++i)
    t[i] = y[i] + m.d[static_cast<std::size_t>(i)] * x[i];
  for (int i = 0; i < 6; ++i)
    y[i] = t[i];
}

inline constexpr std::array<double, 6> kZero6{};  // the ground's motion: a, u, v all zero

// What the step's passes read of an edge (hot), kept apart from its 6x6 matrices (cold) so
// that a pass over aligned edges streams 120 bytes an edge instead of 2 KiB.
struct ForestEdge {
  std::int32_t child = 0;
  std::int32_t parent = kGround;
  std::int32_t hinge = 0;
  std::int32_t sign = 1;  // +1: the child is the hinge's node 1; -1: its node 2
  // A centric hinge whose frame is aligned with the global axes (the common case in frames):
  // up, down_a, proj_p and proj_c are one diagonal matrix, the rigid directions in global axes
  // (the seed's sums, S 20), and down_r is diagonal. The passes then use these two diagonals
  // and never read the edge's matrices.
  bool aligned = false;
  Diag6 rigid_d;
  Diag6 down_r_d;
};

// The general (rotated or eccentric) edge's matrices, one per edge at the edge's index.
struct ForestEdgeMatrices {
  Mat6 up;      // r_parent += up r_child                         (upward pass)
  Mat6 down_a;  // a_child = down_a a_parent + down_r r_child     (downward pass)
  Mat6 down_r;
  Mat6 proj_p;  // u_child += proj_p u_parent - proj_c u_child    (projection)
  Mat6 proj_c;
  Mat6 force_a;  // lambda = force_a a_child - force_r r_child     (hinge force, rigid rows)
  Mat6 force_r;
};

struct ForestRoot {
  std::int32_t node = 0;
  bool diagonal = false;  // inv_mass is diagonal: the step uses inv_mass_d
  Diag6 inv_mass_d;
  Mat6 inv_mass;  // inverse effective mass; zero rows and columns at held DOFs
};

namespace detail {

inline bool same(const Diag6& a, const Diag6& b) {
  for (std::size_t i = 0; i < 6; ++i) {
    if (a.d[i] != b.d[i]) return false;
  }
  return true;
}

// The diagonal of m into `out`; false if an entry off the diagonal is nonzero.
inline bool diagonal_of(const Mat6& m, Diag6& out) {
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const double x = m.a[static_cast<std::size_t>(6 * i + j)];
      if (i == j) {
        out.d[static_cast<std::size_t>(i)] = x;
      } else if (x != 0.0) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace detail

// ---- The rigid graph and its cycles (DESIGN §7.1): the one rule ----------------------------
//
// The graph has a vertex per node and one for the ground, an edge per hinge with a rigid
// direction, and an edge to the ground for every supported node (NodeSpec::fixed != 0) that such
// a hinge touches. Supports go in first, then the hinges in order; the first hinge that joins two
// vertices already joined closes a cycle (two hinges between one pair, a loop, a tree that reaches
// the ground twice). The kernel (build_forest), the model compiler (its file:line:column message
// names the hinge and the cycle's nodes) and modal analysis all ask this function.

// Caller-owned workspace, no heap. `set` (one entry per node) is required; `up` and `mark` (one
// per node plus one for the ground) and `path` (the same) only when the cycle's nodes are wanted:
// leave all three empty for the closing hinges alone.
struct RigidCycleWork {
  std::span<std::int32_t> set;  // union-find: parent, or -1 (a root) / -2 (a root joined to ground)
  std::span<std::int32_t> up;   // the accepted edges as a forest of parent links (ground: last)
  std::span<std::int32_t> mark;  // ancestors of the hinge's node 1, by hinge index
  std::span<std::int32_t> path;  // receives the cycle's nodes (kGround for the ground)
};

// Calls on_cycle(hinge, nodes) for each hinge that closes a cycle, `nodes` the cycle from the
// hinge's node 1 to its node 2 (empty without path workspace); stops early when on_cycle returns
// false. `rigid(h)` says whether hinge h has a rigid direction (the caller's rule: HingeData::rigid
// for the kernel, the declared behaviour for the model compiler). Returns the number of cycles
// reported. Hinge nodes must be valid (0..nodes-1, node2 also kGround).
template <class Hinge, class IsRigid, class OnCycle>
int for_each_rigid_cycle(std::span<const Hinge> hinges, std::span<const NodeSpec> nodes,
                         IsRigid rigid, const RigidCycleWork& w, OnCycle on_cycle) {
  const int n = static_cast<int>(nodes.size());
  const int ground = n;  // the ground's vertex in `up`, `mark`
  const bool paths = !w.path.empty();
  auto at = [](std::span<std::int32_t> s, int i) -> std::int32_t& {
    return s[static_cast<std::size_t>(i)];
  };
  const int nh = static_cast<int>(hinges.size());
  for (int i = 0; i < n; ++i)
    at(w.set, i) = -1;
  for (int h = 0; h < nh; ++h) {  // touched by a rigid hinge: -3 until the supports are in
    if (!rigid(h)) continue;
    const Hinge& hd = hinges[static_cast<std::size_t>(h)];
    at(w.set, hd.node1) = -3;
    if (hd.node2 != kGround) at(w.set, hd.node2) = -3;
  }
  for (int i = 0; i < n; ++i) {
    const bool grounded = at(w.set, i) == -3 && nodes[static_cast<std::size_t>(i)].fixed != 0;
    at(w.set, i) = grounded ? -2 : -1;
    if (paths) at(w.up, i) = grounded ? ground : -1, at(w.mark, i) = -1;
  }
  if (paths) at(w.up, ground) = -1, at(w.mark, ground) = -1;
  auto find = [&](int x) {
    while (at(w.set, x) >= 0) {
      const int p = at(w.set, x);
      if (at(w.set, p) >= 0) at(w.set, x) = at(w.set, p);  // path halving
      x = at(w.set, x);
    }
    return x;
  };
  auto evert = [&](int x) {  // makes x the root of its tree in `up`
    for (int prev = -1; x != -1;) {
      const int next = at(w.up, x);
      at(w.up, x) = prev;
      prev = x, x = next;
    }
  };
  auto node_of = [ground](int v) { return v == ground ? kGround : v; };
  int cycles = 0;
  for (int h = 0; h < nh; ++h) {
    if (!rigid(h)) continue;
    const Hinge& hd = hinges[static_cast<std::size_t>(h)];
    const int a = hd.node1, b = hd.node2 == kGround ? ground : hd.node2;
    const int ra = find(a), rb = b == ground ? ground : find(b);
    const bool ga = at(w.set, ra) == -2, gb = b == ground || at(w.set, rb) == -2;
    if ((b != ground && ra == rb) || (ga && gb)) {
      ++cycles;
      int len = 0;
      if (paths) {  // a up to the lowest common ancestor, then down to b
        for (int x = a; x != -1; x = at(w.up, x))
          at(w.mark, x) = h;
        int lca = b;
        while (at(w.mark, lca) != h)
          lca = at(w.up, lca);
        for (int x = a;; x = at(w.up, x)) {
          at(w.path, len++) = node_of(x);
          if (x == lca) break;
        }
        int tail = 0;
        for (int y = b; y != lca; y = at(w.up, y))
          ++tail;
        len += tail;
        int j = len - 1;
        for (int y = b; y != lca; y = at(w.up, y))
          at(w.path, j--) = node_of(y);
      }
      if (!on_cycle(h, std::span<const std::int32_t>(w.path.data(), static_cast<std::size_t>(len))))
        return cycles;
      continue;
    }
    if (b == ground) {
      at(w.set, ra) = -2;
    } else {
      at(w.set, ra) = rb;
      if (ga) at(w.set, rb) = -2;
    }
    if (paths) {  // hang the side not joined to the ground from the other (the ground stays a root)
      if (ga) {
        evert(b), at(w.up, b) = a;
      } else {
        evert(a), at(w.up, a) = b;
      }
    }
  }
  return cycles;
}

// build_forest's workspace, one entry per hinge (init only: init() keeps it out of the Model).
struct ForestWork {
  // Step 2: the k-th placed edge (breadth-first, parents first) before it is written to `edges`.
  std::int32_t hinge = 0;
  std::int32_t child = 0;
  std::int32_t parent = kGround;
  std::int32_t sign = 1;
  Mat6 mass_up;  // step 3: the mass edge k hands its parent, T^T G S G^T T (DESIGN §7.1)
};

struct ForestBuild {
  InitStatus status;
  int edges = 0;
  int roots = 0;
  int held_dofs = 0;  // mechanism DOFs held at zero (DESIGN §7.1)
};

// The forest's topology (DESIGN §7.1): which nodes form each rigid tree, its root, and its edges
// breadth-first, parents before children, trees one after the other. `node_tree` (per node)
// receives the tree index or -1; `edges` (per hinge) the edges' child, parent, hinge and sign,
// `roots` (per hinge) the root node of each tree not rooted at the ground; `work` (per
// hinge) is workspace. A cycle of rigid connections (for_each_rigid_cycle) is refused (kRigidCycle,
// `where` = the hinge that closes it). Modal analysis builds its constraint transformation on this
// same topology.
inline ForestBuild forest_topology(std::span<const HingeData> hinges,
                                   std::span<const NodeSpec> nodes, std::span<const double> mass,
                                   std::span<std::int32_t> node_tree, std::span<ForestEdge> edges,
                                   std::span<ForestRoot> roots, std::span<ForestWork> work) {
  ForestBuild out;
  const int nh = static_cast<int>(hinges.size());
  auto rigid = [&](int h) { return hinges[static_cast<std::size_t>(h)].rigid != 0; };
  {  // 0. The cycle rule, with node_tree as its union-find workspace.
    int closing = -1;
    (void)for_each_rigid_cycle(hinges, nodes, rigid, RigidCycleWork{node_tree, {}, {}, {}},
                               [&closing](int h, std::span<const std::int32_t>) {
                                 closing = h;
                                 return false;
                               });
    if (closing >= 0) {
      out.status = {InitError::kRigidCycle, closing};
      return out;
    }
  }
  for (auto& t : node_tree)
    t = -1;
  auto tree_of = [&](int n) { return n == kGround ? -2 : node_tree[static_cast<std::size_t>(n)]; };

  // 1. Trees: grow each from an unassigned rigid hinge until no hinge touches it. Until the
  // edges are ordered, edges[h].hinge holds hinge h's tree (-1: none yet).
  int trees = 0;
  for (int h = 0; h < nh; ++h)
    edges[static_cast<std::size_t>(h)].hinge = -1;
  for (int seed = 0; seed < nh; ++seed) {
    if (!rigid(seed) || edges[static_cast<std::size_t>(seed)].hinge >= 0) continue;
    const int t = trees++;
    node_tree[static_cast<std::size_t>(hinges[static_cast<std::size_t>(seed)].node1)] = t;
    for (bool grew = true; grew;) {
      grew = false;
      for (int h = 0; h < nh; ++h) {
        if (!rigid(h) || edges[static_cast<std::size_t>(h)].hinge >= 0) continue;
        const HingeData& hd = hinges[static_cast<std::size_t>(h)];
        if (tree_of(hd.node1) != t && tree_of(hd.node2) != t) continue;
        edges[static_cast<std::size_t>(h)].hinge = t;
        node_tree[static_cast<std::size_t>(hd.node1)] = t;
        if (hd.node2 != kGround) node_tree[static_cast<std::size_t>(hd.node2)] = t;
        grew = true;
      }
    }
  }

  // 2. Per tree (acyclic by step 0): pick the root and place the tree's edges breadth-first,
  // parents before children. Placements go to `work` (until build_forest's step 3) and a placed
  // hinge is marked with tree id -(t + 2).
  int written = 0;
  auto stash = [&](int k) -> ForestWork& { return work[static_cast<std::size_t>(k)]; };
  for (int t = 0; t < trees; ++t) {
    int grounds = 0, supported = 0;
    for (std::size_t n = 0; n < node_tree.size(); ++n) {
      if (node_tree[n] == t && nodes[n].fixed != 0) ++supported;
    }
    for (int h = 0; h < nh; ++h) {
      if (edges[static_cast<std::size_t>(h)].hinge == t &&
          hinges[static_cast<std::size_t>(h)].node2 == kGround)
        ++grounds;
    }
    // Root: the ground, else the supported node, else the node with the most rigid hinges
    // (a joint), then the heaviest, then the lowest index.
    int root = kGround;
    if (grounds == 0) {
      int best_degree = -1;
      double best_mass = -1;
      for (std::size_t n = 0; n < node_tree.size(); ++n) {
        if (node_tree[n] != t) continue;
        if (supported > 0) {
          if (nodes[n].fixed != 0) root = static_cast<int>(n);
          continue;
        }
        int degree = 0;
        for (int h = 0; h < nh; ++h) {
          const HingeData& hd = hinges[static_cast<std::size_t>(h)];
          if (edges[static_cast<std::size_t>(h)].hinge == t &&
              (hd.node1 == static_cast<int>(n) || hd.node2 == static_cast<int>(n)))
            ++degree;
        }
        const double m = mass[6 * n] + mass[6 * n + 1] + mass[6 * n + 2];
        if (degree > best_degree || (degree == best_degree && m > best_mass)) {
          root = static_cast<int>(n), best_degree = degree, best_mass = m;
        }
      }
      roots[static_cast<std::size_t>(out.roots++)].node = root;
    }
    auto place_children_of = [&](int parent) {
      for (int h = 0; h < nh; ++h) {
        if (edges[static_cast<std::size_t>(h)].hinge != t) continue;
        const HingeData& hd = hinges[static_cast<std::size_t>(h)];
        int child = -1, sign = 1;
        if (hd.node2 == parent) {
          child = hd.node1, sign = 1;
        } else if (parent != kGround && hd.node1 == parent) {
          child = hd.node2, sign = -1;
        }
        if (child < 0) continue;
        edges[static_cast<std::size_t>(h)].hinge = -(t + 2);
        ForestWork& slot = stash(written++);
        slot.hinge = h, slot.child = child, slot.parent = parent, slot.sign = sign;
      }
    };
    int level_begin = written;
    place_children_of(root);
    while (level_begin < written) {
      const int level_end = written;
      for (int k = level_begin; k < level_end; ++k) {
        place_children_of(stash(k).child);
      }
      level_begin = level_end;
    }
  }
  // Unstash the placements into the edges (hinge indices were tree marks until now).
  for (int k = 0; k < written; ++k) {
    const ForestWork& slot = work[static_cast<std::size_t>(k)];
    ForestEdge& e = edges[static_cast<std::size_t>(k)];
    e = ForestEdge{};
    e.hinge = slot.hinge;
    e.child = slot.child;
    e.parent = slot.parent;
    e.sign = slot.sign;
  }
  out.edges = written;
  return out;
}

// Builds the forest of the hinges' rigid directions: its topology (forest_topology), then each
// edge's constant matrices and each root's inverse effective mass. `held` (per node) receives the
// DOFs held at zero as mechanisms; `work` has one entry per hinge (init only: init() keeps it out
// of the Model).
ForestBuild build_forest(std::span<const HingeData> hinges, std::span<const NodeSpec> nodes,
                         std::span<const double> mass, std::span<std::int32_t> node_tree,
                         std::span<ForestEdge> edges, std::span<ForestEdgeMatrices> mats,
                         std::span<ForestRoot> roots, std::span<ForestWork> work,
                         std::span<std::uint8_t> held);

// Upward pass, leaves to root: each child hands its parent T^T G (G^T R_q - ...) (DESIGN §7.1).
// The edges of one parent are consecutive (build_forest places them breadth-first), so its sum
// stays in registers while they add to it, in the same order as one edge at a time.
inline void forest_up(std::span<const ForestEdge> edges, std::span<const ForestEdgeMatrices> mats,
                      int count, double* r) {
  int k = count - 1;
  while (k >= 0) {
    const std::int32_t parent = edges[static_cast<std::size_t>(k)].parent;
    if (parent == kGround) {
      --k;
      continue;
    }
    double* rp = r + 6 * parent;
    double sum[6];
    for (int d = 0; d < 6; ++d)
      sum[d] = rp[d];
    for (; k >= 0 && edges[static_cast<std::size_t>(k)].parent == parent; --k) {
      const ForestEdge& e = edges[static_cast<std::size_t>(k)];
      if (e.aligned) {
        diag6_madd(e.rigid_d, r + 6 * e.child, sum);
      } else {
        mat6_madd(mats[static_cast<std::size_t>(k)].up, r + 6 * e.child, sum);
      }
    }
    for (int d = 0; d < 6; ++d)
      rp[d] = sum[d];
  }
}

// Roots, then the downward pass: a_root = M_root^-1 R_root; a_c = Y^-1 q (DESIGN §7.1).
// `r` holds the forces of the upward pass; `a` receives the accelerations and may be `r` itself
// (the step works in place: each node's forces are read before its accelerations are stored).
inline void forest_down(std::span<const ForestRoot> roots, int root_count,
                        std::span<const ForestEdge> edges, std::span<const ForestEdgeMatrices> mats,
                        int count, const double* r, double* a) {
  for (int k = 0; k < root_count; ++k) {
    const ForestRoot& root = roots[static_cast<std::size_t>(k)];
    double rr[6], ar[6] = {0, 0, 0, 0, 0, 0};
    for (int d = 0; d < 6; ++d)
      rr[d] = r[6 * root.node + d];
    if (root.diagonal) {
      for (int d = 0; d < 6; ++d)
        ar[d] = root.inv_mass_d.d[static_cast<std::size_t>(d)] * rr[d];
    } else {
      mat6_madd(root.inv_mass, rr, ar);
    }
    for (int d = 0; d < 6; ++d)
      a[6 * root.node + d] = ar[d];
  }
  for (int k = 0; k < count; ++k) {
    const ForestEdge& e = edges[static_cast<std::size_t>(k)];
    double rc[6], ac[6];
    for (int d = 0; d < 6; ++d)
      rc[d] = r[6 * e.child + d];
    const double* ap = e.parent != kGround ? a + 6 * e.parent : kZero6.data();
    if (e.aligned) {
      // a_c = G a_p + down_r r_c with G the 0/1 rigid diagonal, in one pass
      for (int d = 0; d < 6; ++d) {
        const auto i = static_cast<std::size_t>(d);
        ac[d] = e.rigid_d.d[i] * ap[d] + e.down_r_d.d[i] * rc[d];
      }
    } else {
      for (int d = 0; d < 6; ++d)
        ac[d] = 0;
      const ForestEdgeMatrices& mx = mats[static_cast<std::size_t>(k)];
      if (e.parent != kGround) mat6_madd(mx.down_a, ap, ac);
      mat6_madd(mx.down_r, rc, ac);
    }
    for (int d = 0; d < 6; ++d)
      a[6 * e.child + d] = ac[d];
  }
}

// The change of the child's x (u or v) that gives its rigid components of q its parent's:
// delta = P_p x_parent - P_c x_child (a 0/1 diagonal for an aligned edge).
inline void edge_delta(const ForestEdge& e, const ForestEdgeMatrices& mx, const double* x,
                       double* delta) {
  double to[6] = {0, 0, 0, 0, 0, 0}, back[6] = {0, 0, 0, 0, 0, 0};
  const double* xc = x + 6 * e.child;
  if (e.aligned) {
    if (e.parent != kGround) diag6_madd(e.rigid_d, x + 6 * e.parent, to);
    diag6_madd(e.rigid_d, xc, back);
  } else {
    if (e.parent != kGround) mat6_madd(mx.proj_p, x + 6 * e.parent, to);
    mat6_madd(mx.proj_c, xc, back);
  }
  for (int d = 0; d < 6; ++d)
    delta[d] = to[d] - back[d];
}

// Projection of one edge, after its parent's: the child's rigid components of q are set from its
// parent's (generalizes S 30-31), and v, a of the changed DOFs follow (S 35-37): a change du of
// u_{n+1} changes v_{n+1/2} by du / dt and a_n by du / dt^2.
// Returns whether it moved the child (a delta not zero).
inline bool project_edge(const ForestEdge& e, const ForestEdgeMatrices& mx, double* u, double* v,
                         double* a, double inv_dt) {
  double delta[6];
  edge_delta(e, mx, u, delta);
  double* uc = u + 6 * e.child;
  double* vc = v + 6 * e.child;
  double* ac = a + 6 * e.child;
  double nu[6], nv[6], na[6];  // loads before stores, as in diag6_madd
  for (int d = 0; d < 6; ++d) {
    nu[d] = uc[d] + delta[d];
    nv[d] = vc[d] + delta[d] * inv_dt;
    na[d] = ac[d] + delta[d] * inv_dt * inv_dt;
  }
  for (int d = 0; d < 6; ++d)
    uc[d] = nu[d];
  for (int d = 0; d < 6; ++d)
    vc[d] = nv[d];
  for (int d = 0; d < 6; ++d)
    ac[d] = na[d];
  bool changed = false;
  for (int d = 0; d < 6; ++d)
    changed = changed || delta[d] != 0.0;
  return changed;
}

// Projection after the update, root to leaves, of the edges in `list` (ascending, so parents
// first): see select_projected_edges for which edges need it. A child it moves gets `event` in
// `moved` (ClampWork::moved), where given.
inline void forest_project(std::span<const ForestEdge> edges,
                           std::span<const ForestEdgeMatrices> mats,
                           std::span<const std::int32_t> list, int count, double* u, double* v,
                           double* a, double inv_dt, std::int64_t* moved = nullptr,
                           std::int64_t event = 0) {
  for (int k = 0; k < count; ++k) {
    const auto e = static_cast<std::size_t>(list[static_cast<std::size_t>(k)]);
    if (project_edge(edges[e], mats[e], u, v, a, inv_dt) && moved != nullptr)
      moved[edges[e].child] = event;
  }
}

// One rigid tree: its edges [first_edge, end_edge) (contiguous: build_forest places the trees
// one after the other) and its root (index into the roots), or -1 when rooted at the ground.
struct ForestTree {
  std::int32_t first_edge = 0;
  std::int32_t end_edge = 0;
  std::int32_t root = -1;
  std::int32_t first_stop = 0;  // its stop hinges with both nodes in it: Model::tree_stops range
  std::int32_t end_stop = 0;
};

// One tree's accelerations: its upward pass, its root, its downward pass (DESIGN §7.1).
inline void forest_tree_accelerations(const ForestTree& t, std::span<const ForestRoot> roots,
                                      std::span<const ForestEdge> edges,
                                      std::span<const ForestEdgeMatrices> mats, double* r,
                                      double* a) {
  const auto first = static_cast<std::size_t>(t.first_edge);
  const int count = t.end_edge - t.first_edge;
  const auto tree_edges = edges.subspan(first);
  const auto tree_mats = mats.subspan(first);
  forest_up(tree_edges, tree_mats, count, r);
  const auto root = roots.subspan(static_cast<std::size_t>(t.root < 0 ? 0 : t.root));
  forest_down(root, t.root < 0 ? 0 : 1, tree_edges, tree_mats, count, r, a);
}

// The trees of a built forest, in the order of node_tree's indices; returns their number.
// A tree is rooted at the ground when its first edge hangs from the ground; the others take the
// roots in order (build_forest adds a root for each tree not rooted at the ground).
inline int forest_trees(std::span<const ForestEdge> edges, std::span<const std::int32_t> node_tree,
                        std::span<ForestTree> out) {
  int n = 0, roots = 0;
  std::size_t begin = 0;
  while (begin < edges.size()) {
    const std::int32_t tree = node_tree[static_cast<std::size_t>(edges[begin].child)];
    std::size_t end = begin;
    while (end < edges.size() && node_tree[static_cast<std::size_t>(edges[end].child)] == tree)
      ++end;
    ForestTree& t = out[static_cast<std::size_t>(n++)];
    t.first_edge = static_cast<std::int32_t>(begin);
    t.end_edge = static_cast<std::int32_t>(end);
    t.root = edges[begin].parent == kGround ? -1 : roots++;
    begin = end;
  }
  return n;
}

// Which edges the step re-projects (DESIGN §7.1); returns their number, indices in `out`.
// In a tree whose edges are all aligned, the downward pass sets a child's rigid accelerations to
// its parent's exactly (a product by 1 plus products by 0), and the update then moves child and
// parent alike, so their rigid components stay equal with no projection: projecting would
// change at most the sign of a zero. A tree with a rotated or eccentric edge rounds, so all its
// edges are re-projected every step; so is every tree when the S 33 clamp (`all`), which moves
// single nodes, is in use.
inline int select_projected_edges(std::span<const ForestEdge> edges,
                                  std::span<const ForestTree> trees, bool all,
                                  std::span<std::int32_t> out) {
  int n = 0;
  for (const ForestTree& t : trees) {
    const auto begin = edges.begin() + t.first_edge, end = edges.begin() + t.end_edge;
    if (all || !std::all_of(begin, end, [](const ForestEdge& e) { return e.aligned; })) {
      for (std::int32_t k = t.first_edge; k < t.end_edge; ++k)
        out[static_cast<std::size_t>(n++)] = k;
    }
  }
  return n;
}

// The initial conditions onto the constraints, root to leaves, every edge: u_0 and v_0 of each
// child take their parent's rigid components (start() does this once, so that the step need
// only re-project the trees that round).
inline void forest_project_initial(std::span<const ForestEdge> edges,
                                   std::span<const ForestEdgeMatrices> mats, int count, double* u,
                                   double* v) {
  for (int k = 0; k < count; ++k) {
    const ForestEdge& e = edges[static_cast<std::size_t>(k)];
    for (double* x : {u, v}) {
      double delta[6];
      edge_delta(e, mats[static_cast<std::size_t>(k)], x, delta);
      for (int d = 0; d < 6; ++d)
        x[6 * e.child + d] += delta[d];
    }
  }
}

// Hinge force in the rigid directions, on node 1 in the hinge frame:
// lambda = G^T (M_q q - R_q) for the child, negated when the child is node 2.
inline void forest_hinge_force(const ForestEdge& e, const ForestEdgeMatrices& mx, const double* a,
                               const double* r, double* lambda) {
  double fa[6] = {0, 0, 0, 0, 0, 0}, fr[6] = {0, 0, 0, 0, 0, 0};
  mat6_madd(mx.force_a, a + 6 * e.child, fa);
  mat6_madd(mx.force_r, r + 6 * e.child, fr);
  for (int d = 0; d < 6; ++d)
    lambda[d] = static_cast<double>(e.sign) * (fa[d] - fr[d]);
}

}  // namespace ntn
