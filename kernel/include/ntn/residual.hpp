// The residual R_n - C v_{n-1/2} = P_n - F_n - alpha M v_{n-1/2} (seed S 2-3, DESIGN §5): the one
// pass over every DOF that the hinge methods finish differently (hinge_methods.hpp), and P_n at
// one DOF for the outputs.
#pragma once

#include <algorithm>
#include <cstddef>

#include "ntn/dof_pass.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/state.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp

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

// R_n - C v_{n-1/2} = P_n - F_n - alpha M v_{n-1/2} (S 2-3) into out[j] for the DOFs of nodes
// [first, last), times scale[j] (or not: kScaled false): P_n = m g_d on the fly (C = alpha M
// likewise: the same products as Model::damping). The load slots are residual_slots()'.
template <Sizes S, bool kScaled = true>
void residual_nodes(const Model<S>& m, const State<S>& s, const Scratch<S>& w, const double* scale,
                    double* out, std::size_t first, std::size_t last) {
  const double alpha = m.alpha;
  double g[kDofsPerNode];  // locals: the stores to `out` may alias the model and the scratch
  for (std::size_t d = 0; d < kDofsPerNode; ++d)
    g[d] = w.load_g[d];
  for (std::size_t n = kDofsPerNode * first; n < kDofsPerNode * last; n += kDofsPerNode) {
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
}

// The load slots' DOFs again, with their whole P_n (after residual_nodes() of every node).
template <Sizes S, bool kScaled = true>
void residual_slots(const Model<S>& m, const State<S>& s, const Scratch<S>& w, const double* scale,
                    double* out) {
  const double alpha = m.alpha;
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

// R_n - C v_{n-1/2} into out[j] for every DOF (times scale[j] when kScaled), in one pass.
template <Sizes S, bool kScaled = true>
void residual(const Model<S>& m, const State<S>& s, const Scratch<S>& w, const double* scale,
              double* out) {
  residual_nodes<S, kScaled>(m, s, w, scale, out, 0, m.sizes.nodes);
  residual_slots<S, kScaled>(m, s, w, scale, out);
}

// The lead of the damping velocity that alpha M acts at, v_d = v_{n-1/2} + lead a_n, s: dt/2 with
// damping_velocity = "central" (v_n), 0 with "lagged" or no alpha.
template <Sizes S>
double damping_lead(const Model<S>& m) {
  return m.mass_factor != 1.0 ? 0.5 * m.dt : 0.0;
}

// A model without hinges: the residual, a_n and the update of nodes [first, last) in one pass
// (dof_pass.hpp), the load slots' DOFs (sorted by DOF: make_model) with their whole P_n. Returns
// false when a velocity is non-finite.
template <Sizes S>
bool residual_update(const Model<S>& m, State<S>& s, Scratch<S>& w, std::size_t first,
                     std::size_t last) {
  DofPassData x{m.mass.data(),
                m.inv_mass.data(),
                w.f.data(),
                w.load_g.data(),
                m.alpha,
                m.dt,
                w.a.data(),
                s.v.data(),
                s.u.data(),
                m.mass_table.data(),
                m.mass_entry.data()};
  BookPartials partials;
  if (m.books) {
    x.group_books = w.group_books.data();
    x.partials = &partials;
    x.nodes = m.sizes.nodes;
    x.damp_lead = damping_lead(m);
  }
  double bad = 0;
  int k = 0;  // the first slot at or after node `first`
  while (k < m.num_slots &&
         static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]) < kDofsPerNode * first)
    ++k;
  for (std::size_t n = first; n < last;) {
    std::size_t loaded = last;  // the next node with a slot
    if (k < m.num_slots)
      loaded = std::min(
          last, static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]) / kDofsPerNode);
    if (dof_pass_nodes(m.element_pass, x, n, loaded) != 0.0) bad = 1.0;
    if (loaded == last) break;
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      const std::size_t j = kDofsPerNode * loaded + d;
      double p = m.mass[j] * w.load_g[d];
      if (k < m.num_slots && static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]) == j)
        p = w.p_slot[static_cast<std::size_t>(k++)];
      const double v = m.books ? dof_update_booked(x, j, p) : dof_update(x, j, p);
      bad = v - v == 0.0 ? bad : 1.0;
    }
    if (m.books) end_booked_node(x, loaded);
    n = loaded + 1;
  }
  return bad == 0;
}

// A model with hinges, with Model::books on: the energy books' sums over every DOF after the
// constraint stages (books.hpp), from the v_{n+1/2} and a_n they left (v_{n-1/2} = v_{n+1/2} -
// dt a_n), DOF by DOF and group by group as the DOF pass sums them.
template <Sizes S>
void book_dofs(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  BookPartials b;
  const double dt = m.dt, half_dt = 0.5 * m.dt, lead = damping_lead(m);
  int k = 0;  // the next load slot, by DOF
  for (std::size_t n = 0; n < m.sizes.nodes; ++n) {
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      const std::size_t j = kDofsPerNode * n + d;
      double p = m.mass[j] * w.load_g[d];
      if (k < m.num_slots && static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]) == j)
        p = w.p_slot[static_cast<std::size_t>(k++)];
      const double v = s.v[j], a = w.a[j], mass = m.mass[j];
      const double v0 = v - dt * a;
      const double am = m.alpha * mass;
      book_dof(b, j, half_dt, v0, v, p, w.f[j], lead != 0.0 ? am * (v0 + lead * a) : am * v0, mass);
    }
    if (ends_book_group(n, m.sizes.nodes)) flush_group(b, w.group_books[n / kBookNodes].data());
  }
}

// a_n at DOF j of a model without hinges, as residual_update() will compute it: the outputs read
// it before that pass.
template <Sizes S>
double acceleration_at(const Model<S>& m, const State<S>& s, const Scratch<S>& w, std::size_t j) {
  return acceleration(external_load(m, w, j), w.f[j], m.alpha, m.mass[j], s.v[j], m.inv_mass[j]);
}

// R_n - C v_{n-1/2} at the six DOFs of one node, as the outputs recompute it (with
// Model::damping, the same products as the residual pass).
template <Sizes S>
void node_residual(const Model<S>& m, const State<S>& s, const Scratch<S>& w, int node,
                   NodeBlock r) {
  for (std::size_t c = 0; c < kDofsPerNode; ++c) {
    const auto j = static_cast<std::size_t>(kDofsPerNode * node) + c;
    r[c] = (external_load(m, w, j) - w.f[j]) - m.damping[j] * s.v[j];
  }
}

}  // namespace detail
}  // namespace ntn
