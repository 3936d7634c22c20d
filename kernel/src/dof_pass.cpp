// The DOF pass's SIMD path (dof_pass.hpp): dof_update() and acceleration() in every lane, with
// Highway's portable vectors compiled for each instruction set and the widest the CPU has picked at
// run time. Each line is one line of dof_update in the same order (IEEE products and sums, never
// fused: the build has -ffp-contract=off), so each lane's values are the scalar path's bits. P_n =
// m g_d repeats every 6 DOFs: four nodes (24 DOFs) are a whole number of vectors of 1, 2, 4 or 8
// lanes, with the pattern of g loaded at the same offset for each (8 lanes on AVX-512: one vector
// of DOFs where the element pass takes a block of four elements in 256 bits).

#include "ntn/dof_pass.hpp"

#include <algorithm>

#if defined(NTN_SIMD)

#include "hwy_baseline.hpp"  // before Highway's headers

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "dof_pass.cpp"  // NOLINT: Highway re-includes this file per target
#include <hwy/foreach_target.h>            // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ntn::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// kBooks: the energy books' terms too (books.hpp), as the scalar path's book_dof(): lane l of the
// vector at DOF j into partial (j + l) % 8, held in registers (kAcc vectors per account) from
// the start of the range to its end (x.partials before and after), each book group's sums out
// by the same tree. kLead: the damping velocity v_{n-1/2} + lead a_n (else v_{n-1/2}).
template <bool kBooks, bool kLead>
double Pass(const DofPassData& x, std::size_t first, std::size_t last) {
  using D = hn::CappedTag<double, 8>;  // 24 DOFs: 3 vectors of 8, 6 of 4, 12 of 2 or 24 of 1
  using V = hn::Vec<D>;
  const D d;
  constexpr std::size_t kGroupDofs = kMassGroup * kDofsPerNode;
  constexpr std::size_t kLanes = hn::MaxLanes(D());
  constexpr std::size_t kAcc = kBookLanes / kLanes;  // vectors of partials per account
  static_assert(kBookLanes % kLanes == 0 && kGroupDofs % kBookLanes == 0);
  double pattern[kGroupDofs];  // g four times: lanes [k, k + lanes) go with DOFs 6 n + k
  for (std::size_t k = 0; k < kGroupDofs; ++k)
    pattern[k] = x.g[k % kDofsPerNode];
  const V alpha = hn::Set(d, x.alpha), dt = hn::Set(d, x.dt), zero = hn::Zero(d);
  [[maybe_unused]] const V half_dt = hn::Set(d, 0.5 * x.dt), lead = hn::Set(d, x.damp_lead);
  // Locals: the vector stores may alias anything (Highway's stores are may_alias), so pointers
  // read through x would be reloaded after every store.
  const MassBlock* HWY_RESTRICT table = x.mass_table;
  const std::int32_t* HWY_RESTRICT entry = x.mass_entry;
  const double* HWY_RESTRICT f = x.f;
  double* HWY_RESTRICT acc = x.a;
  double* HWY_RESTRICT vel = x.v;
  double* HWY_RESTRICT dis = x.u;
  V bad = zero;
  // Nodes up to the first whole group by the scalar path, then the groups with their masses from
  // the table, then the rest by the scalar path.
  std::size_t n = std::min(last, (first + kMassGroup - 1) / kMassGroup * kMassGroup);
  const double head = dof_pass_nodes_scalar(x, first, n);
  [[maybe_unused]] V book[kBookAccounts][kAcc];
  if constexpr (kBooks) {
    for (std::size_t q = 0; q < kBookAccounts; ++q)
      for (std::size_t i = 0; i < kAcc; ++i)
        book[q][i] = hn::LoadU(d, x.partials->p[q] + i * kLanes);
  }
  for (; n + kMassGroup <= last; n += kMassGroup) {
    const MassBlock& mb = table[entry[n / kMassGroup]];
    for (std::size_t k = 0; k < kGroupDofs; k += kLanes) {
      const std::size_t j = kDofsPerNode * n + k;
      const V m = hn::Load(d, mb.mass.data() + k);
      const V v0 = hn::LoadU(d, vel + j);
      const V p = hn::Mul(m, hn::LoadU(d, pattern + k));
      const V fj = hn::LoadU(d, f + j);
      const V am = hn::Mul(alpha, m);
      const V a =
          hn::Mul(hn::Sub(hn::Sub(p, fj), hn::Mul(am, v0)), hn::Load(d, mb.inv_mass.data() + k));
      hn::StoreU(a, d, acc + j);
      const V v = hn::Add(v0, hn::Mul(dt, a));
      hn::StoreU(v, d, vel + j);
      hn::StoreU(hn::Add(hn::LoadU(d, dis + j), hn::Mul(dt, v)), d, dis + j);
      bad = hn::IfThenElse(hn::Eq(hn::Sub(v, v), zero), bad, hn::Set(d, 1.0));
      if constexpr (kBooks) {
        const std::size_t i = (k % kBookLanes) / kLanes;
        const V delta = hn::Mul(half_dt, hn::Add(v0, v));
        const V c = kLead ? hn::Mul(am, hn::Add(v0, hn::Mul(lead, a))) : hn::Mul(am, v0);
        book[0][i] = hn::Add(book[0][i], hn::Mul(delta, p));
        book[1][i] = hn::Add(book[1][i], hn::Mul(delta, fj));
        book[2][i] = hn::Add(book[2][i], hn::Mul(delta, c));
        book[3][i] = hn::Add(book[3][i], hn::Mul(hn::Mul(m, v), v));
      }
    }
    if constexpr (kBooks) {
      if (ends_book_group(n + kMassGroup - 1, x.nodes)) {
        BookPartials out;
        for (std::size_t q = 0; q < kBookAccounts; ++q)
          for (std::size_t i = 0; i < kAcc; ++i) {
            hn::StoreU(book[q][i], d, out.p[q] + i * kLanes);
            book[q][i] = zero;
          }
        flush_group(out, x.group_books[n / kBookNodes].data());
      }
    }
  }
  if constexpr (kBooks) {
    for (std::size_t q = 0; q < kBookAccounts; ++q)
      for (std::size_t i = 0; i < kAcc; ++i)
        hn::StoreU(book[q][i], d, x.partials->p[q] + i * kLanes);
  }
  const double tail = dof_pass_nodes_scalar(x, n, last);
  return hn::AllTrue(d, hn::Eq(bad, zero)) && head == 0.0 ? tail : 1.0;
}

double DofPassNodes(const DofPassData& x, std::size_t first, std::size_t last) {
  if (x.group_books == nullptr) return Pass<false, false>(x, first, last);
  return x.damp_lead != 0.0 ? Pass<true, true>(x, first, last) : Pass<true, false>(x, first, last);
}

}  // namespace HWY_NAMESPACE
}  // namespace ntn::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ntn::detail {

HWY_EXPORT(DofPassNodes);

double dof_pass_nodes_simd(const DofPassData& x, std::size_t first, std::size_t last) {
  return HWY_DYNAMIC_DISPATCH(DofPassNodes)(x, first, last);
}

}  // namespace ntn::detail
#endif  // HWY_ONCE

#endif  // NTN_SIMD
