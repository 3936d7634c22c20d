// Rigid-plastic hinge directions under ntn_exact (HingeBehaviour::kRigidPlastic): rigid
// while the force that holds them stays within their yield, sliding at the yield force when it
// would not. No penalty spring: the direction is free in the constraint forest and held, after
// the update, by the slip stage, a momentum-conserving move of the constrained system like the
// stops' clamp (clamp.hpp). For direction k with row b of B, mobility W = b^T M_c^-1 b (M_c^-1 the
// lumped inverse mass with the rigid trees applied) and the relative displacement d = b u_{n+1}
// after the update: the force f that keeps d where the direction sticks, s (its slip so far,
// State::plastic), is f = (d - s) / (W dt^2), since a force f acting at t_n moves u_{n+1} by
// -f dt^2 M_c^-1 b (f acts like a spring force f_L: on node 1, in the hinge frame). When
// -yield_neg <= f <= yield_pos the model moves by -f dt^2 M_c^-1 b and d lands on s (stick, to
// rounding); otherwise f is the yield it passed, the model moves by that, and the direction has
// slid to where d now is: s takes it, and the friction work |f| |ds| is dissipated (exact: f is
// constant over the slide). The direction sticks again when the force to hold it falls back
// inside its yield, i.e. when the trial relative motion reverses. The slip directions of one rigid
// tree are solved together (slip_tree_solve: a box-constrained problem in their forces, by an
// active set and L D L^T, like the stops' clamp_tree); those between parts, on the ground, or in
// a tree the block solve declines, by projected Gauss-Seidel in a fixed order until no force
// changes by more than 1e-12 of its limit. The same inputs give the same bits.
// The forces a_n receives are the step's f (S 35-37 increments, as the stops' clamp).
// Friction (HysteresisData::normal): the limit mu max(0, -N) + cohesion, N the normal
// direction's force at t_n (slip_normals, integrator.hpp); two friction directions of a hinge
// may share it on their resultant (HysteresisData::circle, the friction circle: solved as a pair
// by Gauss-Seidel, circle_step). fixed_if (HysteresisData::fixed_if):
// held with no limit while that force has the given sign, free otherwise (RFEM's "fixed if
// N-"). Failure (HysteresisRule::kBrittle): the first slide breaks the direction, which is free
// from the next step on; State::first_slip records when any rigid-plastic direction first slid.
// Hardening with the slip: a spring in parallel (HingeSpec::stiffness, the spring stage's), so
// that the force is yield + H d while sliding (linear kinematic hardening, exact).
// State::slip_state keeps how each direction left the step (stuck, sliding, free): an output
// channel, and where the next step's tree solve starts its active set.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "ntn/clamp.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hysteresis.hpp"
#include "ntn/root.hpp"
#include "ntn/state.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp
template <Sizes S>
struct InitWorkspace;  // model.hpp

inline constexpr int kSlipSweeps = 64;           // Gauss-Seidel sweeps per step, at most
inline constexpr double kSlipTolerance = 1e-12;  // force change, relative to the yield

// A friction direction's limit: mu max(0, -N) + cohesion (N < 0 presses the nodes together).
inline double friction_limit(const HysteresisData& law, double normal) {
  return law.mu * (normal < 0 ? -normal : 0.0) + law.cohesion;
}

// The limit of a held fixed_if direction: any force it takes (finite, so that the solves'
// arithmetic stays finite).
inline constexpr double kHeld = 1e300;

// The limits of slip direction `slot` now, in the positive and the negative sense: its yields,
// its friction limit, held or free by the sign of its control (fixed_if), or none left once a
// `failure` direction has broken.
template <Sizes S>
void slip_limits(const HysteresisData& law, const State<S>& s, const Scratch<S>& w,
                 std::size_t slot, double& up, double& down) {
  up = law.yield_pos, down = law.yield_neg;
  if (law.fixed_if != 0) {
    const double n = w.slip_normal[slot];
    up = down = (law.fixed_if < 0 ? n < 0 : n > 0) ? kHeld : 0.0;
  } else if (law.normal >= 0) {
    up = down = friction_limit(law, w.slip_normal[slot]);
  }
  if (law_breaks(law.rule) && s.first_slip[slot] != 0) up = down = 0.0;
}

