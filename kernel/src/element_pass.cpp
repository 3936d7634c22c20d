// The SIMD element pass (element_pass.hpp): beam_force() (beam.hpp) in every lane of a block, with
// Highway's portable vectors compiled for each instruction set it knows and the widest the CPU has
// picked at run time (dynamic dispatch). Every line below is one line of beam_force in the same
// order: IEEE products, sums and negations lane by lane (the build has -ffp-contract=off, and
// Highway's Mul/Add/Sub/Neg are never fused), and the picks and sign flips of an aligned element
// (beam.hpp, AxisMap) where beam_force picks, so each lane's forces are the scalar path's bits.
// The end forces are then added to the nodes lane by lane, in the model's element order. The
// second-order chord forces (geometry.hpp) are computed the same way: geometric_force and
// beam_to_global in the lanes of a GeometricBlock, then added element by element.

#include "ntn/element_pass.hpp"
#include "ntn/geometry.hpp"

#if !defined(NTN_SIMD)

namespace ntn {
const char* element_pass_target() {
  return "scalar";
}
}  // namespace ntn

#else

#include <algorithm>

#include "hwy_baseline.hpp"  // before Highway's headers

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "element_pass.cpp"  // NOLINT: Highway re-includes this file per target
#include <hwy/foreach_target.h>                // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace ntn::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// At most one block per vector: on AVX-512 the block's 4 lanes take a 256-bit vector, on 128-bit
// sets (SSE4, NEON) a block is two vectors.
using D = hn::CappedTag<double, kBeamLanes>;
using V = hn::Vec<D>;

// rotate_to_local: l = R g, rows of R.
HWY_INLINE void to_local(const V* R, const V* g, V* l) {
  l[0] = hn::Add(hn::Add(hn::Mul(R[0], g[0]), hn::Mul(R[1], g[1])), hn::Mul(R[2], g[2]));
  l[1] = hn::Add(hn::Add(hn::Mul(R[3], g[0]), hn::Mul(R[4], g[1])), hn::Mul(R[5], g[2]));
  l[2] = hn::Add(hn::Add(hn::Mul(R[6], g[0]), hn::Mul(R[7], g[1])), hn::Mul(R[8], g[2]));
}

// rotate_to_global: g = R^T l.
HWY_INLINE void to_global(const V* R, const V* l, V* g) {
  g[0] = hn::Add(hn::Add(hn::Mul(R[0], l[0]), hn::Mul(R[3], l[1])), hn::Mul(R[6], l[2]));
  g[1] = hn::Add(hn::Add(hn::Mul(R[1], l[0]), hn::Mul(R[4], l[1])), hn::Mul(R[7], l[2]));
  g[2] = hn::Add(hn::Add(hn::Mul(R[2], l[0]), hn::Mul(R[5], l[1])), hn::Mul(R[8], l[2]));
}

// How a block's lanes rotate (beam.hpp, AxisMap): all by the full products, all by one and the
// same right-handed pick (the common case: members meshed in place, numbered member by member), or
// lane by lane (lanes that rotate differently, and the left-handed picks that beam_geometry never
// makes: a hand-made BeamData's).
enum class Axes : std::uint8_t { kGeneral, kUniform, kMixed };

using BlockAxes = std::array<AxisMap, kBeamLanes>;

HWY_INLINE Axes block_axes(const BlockAxes& axes) {
  const AxisMap m = axes[0];
  for (std::size_t l = 1; l < kBeamLanes; ++l) {
    if (axes[l] != m) return Axes::kMixed;
  }
  if (m == kGeneralAxes) return Axes::kGeneral;
  return right_handed(m) ? Axes::kUniform : Axes::kMixed;
}

// A uniform block's picks: local axis k is global axis kA<k> (one of the six orders of x, y, z),
// negated where bit k of kNeg is set (flip() of beam.hpp: the sign bit alone, exact). Both are
// template arguments, so that the picks are register names and an axis that is not negated costs
// no instruction (a building frame's members have one negated axis or none). (Vectors are passed
// as arrays, not in structs: a struct's implicit constructor lacks Highway's target attributes.)
template <bool kNegated>
HWY_INLINE V flip(V x) {
  if constexpr (kNegated) {
    return hn::Neg(x);
  } else {
    return x;
  }
}

template <std::size_t kA0, std::size_t kA1, unsigned kNeg>
HWY_INLINE void pick_local(const V* g, V* l) {
  constexpr std::size_t kA2 = 3 - kA0 - kA1;
  l[0] = flip<(kNeg & 1U) != 0>(g[kA0]);
  l[1] = flip<(kNeg & 2U) != 0>(g[kA1]);
  l[2] = flip<(kNeg & 4U) != 0>(g[kA2]);
}

template <std::size_t kA0, std::size_t kA1, unsigned kNeg>
HWY_INLINE void pick_global(const V* l, V* g) {
  constexpr std::size_t kA2 = 3 - kA0 - kA1;
  g[kA0] = flip<(kNeg & 1U) != 0>(l[0]);
  g[kA1] = flip<(kNeg & 2U) != 0>(l[1]);
  g[kA2] = flip<(kNeg & 4U) != 0>(l[2]);
}

