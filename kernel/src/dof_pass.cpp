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

double DofPassNodes(const DofPassData& x, std::size_t first, std::size_t last) {
  using D = hn::CappedTag<double, 8>;  // 24 DOFs: 3 vectors of 8, 6 of 4, 12 of 2 or 24 of 1
  using V = hn::Vec<D>;
  const D d;
  constexpr std::size_t kGroupDofs = kMassGroup * kDofsPerNode;
  const std::size_t lanes = hn::Lanes(d);
  double pattern[kGroupDofs];  // g four times: lanes [k, k + lanes) go with DOFs 6 n + k
  for (std::size_t k = 0; k < kGroupDofs; ++k)
    pattern[k] = x.g[k % kDofsPerNode];
  const V alpha = hn::Set(d, x.alpha), dt = hn::Set(d, x.dt), zero = hn::Zero(d);
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
  for (; n + kMassGroup <= last; n += kMassGroup) {
    const MassBlock& mb = table[entry[n / kMassGroup]];
    for (std::size_t k = 0; k < kGroupDofs; k += lanes) {
      const std::size_t j = kDofsPerNode * n + k;
      const V m = hn::Load(d, mb.mass.data() + k);
      const V v0 = hn::LoadU(d, vel + j);
      const V p = hn::Mul(m, hn::LoadU(d, pattern + k));
      const V a = hn::Mul(hn::Sub(hn::Sub(p, hn::LoadU(d, f + j)), hn::Mul(hn::Mul(alpha, m), v0)),
                          hn::Load(d, mb.inv_mass.data() + k));
      hn::StoreU(a, d, acc + j);
      const V v = hn::Add(v0, hn::Mul(dt, a));
      hn::StoreU(v, d, vel + j);
      hn::StoreU(hn::Add(hn::LoadU(d, dis + j), hn::Mul(dt, v)), d, dis + j);
      bad = hn::IfThenElse(hn::Eq(hn::Sub(v, v), zero), bad, hn::Set(d, 1.0));
    }
  }
  const double tail = dof_pass_nodes_scalar(x, n, last);
  return hn::AllTrue(d, hn::Eq(bad, zero)) && head == 0.0 ? tail : 1.0;
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