namespace detail {

// L D L^T of the symmetric n x n matrix A (row stride kSlipBlock, its lower triangle read) in
// place: L below the diagonal, D on it. False when a pivot is not above 1e-12 of the largest
// diagonal entry (dependent directions).
inline bool ldl_factor(double* A, int n) {
  double scale = 0;
  for (int i = 0; i < n; ++i) {
    if (A[i * kSlipBlock + i] > scale) scale = A[i * kSlipBlock + i];
  }
  for (int j = 0; j < n; ++j) {
    double* rj = A + j * kSlipBlock;
    double djj = rj[j];
    for (int q = 0; q < j; ++q)
      djj -= rj[q] * rj[q] * A[q * kSlipBlock + q];
    if (!(djj > 1e-12 * scale)) return false;
    rj[j] = djj;
    for (int i = j + 1; i < n; ++i) {
      double* ri = A + i * kSlipBlock;
      double sum = ri[j];
      for (int q = 0; q < j; ++q)
        sum -= ri[q] * rj[q] * A[q * kSlipBlock + q];
      ri[j] = sum / djj;
    }
  }
  return true;
}

// Solves L D L^T x = b in place (b in x), with ldl_factor's A.
inline void ldl_solve(const double* A, int n, double* x) {
  for (int i = 0; i < n; ++i) {
    for (int q = 0; q < i; ++q)
      x[i] -= A[i * kSlipBlock + q] * x[q];
  }
  for (int i = 0; i < n; ++i)
    x[i] /= A[i * kSlipBlock + i];
  for (int i = n - 1; i >= 0; --i) {
    for (int q = i + 1; q < n; ++q)
      x[i] -= A[q * kSlipBlock + i] * x[q];
  }
}

inline constexpr int kCircleIterations = 32;  // the sliding direction's fixed point, at most

// One Gauss-Seidel step of the friction circle of hinge h's directions k and p = the circle of k
// (k < p): one limit R on the resultant of their forces f = (f_k, f_p). With W the pair's 2 x 2
// mobility and r = (d - s) / dt^2 what the forces must still do, f + W^-1 r holds both (stick)
// when it lies within R; else the pair slides, its force at R along the slip it leaves,
// g = r - W (f_new - f), found by the fixed point f_new = R g / |g| (exact at once when W is
// isotropic, as for a node's two tangential directions; kCircleIterations at most). Moves the
// parts once; returns the largest force change relative to R.
template <Sizes S>
double circle_step(const Model<S>& m, State<S>& s, Scratch<S>& w, const HingeData& h,
                   const ClampPart (&parts)[2], std::size_t k, const double* d, bool first) {
  const auto p =
      static_cast<std::size_t>(m.hystereses[static_cast<std::size_t>(h.history[k])].circle);
  const auto sk = static_cast<std::size_t>(h.history[k]),
             sp = static_cast<std::size_t>(h.history[p]);
  const double dt2 = w.clamp.h2;  // dt^2 in a step (ClampWork)
  clamp_response(m, w, h, k, parts);
  const double wkk = clamp_projection(w, h, k), wkp = clamp_projection(w, h, p);
  clamp_response(m, w, h, p, parts);
  const double wpp = clamp_projection(w, h, p), wpk = clamp_projection(w, h, k);
  const double w12 = 0.5 * (wkp + wpk), det = wkk * wpp - w12 * w12;
  if (first) w.slip_force[sk] = w.slip_force[sp] = 0.0;
  if (!(wkk > 0) || !(wpp > 0) || !(det > 0)) return 0.0;  // held: nothing can slide
  double up = 0, down = 0;
  slip_limits(m.hystereses[sk], s, w, sk, up, down);
  const double R = up;
  const double fk = w.slip_force[sk], fp = w.slip_force[sp];
  const double rk = (d[k] - s.plastic[sk]) / dt2, rp = (d[p] - s.plastic[sp]) / dt2;
  double nk = fk + (wpp * rk - w12 * rp) / det, np = fp + (wkk * rp - w12 * rk) / det;
  if (nk * nk + np * np > R * R) {  // it slides: the force at R along the slip it leaves
    double size = root(nk * nk + np * np);
    nk *= R / size, np *= R / size;
    for (int it = 0; it < kCircleIterations; ++it) {
      const double gk = rk - wkk * (nk - fk) - w12 * (np - fp);
      const double gp = rp - w12 * (nk - fk) - wpp * (np - fp);
      size = root(gk * gk + gp * gp);
      if (!(size > 0)) break;
      const double ak = R * gk / size, ap = R * gp / size;
      const double ek = ak - nk, ep = ap - np;
      const bool settled = (ek < 0 ? -ek : ek) <= 1e-15 * R && (ep < 0 ? -ep : ep) <= 1e-15 * R;
      nk = ak, np = ap;
      if (settled) break;
    }
  }
  const double ck = nk - fk, cp = np - fp;
  if (ck == 0 && cp == 0) return 0.0;
  w.slip_force[sk] = nk, w.slip_force[sp] = np;
  clear_impulse(m, parts, w.clamp.impulse.data());
  add_impulse(h, k, -dt2 * ck, w.clamp.impulse.data());
  add_impulse(h, p, -dt2 * cp, w.clamp.impulse.data());
  parts_response(m, parts, w.clamp.impulse.data(), w.clamp.response.data());
  clamp_move(m, s, w, parts, 1.0, ++w.clamp.events);
  const double ak = ck < 0 ? -ck : ck, ap = cp < 0 ? -cp : cp;
  const double change = ak > ap ? ak : ap;
  return R > 0 ? change / R : change;
}

// One Gauss-Seidel sweep over the slip directions of slip hinges [begin, end): each one's force
// moves toward what holds it, within its limits. Returns the largest change of a force relative
// to its limit.
template <Sizes S>
double slip_sweep(const Model<S>& m, State<S>& s, Scratch<S>& w, bool first, int begin, int end) {
  double largest = 0;
  const double dt2 = w.clamp.h2;  // dt^2 in a step (ClampWork)
  for (int i = begin; i < end; ++i) {
    const HingeData& h =
        m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(i)])];
    ClampPart parts[2];
    clamp_parts(m, h, parts);
    const auto i1 = static_cast<std::size_t>(kDofsPerNode * h.node1);
    const bool ground = h.node2 == kGround;
    const auto i2 = ground ? 0 : static_cast<std::size_t>(kDofsPerNode * h.node2);
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((h.slip >> k) & 1U)) continue;
      const auto slot = static_cast<std::size_t>(h.history[k]);
      const HysteresisData& law = m.hystereses[slot];
      double d[6];
      hinge_relative(h, &s.u[i1], ground ? nullptr : &s.u[i2], d);
      if (law.circle >= 0) {  // a friction circle: the pair together, from its first direction
        if (static_cast<std::size_t>(law.circle) > k) {
          const double rel = circle_step(m, s, w, h, parts, k, d, first);
          if (rel > largest) largest = rel;
        }
        continue;
      }
      clamp_response(m, w, h, k, parts);
      const double mobility = clamp_projection(w, h, k);  // b^T M_c^-1 b
      if (first) w.slip_force[slot] = 0.0;
      if (!(mobility > 0)) continue;  // both sides held: nothing can slide
      const double old_force = w.slip_force[slot];
      double force = old_force + (d[k] - s.plastic[slot]) / (mobility * dt2);
      double up = 0, down = 0;
      slip_limits(law, s, w, slot, up, down);
      if (force > up) force = up;
      if (force < -down) force = -down;
      const double change = force - old_force;
      if (change == 0) continue;
      w.slip_force[slot] = force;
      clamp_move(m, s, w, parts, -change * dt2, ++w.clamp.events);
      // relative to its limit (to the force itself when held without one)
      double scale = up > down ? up : down;
      if (scale >= kHeld) scale = force < 0 ? -force : force;
      const double size = change > 0 ? change : -change;
      const double rel = scale > 0 ? size / scale : size;
      if (rel > largest) largest = rel;
    }
  }
  return largest;
}