// A block whose lanes rotate differently: each lane's AxisMap as vectors over lanes
// [first, first + Lanes): aligned 1.0 in the lanes with an AxisMap (the others take the full
// products), axis[k] the global axis of local axis k (0.0, 1.0 or 2.0), sign[k] -0.0 where local
// axis k is negated, else +0.0.
HWY_INLINE void lane_axes(const BlockAxes& axes, std::size_t first, V& aligned, V* axis, V* sign) {
  const D d;
  alignas(64) double al[kBeamLanes], ax[3][kBeamLanes], sg[3][kBeamLanes];
  for (std::size_t l = 0; l < kBeamLanes; ++l) {
    const AxisMap m = axes[l];
    al[l] = m == kGeneralAxes ? 0.0 : 1.0;
    for (std::size_t k = 0; k < 3; ++k) {
      ax[k][l] = static_cast<double>(axis_of(m, k));
      sg[k][l] = axis_negated(m, k) ? -0.0 : 0.0;
    }
  }
  aligned = hn::LoadU(d, al + first);
  for (std::size_t k = 0; k < 3; ++k) {
    axis[k] = hn::LoadU(d, ax[k] + first);
    sign[k] = hn::LoadU(d, sg[k] + first);
  }
}

// In the aligned lanes of a mixed block, l (the full products) replaced by the picks of g.
HWY_INLINE void repick_local(V aligned, const V* axis, const V* sign, const V* g, V* l) {
  const D d;
  for (std::size_t k = 0; k < 3; ++k) {
    const V pick = hn::IfThenElse(hn::Eq(axis[k], hn::Zero(d)), g[0],
                                  hn::IfThenElse(hn::Eq(axis[k], hn::Set(d, 1.0)), g[1], g[2]));
    l[k] = hn::IfThenElse(hn::Ne(aligned, hn::Zero(d)), hn::Xor(pick, sign[k]), l[k]);
  }
}

// ... and g (the full products) replaced by the picks of l.
HWY_INLINE void repick_global(V aligned, const V* axis, const V* sign, const V* l, V* g) {
  const D d;
  for (std::size_t c = 0; c < 3; ++c) {
    const V at = hn::Set(d, static_cast<double>(c));
    const V pick = hn::IfThenElse(
        hn::Eq(axis[0], at), hn::Xor(l[0], sign[0]),
        hn::IfThenElse(hn::Eq(axis[1], at), hn::Xor(l[1], sign[1]), hn::Xor(l[2], sign[2])));
    g[c] = hn::IfThenElse(hn::Ne(aligned, hn::Zero(d)), pick, g[c]);
  }
}

// beam_force from the global displacements ug [u_i, theta_i, u_j, theta_j] (one vector per DOF,
// lanes [first, first + Lanes) of the block) to the global end forces g, in the same order.
template <Axes kAxes, std::size_t kA0 = 0, std::size_t kA1 = 1, unsigned kNeg = 0>
HWY_INLINE void lane_forces(const BeamBlock& blk, const BeamRotations& rot,
                            const BeamStiffnessBlock& st, std::size_t first, const V* ug, V* g) {
  const D d;
  [[maybe_unused]] V R[9];     // the rotation, for the full products
  [[maybe_unused]] V aligned;  // a mixed block's lanes (lane_axes)
  [[maybe_unused]] V axis[3];  // ...
  [[maybe_unused]] V sign[3];  // ... and the sign bits of its picks
  V dl[12];                    // beam_local_displacements
  if constexpr (kAxes == Axes::kUniform) {
    for (std::size_t e = 0; e < 12; e += 3)
      pick_local<kA0, kA1, kNeg>(ug + e, dl + e);
  } else {
    for (std::size_t k = 0; k < 9; ++k)
      R[k] = hn::LoadU(d, rot.rotation[k].data() + first);
    for (std::size_t e = 0; e < 12; e += 3)
      to_local(R, ug + e, dl + e);
    if constexpr (kAxes == Axes::kMixed) {
      lane_axes(blk.axes, first, aligned, axis, sign);
      for (std::size_t e = 0; e < 12; e += 3)
        repick_local(aligned, axis, sign, ug + e, dl + e);
    }
  }

  // beam_local_force
  V f[12];
  const V n = hn::Mul(hn::LoadU(d, st.axial.data() + first), hn::Sub(dl[6], dl[0]));
  const V t = hn::Mul(hn::LoadU(d, st.torsion.data() + first), hn::Sub(dl[9], dl[3]));
  f[0] = hn::Neg(n), f[6] = n, f[3] = hn::Neg(t), f[9] = t;
  const V p0 = hn::LoadU(d, st.xy[0].data() + first), p1 = hn::LoadU(d, st.xy[1].data() + first);
  const V p2 = hn::LoadU(d, st.xy[2].data() + first), p3 = hn::LoadU(d, st.xy[3].data() + first);
  const V dv = hn::Sub(dl[1], dl[7]);
  f[1] = hn::Add(hn::Mul(p0, dv), hn::Mul(p1, hn::Add(dl[5], dl[11])));
  f[7] = hn::Neg(f[1]);
  f[5] = hn::Add(hn::Add(hn::Mul(p1, dv), hn::Mul(p2, dl[5])), hn::Mul(p3, dl[11]));
  f[11] = hn::Add(hn::Add(hn::Mul(p1, dv), hn::Mul(p3, dl[5])), hn::Mul(p2, dl[11]));
  const V q0 = hn::LoadU(d, st.xz[0].data() + first), q1 = hn::LoadU(d, st.xz[1].data() + first);
  const V q2 = hn::LoadU(d, st.xz[2].data() + first), q3 = hn::LoadU(d, st.xz[3].data() + first);
  const V dw = hn::Sub(dl[2], dl[8]);
  f[2] = hn::Sub(hn::Mul(q0, dw), hn::Mul(q1, hn::Add(dl[4], dl[10])));
  f[8] = hn::Neg(f[2]);
  // -q1 * dw: the scalar code negates q1, then multiplies
  const V mq1 = hn::Neg(q1);
  f[4] = hn::Add(hn::Add(hn::Mul(mq1, dw), hn::Mul(q2, dl[4])), hn::Mul(q3, dl[10]));
  f[10] = hn::Add(hn::Add(hn::Mul(mq1, dw), hn::Mul(q3, dl[4])), hn::Mul(q2, dl[10]));

  // beam_to_global, end by end
  if constexpr (kAxes == Axes::kUniform) {
    for (std::size_t e = 0; e < 12; e += 3)
      pick_global<kA0, kA1, kNeg>(f + e, g + e);
  } else {
    for (std::size_t e = 0; e < 12; e += 3)
      to_global(R, f + e, g + e);
    if constexpr (kAxes == Axes::kMixed) {
      for (std::size_t e = 0; e < 12; e += 3)
        repick_global(aligned, axis, sign, f + e, g + e);
    }
  }
}

