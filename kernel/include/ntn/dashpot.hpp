// Hinge dashpots at the velocity of t_n (damping_velocity = "central"). The spring stage gives a
// dashpot c the force c d_dot_{n-1/2}, from v_{n-1/2}; at t_n the relative velocity is
// d_dot_n = d_dot_{n-1/2} + dt/2 (b . a_n), b the direction's row of B. This stage, after the
// coupling, adds to each dashpot direction the force df = c dt/2 (b . a_n) with the a_n it
// changes: a_n = a - df y, y = M_c^-1 b (the constrained response of the step mass, clamp.hpp's
// parts: the forest over a tree, M_e^-1 at a lone node) and W = b . y, so
//     df = g (b . a),   g = c (dt/2) / (1 + c W dt/2),
// the central form (M_e + c b b^T dt/2) a_n = R - c b d_dot_{n-1/2} solved exactly for one
// dashpot. Dashpots that share a node take their corrections one after another in the order of
// the spring hinges (a Gauss-Seidel sweep): each is then exact given the others', and the force
// differs from c d_dot_n by the others' later corrections, O(dt^2). F_n takes B^T df (so the
// reactions, the coupled directions' forces and the energy books see it) and
// Scratch::dashpot_force keeps df for the hinge-force channels.
#pragma once

#include <cstddef>

#include "ntn/clamp.hpp"
#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/state.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp

// True when direction k of h carries a dashpot force (hinge_spring_force's c d_dot).
inline bool has_dashpot(const HingeData& h, std::size_t k) {
  if (!((h.springs >> k) & 1U) || !(h.dashpot[k] > 0)) return false;
  return ((h.plastic >> k) & 1U) || h.behaviour[k] != HingeBehaviour::kCurve;
}

namespace detail {

// The dashpot stage (above): a_n and F_n with every dashpot at t_n. Lagged models skip it.
template <Sizes S>
void dashpots_at_tn(const Model<S>& m, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.damping_velocity != DampingVelocity::kCentral || m.sizes.hinges == 0) return;
    const double half_dt = 0.5 * m.dt;
    for (int i = 0; i < m.num_spring_hinges; ++i) {
      const auto hi = static_cast<std::size_t>(m.spring_hinges[static_cast<std::size_t>(i)]);
      const HingeData& h = m.hinges[hi];
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!has_dashpot(h, k)) continue;
        ClampPart parts[2];
        clamp_parts(m, h, parts);
        clamp_response(m, w, h, k, parts);                     // y = M_c^-1 b
        const double mobility = clamp_projection(w, h, k);     // W = b . y
        const double rate = response_along(h, k, w.a.data());  // b . a
        const double c = h.dashpot[k] * half_dt;               // c dt/2
        const double df = c * rate / (1.0 + c * mobility);
        w.dashpot_force[hi][k] = df;
        for (const ClampPart& p : parts) {
          for_each_node(m, p, [&](int n) {
            for (std::size_t q = 0; q < kDofsPerNode; ++q) {
              const auto j = static_cast<std::size_t>(kDofsPerNode * n) + q;
              w.a[j] -= df * w.clamp.response[j];
            }
          });
        }
        double f[6] = {};
        f[k] = df;
        const bool ground = h.node2 == kGround;
        hinge_scatter(h, f, &w.f[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                      ground ? nullptr : &w.f[static_cast<std::size_t>(kDofsPerNode * h.node2)]);
      }
    }
  }
}

}  // namespace detail
}  // namespace ntn