// The number of slip directions of slip hinges [begin, end).
template <Sizes S>
int slip_directions(const Model<S>& m, int begin, int end) {
  int n = 0;
  for (int q = begin; q < end; ++q)
    for (unsigned bits =
             m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(q)])].slip;
         bits != 0; bits &= bits - 1)
      ++n;
  return n;
}

// The rigid tree that holds both nodes of slip hinge `hinge` (clamp.hpp's hinge_tree), or -1:
// the slip stage solves a tree's directions together.
template <Sizes S>
int slip_tree(const Model<S>& m, int hinge) {
  return hinge_tree(m, m.hinges[static_cast<std::size_t>(hinge)]);
}

// Calls fn(tree, begin, end, first_direction) for each range of slip hinges that one rigid tree
// holds (tree -1: those in none; sort_slip_hinges made each one range), first_direction being
// the number of slip directions before the range (the rows of Model::slip_mobility).
template <Sizes S, class Fn>
void for_each_slip_range(const Model<S>& m, Fn&& fn) {
  int g = 0;
  for (int i = 0; i < m.num_slip_hinges;) {
    const int tree = slip_tree(m, m.slip_hinges[static_cast<std::size_t>(i)]);
    int j = i + 1;
    while (j < m.num_slip_hinges &&
           slip_tree(m, m.slip_hinges[static_cast<std::size_t>(j)]) == tree)
      ++j;
    fn(tree, i, j, g);
    g += slip_directions(m, i, j);
    i = j;
  }
}