// The negated axes of the right-handed pick with local x, y along global kA0, kA1 and the signs
// kLow of x and y: z's sign follows (beam.hpp, right_handed).
template <std::size_t kA0, std::size_t kA1, unsigned kLow>
constexpr unsigned right_handed_signs() {
  return right_handed(aligned_axes(kA0, kA1, kLow)) ? kLow : kLow | 4U;
}

// fn.template operator()<Axes::kUniform, kA0, kA1, kNeg>() for a uniform block of map m with the
// permutation kA0, kA1: the four right-handed choices of its negated axes (block_axes), each a case
// of its own. (A switch on the x and y signs alone, with z's implied, measured as slow as the
// runtime signs on Zen 5.)
template <std::size_t kA0, std::size_t kA1, class Fn>
HWY_INLINE void with_uniform_axes(AxisMap m, Fn&& fn) {
  constexpr unsigned kNeg[4] = {
      right_handed_signs<kA0, kA1, 0>(), right_handed_signs<kA0, kA1, 1>(),
      right_handed_signs<kA0, kA1, 2>(), right_handed_signs<kA0, kA1, 3>()};
  switch (negated_axes(m)) {
    case kNeg[0]:
      fn.template operator()<Axes::kUniform, kA0, kA1, kNeg[0]>();
      return;
    case kNeg[1]:
      fn.template operator()<Axes::kUniform, kA0, kA1, kNeg[1]>();
      return;
    case kNeg[2]:
      fn.template operator()<Axes::kUniform, kA0, kA1, kNeg[2]>();
      return;
    case kNeg[3]:
      fn.template operator()<Axes::kUniform, kA0, kA1, kNeg[3]>();
      return;
    default:  // left-handed: block_axes sends these to the mixed path
      return;
  }
}

// fn.template operator()<kAxes, kA0, kA1, kNeg>() for the block's kind of axes (block_axes) and, in
// a uniform block, its pick as template arguments (lane_forces, chord_forces).
template <class Fn>
HWY_INLINE void with_axes(const BlockAxes& axes, Fn&& fn) {
  switch (block_axes(axes)) {
    case Axes::kUniform:
      switch (3 * axis_of(axes[0], 0) + axis_of(axes[0], 1)) {
        case 1:
          with_uniform_axes<0, 1>(axes[0], fn);
          return;
        case 2:
          with_uniform_axes<0, 2>(axes[0], fn);
          return;
        case 3:
          with_uniform_axes<1, 0>(axes[0], fn);
          return;
        case 5:
          with_uniform_axes<1, 2>(axes[0], fn);
          return;
        case 6:
          with_uniform_axes<2, 0>(axes[0], fn);
          return;
        default:  // 7: axis_map() codes a permutation of x, y, z, so nothing else
          with_uniform_axes<2, 1>(axes[0], fn);
          return;
      }
    case Axes::kGeneral:
      fn.template operator()<Axes::kGeneral, 0, 1, 0>();
      return;
    case Axes::kMixed:
      fn.template operator()<Axes::kMixed, 0, 1, 0>();
      return;
  }
}

