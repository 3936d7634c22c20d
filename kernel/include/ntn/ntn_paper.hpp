// ntn_paper: the seed's NTN modification taken literally (S 17-37), hinge by hinge in index
// order, and the S 33 clamp (also used by clamp = "paper" with the other methods).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/residual.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp
template <Sizes S>
struct InitWorkspace;  // model.hpp

namespace detail {

// Local components (hinge frame) of the translation or rotation block of one node vector.
inline void to_hinge(const HingeData& h, const double* g, double* l) {
  const auto& R = h.frame;
  for (int r = 0; r < 3; ++r) {
    l[r] = R[static_cast<std::size_t>(3 * r)] * g[0] +
           R[static_cast<std::size_t>(3 * r + 1)] * g[1] +
           R[static_cast<std::size_t>(3 * r + 2)] * g[2];
  }
}

inline void from_hinge(const HingeData& h, const double* l, double* g) {
  const auto& R = h.frame;
  for (int c = 0; c < 3; ++c) {
    g[c] = R[static_cast<std::size_t>(c)] * l[0] + R[static_cast<std::size_t>(3 + c)] * l[1] +
           R[static_cast<std::size_t>(6 + c)] * l[2];
  }
}

// Diagonal of T_R diag(m) T_R^T (S 23, then diagonalized) for one 3-DOF block.
inline void mass_to_hinge(const HingeData& h, const double* m, double* l) {
  const auto& R = h.frame;
  for (int r = 0; r < 3; ++r) {
    l[r] = 0;
    for (int c = 0; c < 3; ++c) {
      const double t = R[static_cast<std::size_t>(3 * r + c)];
      l[r] += t * t * m[c];
    }
  }
}

// Diagonal of T_R^T diag(l) T_R (S 26, diagonalized).
inline void mass_from_hinge(const HingeData& h, const double* l, double* m) {
  const auto& R = h.frame;
  for (int c = 0; c < 3; ++c) {
    m[c] = 0;
    for (int r = 0; r < 3; ++r) {
      const double t = R[static_cast<std::size_t>(3 * r + c)];
      m[c] += t * t * l[r];
    }
  }
}

// A node is "rigidly supported" in hinge direction k (S 30-31) when every global DOF that the
// direction touches is held; the ground is supported in every direction.
inline bool supported_in(const HingeData& h, int node, std::span<const std::uint8_t> fixed,
                         std::size_t k) {
  if (node == kGround) return true;
  const std::size_t row = k % 3, block = k < 3 ? 0 : 3;
  for (std::size_t c = 0; c < 3; ++c) {
    if (h.frame[3 * row + c] != 0 && !((fixed[static_cast<std::size_t>(node)] >> (block + c)) & 1U))
      return false;
  }
  return true;
}

}  // namespace detail

// S 22-26, at init: for every hinge in index order, the hinge-frame masses of its two nodes
// (diagonalized) are summed in the rigid directions and taken back to global axes (diagonalized).
// `mass` (per DOF) is modified in place; the ground takes no part.
inline void paper_masses(std::span<const HingeData> hinges, std::span<double> mass) {
  for (const HingeData& h : hinges) {
    if (h.node2 == kGround || h.rigid == 0) continue;
    double* m[2] = {mass.data() + 6 * h.node1, mass.data() + 6 * h.node2};
    for (int block = 0; block < 6; block += 3) {
      double l[2][3], dum[2][3];
      for (int j = 0; j < 2; ++j) {
        detail::mass_to_hinge(h, m[j] + block, l[j]);  // S 23
        for (int r = 0; r < 3; ++r)
          dum[j][r] = l[j][r];  // S 24
      }
      for (int r = 0; r < 3; ++r) {  // S 25
        if (!((h.rigid >> (block + r)) & 1U)) continue;
        l[0][r] += dum[1][r];
        l[1][r] += dum[0][r];
      }
      for (int j = 0; j < 2; ++j)
        detail::mass_from_hinge(h, l[j], m[j] + block);  // S 26
    }
  }
}