// The slip directions of slip hinges [begin, end), all in rigid tree `tree`, together: with
// W_ij = b_i^T M_c^-1 b_j (the constrained system's mobility between them) and e_i = (d_i -
// s_i) / dt^2, the forces f solve the box-constrained problem: W f = e on the directions that
// stick, f_i at a limit where direction i slides (and the rest of e_i points past it). An active
// set (every direction sticking at first; the one furthest past its limit put at it, or the one
// at a limit that would pull back released, one at a time), each round solved by L D L^T on the
// sticking set; then the tree moves once by -dt^2 M_c^-1 sum_j f_j b_j. W is Model's, built at
// init; the directions are numbered from `first_direction` in the slip stage's order. False
// (nothing moved)
// when the tree has more than kSlipBlock directions, W is singular on a set, or the set does not
// settle: the caller then runs Gauss-Seidel.
template <Sizes S>
bool slip_tree_solve(const Model<S>& m, State<S>& s, Scratch<S>& w, int tree, int begin, int end,
                     int first_direction) {
  struct Dir {
    int hinge;
    std::size_t k, slot;
    double e, up, down;
  };
  Dir c[kSlipBlock];
  int n = 0;
  const double dt2 = w.clamp.h2;  // dt^2 in a step (ClampWork)
  for (int q = begin; q < end; ++q) {
    const int hi = m.slip_hinges[static_cast<std::size_t>(q)];
    const HingeData& h = m.hinges[static_cast<std::size_t>(hi)];
    double d[6];
    hinge_relative(h, &s.u[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                   &s.u[static_cast<std::size_t>(kDofsPerNode * h.node2)], d);
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((h.slip >> k) & 1U)) continue;
      if (n == kSlipBlock) return false;
      const auto slot = static_cast<std::size_t>(h.history[k]);
      if (m.hystereses[slot].circle >= 0) return false;  // a circle is not a box: Gauss-Seidel
      double up = 0, down = 0;
      slip_limits(m.hystereses[slot], s, w, slot, up, down);
      c[n++] = {hi, k, slot, (d[k] - s.plastic[slot]) / dt2, up, down};
    }
  }
  const ClampPart parts[2] = {ClampPart{tree, -1}, {}};
  // The tree's mobility matrix W and its L D L^T with every direction sticking (init).
  const double* W = &m.slip_mobility[static_cast<std::size_t>(first_direction * kSlipBlock)];
  const double* full = &m.slip_factor[static_cast<std::size_t>(first_direction * kSlipBlock)];
  for (int i = 0; i < n; ++i) {
    if (!(W[i * kSlipBlock + i] > 0)) return false;
  }
  // at[i]: 0 sticks (free force), +1 at its upper limit, -1 at its lower, 2 held at 0 (no
  // limit). The set starts where the last step left it (State::slip_state): a direction that
  // slid then most often slides now.
  int at[kSlipBlock];
  double f[kSlipBlock];
  for (int i = 0; i < n; ++i) {
    const int last = s.slip_state[c[i].slot];
    at[i] = c[i].up == 0 && c[i].down == 0 ? 2 : last == 1 || last == -1 ? last : 0;
    f[i] = at[i] == 1 ? c[i].up : at[i] == -1 ? -c[i].down : 0.0;
  }
  bool settled = false;
  for (int round = 0; round < 4 * kSlipBlock && !settled; ++round) {
    // W_FF f_F = e_F - W_FB f_B on the sticking set F (gathered): by the init-time factor when
    // every direction sticks, else by factoring W_FF.
    int F[kSlipBlock];
    int nf = 0;
    for (int i = 0; i < n; ++i) {
      if (at[i] == 0) F[nf++] = i;
    }
    double x[kSlipBlock];
    for (int a = 0; a < nf; ++a) {
      const int i = F[a];
      double sum = c[i].e;
      for (int j = 0; j < n; ++j) {
        if (at[j] != 0) sum -= W[i * kSlipBlock + j] * f[j];
      }
      x[a] = sum;
    }
    if (nf == n && full[0] > 0) {
      ldl_solve(full, n, x);
    } else if (nf > 0) {
      double A[kSlipBlock * kSlipBlock];
      for (int a = 0; a < nf; ++a) {
        for (int b = 0; b <= a; ++b)
          A[a * kSlipBlock + b] = W[F[a] * kSlipBlock + F[b]];
      }
      if (!ldl_factor(A, nf)) return false;  // dependent directions
      ldl_solve(A, nf, x);
    }
    for (int a = 0; a < nf; ++a)
      f[F[a]] = x[a];
    // The sticking direction furthest past a limit goes to it; else the direction at a limit
    // whose rest of e points back inside is released; else done.
    int worst = -1;
    double most = 0;
    for (int i = 0; i < n; ++i) {
      if (at[i] != 0) continue;
      const double over = f[i] > c[i].up ? f[i] - c[i].up : -c[i].down - f[i];
      const double limit = c[i].up > c[i].down ? c[i].up : c[i].down;
      if (over > 0 && over > most * limit) most = over / limit, worst = i;
    }
    if (worst >= 0) {
      at[worst] = f[worst] > c[worst].up ? 1 : -1;
      f[worst] = at[worst] > 0 ? c[worst].up : -c[worst].down;
      continue;
    }
    int release = -1;
    double pull = 0;
    for (int i = 0; i < n; ++i) {
      if (at[i] != 1 && at[i] != -1) continue;
      double r = c[i].e, size = c[i].e < 0 ? -c[i].e : c[i].e;
      for (int j = 0; j < n; ++j) {
        const double t = W[i * kSlipBlock + j] * f[j];
        r -= t;
        size += t < 0 ? -t : t;
      }
      const double back = -static_cast<double>(at[i]) * r;  // > 0: it would move back inside
      const double wii = W[i * kSlipBlock + i];
      if (back > 1e-12 * size && back / wii > pull) pull = back / wii, release = i;
    }
    if (release >= 0) {
      at[release] = 0;
      continue;
    }
    settled = true;
  }
  if (!settled) return false;
  // One move of the tree: y = M_c^-1 sum_j (-dt^2 f_j) b_j.
  bool any = false;
  clear_impulse(m, parts, w.clamp.impulse.data());
  for (int j = 0; j < n; ++j) {
    w.slip_force[c[j].slot] = f[j];
    if (f[j] == 0) continue;
    any = true;
    add_impulse(m.hinges[static_cast<std::size_t>(c[j].hinge)], c[j].k, -dt2 * f[j],
                w.clamp.impulse.data());
  }
  if (!any) return true;
  parts_response(m, parts, w.clamp.impulse.data(), w.clamp.response.data());
  clamp_move(m, s, w, parts, 1.0, ++w.clamp.events);
  return true;
}