// lane_forces for the block's kind of axes.
HWY_INLINE void lane_forces(const BeamBlock& blk, const BeamRotations& rot,
                            const BeamStiffnessBlock& st, std::size_t first, const V* ug, V* g) {
  with_axes(
      blk.axes, [&]<Axes kAxes, std::size_t kA0, std::size_t kA1, unsigned kNeg>()
                    __attribute__((always_inline)) {
                      lane_forces<kAxes, kA0, kA1, kNeg>(blk, rot, st, first, ug, g);
                    });
}

// Any vector width: the displacements gathered DOF by DOF, the end forces stored lane by lane
// into fi, fj [DOF][lane].
HWY_INLINE void block_gather(const BeamArrays& a, std::size_t blk_index, const double* u,
                             const double* v, double beta, double (*fi)[kBeamLanes],
                             double (*fj)[kBeamLanes]) {
  const D d;
  const BeamBlock& blk = a.blocks[blk_index];
  const hn::Rebind<std::int32_t, D> d32;
  const hn::Rebind<std::int64_t, D> d64;
  for (std::size_t first = 0; first < kBeamLanes; first += hn::Lanes(d)) {
    const auto ii = hn::PromoteTo(d64, hn::LoadU(d32, blk.dof_i.data() + first));
    const auto jj = hn::PromoteTo(d64, hn::LoadU(d32, blk.dof_j.data() + first));
    V ug[12];
    for (int c = 0; c < 6; ++c) {
      ug[c] = hn::GatherIndex(d, u + c, ii);
      ug[6 + c] = hn::GatherIndex(d, u + c, jj);
    }
    if (beta != 0.0) {
      const V b = hn::Set(d, beta);
      for (int c = 0; c < 6; ++c) {
        ug[c] = hn::Add(ug[c], hn::Mul(b, hn::GatherIndex(d, v + c, ii)));
        ug[6 + c] = hn::Add(ug[6 + c], hn::Mul(b, hn::GatherIndex(d, v + c, jj)));
      }
    }
    V g[12];
    lane_forces(blk, a.rotations[blk_index], a.stiffness[blk.stiffness], first, ug, g);
    for (std::size_t c = 0; c < 6; ++c) {
      hn::StoreU(g[c], d, fi[c] + first);
      hn::StoreU(g[6 + c], d, fj[c] + first);
    }
  }
}

// The first `lanes` lanes' end forces fi, fj [DOF][lane] added to the nodes, element by element
// (kFirst: a node's first end written as 0.0 + its force, BeamBlock::first).
template <bool kFirst = false>
HWY_INLINE void add_lanes(const BeamBlock& blk, std::size_t lanes, const double (*fi)[kBeamLanes],
                          const double (*fj)[kBeamLanes], double* f) {
  for (std::size_t l = 0; l < lanes; ++l) {  // element order, as the scalar pass
    const auto i = static_cast<std::size_t>(blk.dof_i[l]);
    const auto j = static_cast<std::size_t>(blk.dof_j[l]);
    const bool first_i = kFirst && direct_end(blk.first, l, 0);
    const bool first_j = kFirst && direct_end(blk.first, l, 1);
    for (std::size_t c = 0; c < 6; ++c)
      f[i + c] = onto(first_i, f[i + c], fi[c][l]);
    for (std::size_t c = 0; c < 6; ++c)
      f[j + c] = onto(first_j, f[j + c], fj[c][l]);
  }
}

// ... or, for the multi-core pass, each end added to f where `direct` has its bit (written as
// 0.0 + its force where it is its node's first, BeamBlock::first), else stored into
// fe[12 l + 6 end + c] (element by element).
HWY_INLINE void split_lanes(const BeamBlock& blk, std::uint8_t direct,
                            const double (*fi)[kBeamLanes], const double (*fj)[kBeamLanes],
                            double* f, double* fe) {
  for (std::size_t l = 0; l < kBeamLanes; ++l) {
    const double(*ends[2])[kBeamLanes] = {fi, fj};
    const std::int32_t node_dof[2] = {blk.dof_i[l], blk.dof_j[l]};
    for (std::size_t end = 0; end < 2; ++end) {
      const bool first = direct_end(blk.first, l, end);
      for (std::size_t c = 0; c < 6; ++c) {
        if (direct_end(direct, l, end)) {
          double& x = f[static_cast<std::size_t>(node_dof[end]) + c];
          x = onto(first, x, ends[end][c][l]);
        } else {
          fe[12 * l + 6 * end + c] = ends[end][c][l];
        }
      }
    }
  }
}

#if HWY_TARGET != HWY_SCALAR
// 4 x 4 transpose: r[l] holds 4 values of lane l, c[k] value k of every lane (and back).
HWY_INLINE void transpose4(const V* r, V* c) {
  const D d;
  const V t0 = hn::InterleaveLower(d, r[0], r[1]);  // r0[0] r1[0] r0[2] r1[2]
  const V t1 = hn::InterleaveUpper(d, r[0], r[1]);  // r0[1] r1[1] r0[3] r1[3]
  const V t2 = hn::InterleaveLower(d, r[2], r[3]);
  const V t3 = hn::InterleaveUpper(d, r[2], r[3]);
  c[0] = hn::ConcatLowerLower(d, t2, t0);
  c[1] = hn::ConcatLowerLower(d, t3, t1);
  c[2] = hn::ConcatUpperUpper(d, t2, t0);
  c[3] = hn::ConcatUpperUpper(d, t3, t1);
}