// S 17-21, every step: for every hinge, the hinge-frame forces of its two nodes (copies taken
// before the modification) are summed in the rigid directions and taken back.
inline void paper_forces(std::span<const HingeData> hinges, double* r) {
  for (const HingeData& h : hinges) {
    if (h.node2 == kGround || h.rigid == 0) continue;
    double* g[2] = {r + 6 * h.node1, r + 6 * h.node2};
    for (int block = 0; block < 6; block += 3) {
      double l[2][3], dum[2][3];
      for (int j = 0; j < 2; ++j) {
        detail::to_hinge(h, g[j] + block, l[j]);  // S 18
        for (int k = 0; k < 3; ++k)
          dum[j][k] = l[j][k];  // S 19
      }
      for (int k = 0; k < 3; ++k) {  // S 20
        if (!((h.rigid >> (block + k)) & 1U)) continue;
        l[0][k] += dum[1][k];
        l[1][k] += dum[0][k];
      }
      for (int j = 0; j < 2; ++j)
        detail::from_hinge(h, l[j], g[j] + block);  // S 21
    }
  }
}

// Applies a change of u_{n+1} to v_{n+1/2} and a_n (S 35-37 written as increments). `trial`:
// start()'s trial u_1 (integrator.hpp), where v_0 stays and a_0 takes du / dt^2 times
// `a_scale` (2: a force over the first half step alone).
inline void apply_correction(double* u, double* v, double* a, const double* du, double inv_dt,
                             bool trial = false, double a_scale = 1.0) {
  for (int d = 0; d < 6; ++d) {
    u[d] += du[d];
    if (trial) {
      a[d] += du[d] * inv_dt * inv_dt * a_scale;
    } else {
      v[d] += du[d] * inv_dt;
      a[d] += du[d] * inv_dt * inv_dt;
    }
  }
}

// Where paper_after_update marks the nodes it moves (ClampWork::moved: `event`; none without),
// and whether it corrects start()'s trial (apply_correction, with ClampWork::a_scale).
struct PaperMarks {
  std::int64_t* moved = nullptr;
  std::int64_t event = 0;
  bool trial = false;
  double a_scale = 1.0;
};

// S 27-37, after the update: displacements in the hinge frame (S 28); supported hinges copy the
// supported node's rigid components (S 30-31); rigid branches of curves scale both nodes by
// d_lim / d (S 32-33); back to global (S 34); v and a of the changed DOFs follow (S 35-37).
// With `couple` false only the clamps run (clamp = "paper" with ntn_exact or penalty, and
// start()'s trial).
inline void paper_after_update(std::span<const HingeData> hinges,
                               std::span<const std::uint8_t> fixed, double* u, double* v, double* a,
                               double inv_dt, bool couple = true, PaperMarks marks = {}) {
  for (const HingeData& h : hinges) {
    if ((h.rigid == 0 || !couple) && h.branches == 0) continue;
    double* g1 = u + 6 * h.node1;
    double* g2 = h.node2 == kGround ? nullptr : u + 6 * h.node2;
    double l[2][6] = {}, dum[2][6] = {};
    for (int block = 0; block < 6; block += 3) {
      detail::to_hinge(h, g1 + block, l[0] + block);
      if (g2 != nullptr) detail::to_hinge(h, g2 + block, l[1] + block);
    }
    for (int k = 0; k < 6; ++k)
      dum[0][k] = l[0][k], dum[1][k] = l[1][k];  // S 29
    for (std::size_t k = 0; k < 6 && couple; ++k) {
      if (!((h.rigid >> k) & 1U)) continue;
      if (detail::supported_in(h, h.node2, fixed, k)) {
        l[0][k] = dum[1][k];  // S 30
      } else if (detail::supported_in(h, h.node1, fixed, k)) {
        l[1][k] = dum[0][k];  // S 31
      }
    }
    for (std::size_t k = 0; k < 6; ++k) {
      if (!((h.branches >> k) & 1U)) continue;
      const double d = l[1][k] - l[0][k];  // S 32
      const double lim = d > h.branch_upper[k]   ? h.branch_upper[k]
                         : d < h.branch_lower[k] ? h.branch_lower[k]
                                                 : d;
      if (lim == d || d == 0) continue;
      l[0][k] *= lim / d;  // S 33
      l[1][k] *= lim / d;
    }
    double n1[6], n2[6], du[6];
    for (int block = 0; block < 6; block += 3) {
      detail::from_hinge(h, l[0] + block, n1 + block);  // S 34
      detail::from_hinge(h, l[1] + block, n2 + block);
    }
    // Only the components the modification touched change, so rounding of the round trip
    // through the hinge frame does not move untouched DOFs.
    for (int j = 0; j < 2; ++j) {
      double* g = j == 0 ? g1 : g2;
      if (g == nullptr) continue;
      const double* n = j == 0 ? n1 : n2;
      bool changed = false;
      for (int k = 0; k < 6; ++k)
        changed |= l[j][k] != dum[j][k];
      if (!changed) continue;
      for (int c = 0; c < 6; ++c)
        du[c] = n[c] - g[c];
      const int node = j == 0 ? h.node1 : h.node2;
      apply_correction(g, v + 6 * node, a + 6 * node, du, inv_dt, marks.trial,
                       marks.a_scale);  // S 35-37
      if (marks.moved != nullptr) marks.moved[node] = marks.event;
    }
  }
}