// Gauss-Seidel over slip hinges [begin, end) until no force changes by more than kSlipTolerance
// of its limit (kSlipSweeps at most).
template <Sizes S>
void slip_gauss_seidel(const Model<S>& m, State<S>& s, Scratch<S>& w, int begin, int end) {
  for (int sweep = 0; sweep < kSlipSweeps; ++sweep) {
    if (!(slip_sweep(m, s, w, sweep == 0, begin, end) > kSlipTolerance)) break;
  }
}

}  // namespace detail

// At init (ntn_exact, after the forest's trees): the slip hinges ordered by the tree that holds
// both their nodes (those in none first), then by index, so that each tree's are one range.
template <Sizes S>
void sort_slip_hinges(Model<S>& m) {
  const auto first = m.slip_hinges.begin();
  std::sort(first, first + m.num_slip_hinges, [&m](std::int32_t a, std::int32_t b) {
    const int ta = detail::slip_tree(m, a), tb = detail::slip_tree(m, b);
    return ta != tb ? ta < tb : a < b;
  });
}

// At init (ntn_exact, after sort_slip_hinges): the mobility matrix W_ij = b_i^T M_c^-1 b_j of
// each rigid tree's slip directions (at most kSlipBlock), into Model::slip_mobility, symmetrized
// (it is symmetric up to rounding): the masses and the hinge geometry fix it for the run. The
// stops' own impulse and response pieces (clear_impulse, add_impulse, parts_response,
// response_along, clamp.hpp), with InitWorkspace's buffers.
template <Sizes S>
void init_slip_mobility(Model<S>& m, InitWorkspace<S>& work) {
  if constexpr (kMayHaveHystereses<S>) {
    double* impulse = work.slip_impulse.data();
    double* response = work.slip_response.data();
    // The directions of slip hinges [begin, end) in the slip stage's order: fn(hinge, k, index).
    const auto each = [&m](int begin, int end, auto&& fn) {
      int index = 0;
      for (int q = begin; q < end; ++q) {
        const HingeData& h =
            m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(q)])];
        for (std::size_t k = 0; k < kDofsPerNode; ++k) {
          if ((h.slip >> k) & 1U) fn(h, k, index++);
        }
      }
    };
    detail::for_each_slip_range(m, [&](int tree, int begin, int end, int g) {
      const int n = detail::slip_directions(m, begin, end);
      if (tree < 0 || n > kSlipBlock) return;
      const detail::ClampPart parts[2] = {detail::ClampPart{tree, -1}, {}};
      const auto at = [&m, g](int row, int col) -> double& {
        return m.slip_mobility[static_cast<std::size_t>((g + row) * kSlipBlock + col)];
      };
      each(begin, end, [&](const HingeData& hj, std::size_t k, int col) {
        detail::clear_impulse(m, parts, impulse);
        detail::add_impulse(hj, k, 1.0, impulse);
        detail::parts_response(m, parts, impulse, response);
        each(begin, end, [&](const HingeData& hi, std::size_t k2, int row) {
          at(row, col) = detail::response_along(hi, k2, response);
        });
      });
      for (int a = 0; a < n; ++a) {  // symmetric up to rounding
        for (int b = 0; b < a; ++b)
          at(a, b) = at(b, a) = 0.5 * (at(a, b) + at(b, a));
      }
      // Its L D L^T with every direction sticking (the common step), or 0 in the first entry
      // when W is singular (the step then factors each sticking set, or declines).
      double* factor = &m.slip_factor[static_cast<std::size_t>(g * kSlipBlock)];
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b)
          factor[a * kSlipBlock + b] = at(a, b);
      }
      if (!detail::ldl_factor(factor, n)) factor[0] = 0;
    });
  }
}