// One node end's 6 DOFs of the 4 lanes, DOF by DOF: x[dof[l] + c] into out[c], lane l.
HWY_INLINE void load_end(const double* x, const std::int32_t* dof, V* out) {
  const D d;
  const hn::Half<D> dh;
  V r[4];
  for (std::size_t l = 0; l < 4; ++l)
    r[l] = hn::LoadU(d, x + dof[l]);  // DOFs 0..3
  transpose4(r, out);
  // DOFs 4, 5: lanes 0 and 2 in one vector, 1 and 3 in another, then interleaved
  const V a = hn::Combine(d, hn::LoadU(dh, x + dof[2] + 4), hn::LoadU(dh, x + dof[0] + 4));
  const V b = hn::Combine(d, hn::LoadU(dh, x + dof[3] + 4), hn::LoadU(dh, x + dof[1] + 4));
  out[4] = hn::InterleaveLower(d, a, b);
  out[5] = hn::InterleaveUpper(d, a, b);
}

// Vectors of 4 (AVX2, AVX-512): the displacements loaded node by node and transposed into lanes,
// then the end forces g [DOF] of the 4 lanes.
template <bool kBeta>
HWY_INLINE void block_transpose(const BeamArrays& a, std::size_t b, const double* u,
                                const double* v, double beta, V* g) {
  const D d;
  const BeamBlock& blk = a.blocks[b];
  V ug[12];
  load_end(u, blk.dof_i.data(), ug);
  load_end(u, blk.dof_j.data(), ug + 6);
  if constexpr (kBeta) {
    const V b = hn::Set(d, beta);
    V vg[12];
    load_end(v, blk.dof_i.data(), vg);
    load_end(v, blk.dof_j.data(), vg + 6);
    for (std::size_t c = 0; c < 12; ++c)
      ug[c] = hn::Add(ug[c], hn::Mul(b, vg[c]));
  }
  lane_forces(blk, a.rotations[b], a.stiffness[blk.stiffness], 0, ug, g);
}

// The end forces g [DOF] of one node end transposed back, lane by lane: DOFs 0..3 in r[l], DOFs
// 4, 5 in h[l].
HWY_INLINE void rows(const V* g, V* r, hn::Vec<hn::Half<D> >* h) {
  const D d;
  const hn::Half<D> dh;
  transpose4(g, r);
  const V a = hn::InterleaveLower(d, g[4], g[5]), b = hn::InterleaveUpper(d, g[4], g[5]);
  h[0] = hn::LowerHalf(dh, a), h[1] = hn::LowerHalf(dh, b);
  h[2] = hn::UpperHalf(dh, a), h[3] = hn::UpperHalf(dh, b);
}

// A block's end forces g [DOF] transposed back and handed to out(l, ri, hi, rj, hj), lane by lane
// in the model's element order: node i's DOFs 0..3 in ri and 4, 5 in hi, node j's in rj, hj.
template <class Out>
HWY_INLINE void each_lane(const V* g, Out out) {
  V ri[4], rj[4];
  hn::Vec<hn::Half<D> > hi[4], hj[4];
  rows(g, ri, hi);
  rows(g + 6, rj, hj);
  for (std::size_t l = 0; l < 4; ++l)
    out(l, ri[l], hi[l], rj[l], hj[l]);
}

// One node end's forces onto F at p, DOFs 0..3 from r and 4, 5 from h: added, or written as
// 0.0 + the forces where the end is its node's first (`first`: BeamBlock::first), without reading
// F (onto(), element_pass.hpp).
template <class H>
HWY_INLINE void add_end(bool first, double* p, V r, H h) {
  const D d;
  const hn::Half<D> dh;
  if (first) {
    hn::StoreU(hn::Add(hn::Zero(d), r), d, p);
    hn::StoreU(hn::Add(hn::Zero(dh), h), dh, p + 4);
  } else {
    hn::StoreU(hn::Add(hn::LoadU(d, p), r), d, p);
    hn::StoreU(hn::Add(hn::LoadU(dh, p + 4), h), dh, p + 4);
  }
}

// A whole block's end forces added to the nodes 4 and 2 DOFs at a time. Lane l's two ends are
// added before lane l + 1's, so every DOF sums its elements in the model's order. kFirst: a
// node's first end (BeamBlock::first) is written as 0.0 + its force, without reading F.
template <bool kFirst = false>
HWY_INLINE void add_rows(const BeamBlock& blk, const V* g, double* f) {
  each_lane(g, [&](std::size_t l, V ri, auto hi, V rj, auto hj) {
    add_end(kFirst && direct_end(blk.first, l, 0), f + blk.dof_i[l], ri, hi);
    add_end(kFirst && direct_end(blk.first, l, 1), f + blk.dof_j[l], rj, hj);
  });
}

