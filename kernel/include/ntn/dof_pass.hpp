// The DOF pass of a model without hinges: the residual, the accelerations and the update (seed
// S 2-7, DESIGN §5) fused into one pass over the DOF arrays, where the hinged step needs three
// (residual, NTN coupling, update). Per DOF j, with P_n = m_j g_d (or the load slot's value):
//   a_n       = ((P_n - F_n) - (alpha m_j) v_{n-1/2}) * (1 / m_j)
//   v_{n+1/2} = v_{n-1/2} + dt a_n
//   u_{n+1}   = u_n + dt v_{n+1/2}
// the same operations in the same order as the unfused stages (residual_nodes(), then update()),
// so their bits. With Model::books on, the pass also sums the step's energy books over its
// DOFs (books.hpp) from the values it has in hand: v_{n-1/2}, a_n, v_{n+1/2}, P_n and F_n. Two
// paths compute it, as the element pass (element_pass.hpp): the scalar reference below, and the
// SIMD path (kernel/src/dof_pass.cpp, Highway, run-time dispatch) with the same operations in every
// lane; Model::element_pass picks both.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "ntn/books.hpp"
#include "ntn/element_pass.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/shared_table.hpp"

namespace ntn {

// The mass table: the masses and inverse masses of kMassGroup consecutive nodes (group k: nodes
// kMassGroup k to kMassGroup k + kMassGroup - 1, 24 DOFs: a whole number of vectors of 1 to 8
// lanes), copies of Model::mass and Model::inv_mass. Groups with the same bytes share one entry
// (share_entry, shared_table.hpp, as the stiffness table's), so that a frame
// whose floors repeat streams 4 bytes per group for its masses instead of 384 and finds them in
// L1. The SIMD DOF pass reads whole groups from here; the scalar path and everything else read
// Model::mass and inv_mass (the same bits).
inline constexpr std::size_t kMassGroup = 4;

struct alignas(64) MassBlock {
  std::array<double, kMassGroup * kDofsPerNode> mass{};
  std::array<double, kMassGroup * kDofsPerNode> inv_mass{};
};

constexpr std::size_t mass_groups(std::size_t nodes) {
  return nodes / kMassGroup;  // whole groups; the last nodes % kMassGroup nodes have none
}
static_assert(kBookNodes % kMassGroup == 0, "a book group is whole mass groups (books.hpp)");

// Fills the table from the DOF arrays of `nodes` nodes: entry[k] is group k's entry, shared with
// an equal one by share_entry() (shared_table.hpp). Returns the number of entries; those past it
// are zeroed.
inline std::size_t fill_mass_table(const double* mass, const double* inv_mass, std::size_t nodes,
                                   MassBlock* table, std::int32_t* entry) {
  std::size_t distinct = 0;
  const std::size_t groups = mass_groups(nodes);
  constexpr std::size_t kDofs = kMassGroup * kDofsPerNode;
  for (std::size_t k = 0; k < groups; ++k) {
    MassBlock blk;
    for (std::size_t c = 0; c < kDofs; ++c) {
      blk.mass[c] = mass[kDofs * k + c];
      blk.inv_mass[c] = inv_mass[kDofs * k + c];
    }
    entry[k] = static_cast<std::int32_t>(share_entry(table, distinct, blk));
  }
  for (std::size_t i = distinct; i < groups; ++i)
    table[i] = MassBlock{};
  return distinct;
}

// The pass's operands: arrays by DOF unless noted.
struct DofPassData {
  const double* mass;              // kg or kg m^2
  const double* inv_mass;          // 1 / mass
  const double* f;                 // F_n
  const double* g;                 // [kDofsPerNode]: P_n / m per direction (Scratch::load_g)
  double alpha;                    // 1/s: C = alpha M
  double dt;                       // s
  double* a;                       // out: a_n
  double* v;                       // in v_{n-1/2}, out v_{n+1/2}
  double* u;                       // in u_n, out u_{n+1}
  const MassBlock* mass_table;     // the same masses by group (fill_mass_table), for the SIMD path
  const std::int32_t* mass_entry;  // [group]: its entry of mass_table
  // The energy books (books.hpp), when not null: each book group's sums, written when the pass
  // finishes the group's last node (of `nodes`); the partials of the group being summed; the
  // damping velocity's lead, v_d = v_{n-1/2} + lead a_n (0: the lagged damping).
  GroupBooks* group_books = nullptr;
  BookPartials* partials = nullptr;
  std::size_t nodes = 0;
  double damp_lead = 0;
};

namespace detail {

// a_n at one DOF: ((P_n - F_n) - (alpha m) v_{n-1/2}) * (1 / m) (S 2-4), the residual stage's
// products (residual_nodes) times inv_mass.
inline double acceleration(double p, double f, double alpha, double mass, double v,
                           double inv_mass) {
  return ((p - f) - (alpha * mass) * v) * inv_mass;
}

// The update (S 5-7): v = v_{n-1/2} + dt a_n into v, then u += dt v; returns v_{n+1/2}.
inline double advance(double dt, double a, double& v, double& u) {
  v = v + dt * a;
  u += dt * v;
  return v;
}

// One DOF with load p; returns v_{n+1/2}.
inline double dof_update(const DofPassData& x, std::size_t j, double p) {
  const double a = acceleration(p, x.f[j], x.alpha, x.mass[j], x.v[j], x.inv_mass[j]);
  x.a[j] = a;
  return advance(x.dt, a, x.v[j], x.u[j]);
}

// The same with the DOF's terms of the energy books into x.partials.
inline double dof_update_booked(const DofPassData& x, std::size_t j, double p) {
  const double v0 = x.v[j], m = x.mass[j];
  const double a = acceleration(p, x.f[j], x.alpha, m, v0, x.inv_mass[j]);
  x.a[j] = a;
  const double v = advance(x.dt, a, x.v[j], x.u[j]);
  const double am = x.alpha * m;
  book_dof(*x.partials, j, 0.5 * x.dt, v0, v, p, x.f[j],
           x.damp_lead != 0.0 ? am * (v0 + x.damp_lead * a) : am * v0, m);
  return v;
}

// True when node n is the last of its book group among `nodes`.
constexpr bool ends_book_group(std::size_t n, std::size_t nodes) {
  return (n + 1) % kBookNodes == 0 || n + 1 == nodes;
}

// After node n with the books on: its group's sums out when n ends the group.
inline void end_booked_node(const DofPassData& x, std::size_t n) {
  if (ends_book_group(n, x.nodes)) flush_group(*x.partials, x.group_books[n / kBookNodes].data());
}

// Nodes [first, last), none with a load slot, by the scalar reference. Returns 1 when a velocity
// is non-finite, else 0 (x - x is 0 for finite x only: no libm).
inline double dof_pass_nodes_scalar(const DofPassData& x, std::size_t first, std::size_t last) {
  double bad = 0;
  if (x.group_books != nullptr) {
    for (std::size_t n = first; n < last; ++n) {
      for (std::size_t d = 0; d < kDofsPerNode; ++d) {
        const std::size_t j = kDofsPerNode * n + d;
        const double v = dof_update_booked(x, j, x.mass[j] * x.g[d]);
        bad = v - v == 0.0 ? bad : 1.0;
      }
      end_booked_node(x, n);
    }
    return bad;
  }
  for (std::size_t n = first; n < last; ++n) {
    for (std::size_t d = 0; d < kDofsPerNode; ++d) {
      const std::size_t j = kDofsPerNode * n + d;
      const double v = dof_update(x, j, x.mass[j] * x.g[d]);
      bad = v - v == 0.0 ? bad : 1.0;
    }
  }
  return bad;
}

#if defined(NTN_SIMD)
// kernel/src/dof_pass.cpp: the same, a vector of DOFs at a time.
double dof_pass_nodes_simd(const DofPassData& x, std::size_t first, std::size_t last);
#endif

}  // namespace detail

// The pass over nodes [first, last), none with a load slot, by the chosen path; 1 when a velocity
// is non-finite, else 0.
inline double dof_pass_nodes(ElementPass path, const DofPassData& x, std::size_t first,
                             std::size_t last) {
#if defined(NTN_SIMD)
  if (path == ElementPass::kSimd) return detail::dof_pass_nodes_simd(x, first, last);
#else
  (void)path;
#endif
  return detail::dof_pass_nodes_scalar(x, first, last);
}

}  // namespace ntn