// The forces of the slip directions (Scratch::slip_force) and the moves they make, with the
// weights of ClampWork: the slip stage's first half, and what start() runs on its trial.
template <Sizes S>
void slip_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHystereses<S>) {
    if (m.num_slip_hinges == 0) return;
    // Tree by tree (sort_slip_hinges made each tree's one range): together, or by Gauss-Seidel
    // when that fails; the hinges in no tree (first) by Gauss-Seidel.
    detail::for_each_slip_range(m, [&](int tree, int begin, int end, int g) {
      if (tree < 0 || !detail::slip_tree_solve(m, s, w, tree, begin, end, g))
        detail::slip_gauss_seidel(m, s, w, begin, end);
    });
  }
}

// The slip stage (ntn_exact's stops stage, before the stops' clamp): the forces of the slip
// directions, then each direction that is at a yield takes its new slip and the work done.
template <Sizes S>
void slip_stage(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHystereses<S>) {
    if (m.num_slip_hinges == 0) return;
    slip_forces(m, s, w);
    for (int i = 0; i < m.num_slip_hinges; ++i) {
      const HingeData& h =
          m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(i)])];
      const bool ground = h.node2 == kGround;
      double d[6];
      bool have_d = false;  // the relative displacement, once a direction of the hinge slides
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!((h.slip >> k) & 1U)) continue;
        const auto slot = static_cast<std::size_t>(h.history[k]);
        const HysteresisData& law = m.hystereses[slot];
        const double f = w.slip_force[slot];
        double up = 0, down = 0;
        slip_limits(law, s, w, slot, up, down);
        const bool free = up == 0 && down == 0;
        if (law.circle >= 0) {  // at the circle: the resultant at R (to rounding)
          const double g = w.slip_force[static_cast<std::size_t>(
              h.history[static_cast<std::size_t>(law.circle)])];
          const bool at = f * f + g * g >= up * up * (1 - 1e-12);
          s.slip_state[slot] = static_cast<std::int8_t>(free ? 2 : !at ? 0 : f < 0 ? -1 : 1);
        } else {
          s.slip_state[slot] = static_cast<std::int8_t>(free         ? 2
                                                        : f == up    ? 1
                                                        : f == -down ? -1
                                                                     : 0);
        }
        if (s.slip_state[slot] == 0) continue;  // it sticks: s stays
        if (!have_d) {
          hinge_relative(h, &s.u[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                         ground ? nullptr : &s.u[static_cast<std::size_t>(kDofsPerNode * h.node2)],
                         d);
          have_d = true;
        }
        if (s.first_slip[slot] == 0 && (up > 0 || down > 0) && d[k] != s.plastic[slot])
          s.first_slip[slot] = s.tick + 1;  // the first slide (a failure direction breaks)
        const double ds = d[k] - s.plastic[slot];
        s.dissipated[slot] += f * ds;  // >= 0: it slides the way its force resists
        s.plastic[slot] = d[k];
        const double size = d[k] < 0 ? -d[k] : d[k];
        if (size > s.plastic_peak[slot]) s.plastic_peak[slot] = size;
      }
    }
  }
}

// The hinge-force and slip-state channels of slip directions, after the slip stage: its force at
// t_n added to what sample_outputs, which ran before it, gave (0, or the hardening spring's
// force), and how the stage left the direction (State::slip_state).
template <Sizes S>
void slip_outputs(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHystereses<S> && (S.runtime || S.outputs > 0)) {
    if (m.num_slip_hinges == 0) return;
    for (std::size_t c = 0; c < m.sizes.outputs; ++c) {
      const OutputSpec& o = m.outputs[c];
      if (o.kind != OutputKind::kHingeForce && o.kind != OutputKind::kHingeSlipState) continue;
      const HingeData& h = m.hinges[static_cast<std::size_t>(o.hinge)];
      if (!((h.slip >> o.dof) & 1U)) continue;
      const auto slot = static_cast<std::size_t>(h.history[static_cast<std::size_t>(o.dof)]);
      if (o.kind == OutputKind::kHingeForce) {
        w.outputs[c] += w.slip_force[slot];
      } else {
        w.outputs[c] = s.slip_state[slot];
      }
    }
  }
}

}  // namespace ntn