// ... or, for the multi-core pass, each end added to f where `direct` has its bit (a node's first
// end written as 0.0 + its force), else stored into fe[12 l + 6 end + c].
HWY_INLINE void split_rows(const BeamBlock& blk, std::uint8_t direct, const V* g, double* f,
                           double* fe) {
  const D d;
  const hn::Half<D> dh;
  each_lane(g, [&](std::size_t l, V ri, auto hi, V rj, auto hj) {
    const V r[2] = {ri, rj};
    const decltype(hi) h[2] = {hi, hj};
    const std::int32_t node_dof[2] = {blk.dof_i[l], blk.dof_j[l]};
    for (std::size_t end = 0; end < 2; ++end) {
      if (direct_end(direct, l, end)) {
        add_end(direct_end(blk.first, l, end), f + node_dof[end], r[end], h[end]);
      } else {
        hn::StoreU(r[end], d, fe + 12 * l + 6 * end);
        hn::StoreU(h[end], dh, fe + 12 * l + 6 * end + 4);
      }
    }
  });
}

template <bool kBeta, bool kFirst>
HWY_INLINE void forces_transpose(const BeamArrays& a, std::size_t elements, const double* u,
                                 const double* v, double beta, double* f) {
  const D d;
  const std::size_t full = elements / kBeamLanes;
  for (std::size_t b = 0; b < full; ++b) {
    V g[12];
    block_transpose<kBeta>(a, b, u, v, beta, g);
    add_rows<kFirst>(a.blocks[b], g, f);
  }
  if (const std::size_t lanes = elements - full * kBeamLanes; lanes > 0) {
    V g[12];
    block_transpose<kBeta>(a, full, u, v, beta, g);
    alignas(64) double fi[6][kBeamLanes];
    alignas(64) double fj[6][kBeamLanes];
    for (std::size_t c = 0; c < 6; ++c) {
      hn::Store(g[c], d, fi[c]);
      hn::Store(g[6 + c], d, fj[c]);
    }
    add_lanes<kFirst>(a.blocks[full], lanes, fi, fj, f);
  }
}

// Whole blocks whose ends all go to f (the common case) take add_rows with the first writes, as
// the single-core pass.
template <bool kBeta>
HWY_INLINE void split_transpose(const BeamArrays& a, std::size_t first, std::size_t last,
                                const std::uint8_t* direct, const double* u, const double* v,
                                double beta, double* f, double* fe) {
  constexpr std::uint8_t kAll = (1U << (2 * kBeamLanes)) - 1U;
  for (std::size_t b = first; b < last; ++b) {
    V g[12];
    block_transpose<kBeta>(a, b, u, v, beta, g);
    if (direct[b] == kAll) {
      add_rows<true>(a.blocks[b], g, f);
    } else {
      split_rows(a.blocks[b], direct[b], g, f, fe + 12 * kBeamLanes * b);
    }
  }
}

// geometric_force (geometry.hpp) of a block's 4 lanes from their chord's relative translation
// rel = u_j - u_i (one vector per global axis): g on node j, in global axes (beam_to_global), and
// the lanes whose Q is above their limit (`over`).
template <Axes kAxes, std::size_t kA0 = 0, std::size_t kA1 = 1, unsigned kNeg = 0>
HWY_INLINE hn::Mask<D> chord_forces(const GeometricBlock& blk, const BeamRotations& rot,
                                    const V* rel, V* g) {
  const D d;
  [[maybe_unused]] V R[9];     // the rotation, for the full products
  [[maybe_unused]] V aligned;  // a mixed block's lanes (lane_axes)
  [[maybe_unused]] V axis[3];  // ...
  [[maybe_unused]] V sign[3];  // ... and the sign bits of its picks
  V dl[3];                     // beam_to_local
  if constexpr (kAxes == Axes::kUniform) {
    pick_local<kA0, kA1, kNeg>(rel, dl);
  } else {
    for (std::size_t k = 0; k < 9; ++k)
      R[k] = hn::Load(d, rot.rotation[k].data());
    to_local(R, rel, dl);
    if constexpr (kAxes == Axes::kMixed) {
      lane_axes(blk.axes, 0, aligned, axis, sign);
      repick_local(aligned, axis, sign, rel, dl);
    }
  }
  const V axial = hn::Load(d, blk.axial.data());
  const V inv_length = hn::Load(d, blk.inv_length.data());
  const V s = hn::Add(hn::Mul(dl[1], dl[1]), hn::Mul(dl[2], dl[2]));
  const V stretch = hn::Mul(axial, hn::Mul(hn::Mul(hn::Set(d, 0.5), s), inv_length));
  const V normal = hn::Add(hn::Mul(axial, dl[0]), stretch);
  const V string = hn::Mul(normal, inv_length);
  const V gl[3] = {stretch, hn::Mul(string, dl[1]), hn::Mul(string, dl[2])};
  const V tension = hn::IfThenElseZero(hn::Gt(normal, hn::Zero(d)), normal);  // N+
  const V y =
      hn::Sub(hn::Sub(hn::Load(d, blk.limit.data()), tension), hn::Mul(hn::Set(d, 2.0), stretch));
  const auto within =
      hn::And(hn::Ge(y, hn::Zero(d)), hn::Le(hn::Mul(hn::Mul(axial, axial), s), hn::Mul(y, y)));
  if constexpr (kAxes == Axes::kUniform) {
    pick_global<kA0, kA1, kNeg>(gl, g);
  } else {
    to_global(R, gl, g);
    if constexpr (kAxes == Axes::kMixed) repick_global(aligned, axis, sign, gl, g);
  }
  return hn::Not(within);
}