// The method's functions, called only through hinge_methods.hpp.
struct NtnPaperMethod {
  // Rigid direction k of a hinge: held by the NTN coupling.
  static bool rigid_direction(const Settings&, std::size_t k, HingeData& h) {
    h.rigid |= static_cast<std::uint8_t>(1U << k);
    return true;
  }

  // Rigid-plastic directions need the constraint force of a direction to test against its
  // yield, which the seed's algorithm does not give: refused.
  static bool slip_direction(const Settings&, std::size_t, HingeData&) { return false; }

  // S 22-26: the mass the accelerations divide by is the hinge-summed one (init() inverts it).
  template <Sizes S>
  static InitStatus init(const ModelSpec<S>&, Model<S>& model, InitWorkspace<S>& work) {
    paper_masses(model.hinges, work.divided_mass);
    return {};
  }

  // R_n - C v (S 2-3) at every DOF into w.r, unscaled: the coupling sums it first.
  template <Sizes S>
  static void residual(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
    detail::residual<S, false>(m, s, w, nullptr, w.r.data());
  }
  // S 17-21, then a_n = R_n / m with the hinge-summed masses (S 22-26, Model::inv_mass).
  template <Sizes S>
  static void couple(const Model<S>& m, const State<S>&, Scratch<S>& w) {
    paper_forces(m.hinges, w.r.data());
    for (std::size_t j = 0; j < m.dofs(); ++j) {
      w.a[j] = w.r[j] * m.inv_mass[j];
    }
  }

  // The stops are S 33, inside the S 27-37 pass (project), in the seed's order.
  template <Sizes S>
  static void stops(const Model<S>&, State<S>&, Scratch<S>&) {}
  // start(): the stops' S 33 on start()'s trial, with its ClampWork weights.
  template <Sizes S>
  static void start_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, false,
                       {nullptr, 0, true, w.clamp.a_scale});
  }
  // S 27-37 (S 33 included), hinge by hinge.
  template <Sizes S>
  static void project(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    paper_after_update(m.hinges, m.fixed, s.u.data(), s.v.data(), w.a.data(), m.inv_dt, true,
                       {w.clamp.moved.data(), ++w.clamp.events});
  }
  template <Sizes S>
  static void project_initial(const Model<S>&, State<S>&) {}

  // The force of rigid direction k on node 1, hinge frame: T (m_1 a_1 - R_1) from node 1's own
  // step mass (Model::mass_factor m_1) and force, which holds every hinge on node 1 together.
  template <Sizes S>
  static double constraint_force(const Model<S>& m, const State<S>& s, Scratch<S>& w, int hinge,
                                 int k, int&) {
    const HingeData& h = m.hinges[static_cast<std::size_t>(hinge)];
    const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
    double own[kDofsPerNode], g[6], l[6];
    detail::node_residual(m, s, w, h.node1, own);
    for (std::size_t c = 0; c < 6; ++c)
      g[c] = (m.mass[i1 + c] * m.mass_factor) * w.a[i1 + c] - own[c];
    detail::to_hinge(h, g + (k < 3 ? 0 : 3), l);
    return l[k % 3];
  }
};

}  // namespace ntn