// Block b's chord forces (chord_forces, its kind of axes kAxes...) into its elements' rows of
// `rows`, (g_x, g_y, g_z, 0.0). The loads and stores of u, F and the rows here and in
// chords_transpose take 2 DOFs (x, y or z, rx) or 1, not 4: F takes the translations' sums alone,
// and none crosses a cache line (4 DOFs from a node's first, 48 bytes a node, would at every other
// node). Returns how many of its elements (of `count` in all) are past their limit.
template <Axes kAxes, std::size_t kA0, std::size_t kA1, unsigned kNeg>
HWY_INLINE std::size_t chord_rows(const GeometricArrays& a, std::size_t b, std::size_t count,
                                  const double* u, double* rows) {
  const D d;
  const hn::Half<D> dh;
  const GeometricBlock& blk = a.blocks[b];
  const std::size_t lanes = std::min(kBeamLanes, count - b * kBeamLanes);
  hn::Vec<hn::Half<D> > xy[4], z[4];  // u_j - u_i lane by lane: (x, y) and (z, rx)
  for (std::size_t l = 0; l < 4; ++l) {
    const double* ui = u + blk.dof_i[l];
    const double* uj = u + blk.dof_j[l];
    xy[l] = hn::Sub(hn::LoadU(dh, uj), hn::LoadU(dh, ui));
    z[l] = hn::Sub(hn::LoadU(dh, uj + 2), hn::LoadU(dh, ui + 2));
  }
  // lanes 0 and 2 in one vector, 1 and 3 in another, then interleaved (as load_end)
  const V xy02 = hn::Combine(d, xy[2], xy[0]), xy13 = hn::Combine(d, xy[3], xy[1]);
  const V z02 = hn::Combine(d, z[2], z[0]), z13 = hn::Combine(d, z[3], z[1]);
  const V rel[3] = {hn::InterleaveLower(d, xy02, xy13), hn::InterleaveUpper(d, xy02, xy13),
                    hn::InterleaveLower(d, z02, z13)};
  V g[3];
  const auto past = chord_forces<kAxes, kA0, kA1, kNeg>(blk, a.rotations[b], rel, g);
  // back lane by lane: (g_x, g_y) of lanes 0, 2 in `gxy02`'s halves, 1, 3 in gxy13's; (g_z, 0.0)
  const V gxy02 = hn::InterleaveLower(d, g[0], g[1]), gxy13 = hn::InterleaveUpper(d, g[0], g[1]);
  const V gz02 = hn::InterleaveLower(d, g[2], hn::Zero(d));
  const V gz13 = hn::InterleaveUpper(d, g[2], hn::Zero(d));
  const hn::Vec<hn::Half<D> > out_xy[4] = {hn::LowerHalf(dh, gxy02), hn::LowerHalf(dh, gxy13),
                                           hn::UpperHalf(dh, gxy02), hn::UpperHalf(dh, gxy13)};
  const hn::Vec<hn::Half<D> > out_z[4] = {hn::LowerHalf(dh, gz02), hn::LowerHalf(dh, gz13),
                                          hn::UpperHalf(dh, gz02), hn::UpperHalf(dh, gz13)};
  for (std::size_t l = 0; l < lanes; ++l) {
    double* row = rows + 4 * static_cast<std::size_t>(blk.slot[l]);
    hn::StoreU(out_xy[l], dh, row);
    hn::StoreU(out_z[l], dh, row + 2);
  }
  return hn::CountTrue(d, hn::And(past, hn::FirstN(d, lanes)));
}

// geometric_forces over the blocks: each element's g into its row (chord_rows), the blocks taken
// in runs of the same axes (the model's order makes them long), each run by the code of its kind;
// then f += g on node j and -g on node i element by element in element order, as
// geometric_forces adds them. Returns how many elements are past their limit.
HWY_INLINE std::size_t chords_transpose(const GeometricArrays& a, const GeometricElement* elements,
                                        std::size_t count, const double* u, double* f,
                                        double* rows) {
  const hn::Half<D> dh;
  const std::size_t num_blocks = beam_blocks(count);
  std::size_t over = 0;
  for (std::size_t b = 0; b < num_blocks;) {
    const BlockAxes& axes = a.blocks[b].axes;
    std::size_t end = b + 1;
    while (end < num_blocks && a.blocks[end].axes == axes)
      ++end;
    with_axes(
        axes, [&]<Axes kAxes, std::size_t kA0, std::size_t kA1, unsigned kNeg>()
                  __attribute__((always_inline)) {
                    for (; b < end; ++b)
                      over += chord_rows<kAxes, kA0, kA1, kNeg>(a, b, count, u, rows);
                  });
    b = end;  // (with_axes takes every kind of block)
  }
  for (std::size_t k = 0; k < count; ++k) {  // element order, as geometric_forces
    const double* row = rows + 4 * k;
    const auto gxy = hn::LoadU(dh, row);
    double* fj = f + elements[k].dof_j;
    double* fi = f + elements[k].dof_i;
    hn::StoreU(hn::Add(hn::LoadU(dh, fj), gxy), dh, fj);
    fj[2] += row[2];
    hn::StoreU(hn::Sub(hn::LoadU(dh, fi), gxy), dh, fi);
    fi[2] -= row[2];
  }
  return over;
}

#endif  // HWY_TARGET != HWY_SCALAR

std::size_t GeometricForces(const GeometricArrays& a, const GeometricElement* elements,
                            std::size_t count, const double* u, double* f, double* rows) {
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(D()) == kBeamLanes)
    return chords_transpose(a, elements, count, u, f, rows);
#endif
  (void)a, (void)rows;
  return ntn::geometric_forces(elements, count, u, f);  // vectors of another width: the reference
}

template <bool kFirst>
HWY_INLINE void element_forces_on(const BeamArrays& a, std::size_t elements, const double* u,
                                  const double* v, double beta, double* f) {
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(D()) == kBeamLanes) {
    if (beta != 0.0) {
      forces_transpose<true, kFirst>(a, elements, u, v, beta, f);
    } else {
      forces_transpose<false, kFirst>(a, elements, u, v, beta, f);
    }
    return;
  }
#endif
  const std::size_t num_blocks = beam_blocks(elements);
  for (std::size_t b = 0; b < num_blocks; ++b) {
    alignas(64) double fi[6][kBeamLanes];
    alignas(64) double fj[6][kBeamLanes];
    block_gather(a, b, u, v, beta, fi, fj);
    add_lanes<kFirst>(a.blocks[b], b + 1 < num_blocks ? kBeamLanes : elements - b * kBeamLanes, fi,
                      fj, f);
  }
}

void ElementForces(const BeamArrays& a, std::size_t elements, const double* u, const double* v,
                   double beta, double* f) {
  element_forces_on<false>(a, elements, u, v, beta, f);
}

void ElementForcesFirst(const BeamArrays& a, std::size_t elements, const double* u, const double* v,
                        double beta, double* f) {
  element_forces_on<true>(a, elements, u, v, beta, f);
}

void ElementForcesSplit(const BeamArrays& a, std::size_t first, std::size_t last,
                        const std::uint8_t* direct, const double* u, const double* v, double beta,
                        double* f, double* fe) {
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(D()) == kBeamLanes) {
    if (beta != 0.0) {
      split_transpose<true>(a, first, last, direct, u, v, beta, f, fe);
    } else {
      split_transpose<false>(a, first, last, direct, u, v, beta, f, fe);
    }
    return;
  }
#endif
  for (std::size_t b = first; b < last; ++b) {
    alignas(64) double fi[6][kBeamLanes];
    alignas(64) double fj[6][kBeamLanes];
    block_gather(a, b, u, v, beta, fi, fj);
    split_lanes(a.blocks[b], direct[b], fi, fj, f, fe + 12 * kBeamLanes * b);
  }
}

std::int64_t Target() {
  return HWY_TARGET;
}

}  // namespace HWY_NAMESPACE
}  // namespace ntn::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace ntn {
namespace detail {

HWY_EXPORT(ElementForces);
HWY_EXPORT(ElementForcesFirst);
HWY_EXPORT(ElementForcesSplit);
HWY_EXPORT(GeometricForces);
HWY_EXPORT(Target);

void element_forces_simd(const BeamArrays& a, std::size_t elements, const double* u,
                         const double* v, double beta, double* f) {
  HWY_DYNAMIC_DISPATCH(ElementForces)(a, elements, u, v, beta, f);
}

void element_forces_first_simd(const BeamArrays& a, std::size_t elements, const double* u,
                               const double* v, double beta, double* f) {
  HWY_DYNAMIC_DISPATCH(ElementForcesFirst)(a, elements, u, v, beta, f);
}

void element_forces_split_simd(const BeamArrays& a, std::size_t first, std::size_t last,
                               const std::uint8_t* direct, const double* u, const double* v,
                               double beta, double* f, double* fe) {
  HWY_DYNAMIC_DISPATCH(ElementForcesSplit)(a, first, last, direct, u, v, beta, f, fe);
}

std::size_t geometric_forces_simd(const GeometricArrays& a, const GeometricElement* elements,
                                  std::size_t count, const double* u, double* f, double* rows) {
  return HWY_DYNAMIC_DISPATCH(GeometricForces)(a, elements, count, u, f, rows);
}

// Unqualified names only in HWY_DYNAMIC_DISPATCH: where the build's own instruction set is the
// best Highway knows (-march=native on AVX-512), the macro becomes N_<TARGET>::name, which
// must name a function of this namespace.
std::int64_t target_simd() {
  return HWY_DYNAMIC_DISPATCH(Target)();
}

}  // namespace detail

const char* element_pass_target() {
  return hwy::TargetName(detail::target_simd());
}

}  // namespace ntn
#endif  // HWY_ONCE

#endif  // NTN_SIMD
