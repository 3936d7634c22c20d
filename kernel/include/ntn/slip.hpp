// Rigid-plastic hinge directions under ntn_exact (HingeBehaviour::kRigidPlastic, issue 16): rigid
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
// inside its yield, i.e. when the trial relative motion reverses. Several slip directions of one
// part are solved together by projected Gauss-Seidel on their forces (box-constrained, in a fixed
// order, until no force changes by more than 1e-12 of its yield): the same inputs, the same bits.
// The forces a_n receives are the step's f (S 35-37 increments, as the stops' clamp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "ntn/clamp.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hysteresis.hpp"
#include "ntn/state.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp

inline constexpr int kSlipSweeps = 64;           // Gauss-Seidel sweeps per step, at most
inline constexpr double kSlipTolerance = 1e-12;  // force change, relative to the yield

// A friction direction's limit: mu max(0, -N) + cohesion (N < 0 presses the nodes together).
inline double friction_limit(const HysteresisData& law, double normal) {
  return law.mu * (normal < 0 ? -normal : 0.0) + law.cohesion;
}

namespace detail {

// One sweep over every slip direction: each one's force moves toward what holds it, within its
// yields. Returns the largest change of a force relative to its yield.
template <Sizes S>
double slip_sweep(const Model<S>& m, State<S>& s, Scratch<S>& w, bool first) {
  double largest = 0;
  const double dt2 = m.dt * m.dt;
  for (int i = 0; i < m.num_slip_hinges; ++i) {
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
      clamp_response(m, w, h, k, parts);
      const double mobility = clamp_projection(w, h, k);  // b^T M_c^-1 b
      if (first) w.slip_force[slot] = 0.0;
      if (!(mobility > 0)) continue;  // both sides held: nothing can slide
      const double old_force = w.slip_force[slot];
      double force = old_force + (d[k] - s.plastic[slot]) / (mobility * dt2);
      double up = law.yield_pos, down = law.yield_neg;
      if (law.normal >= 0) up = down = friction_limit(law, w.slip_normal[slot]);
      if (force > up) force = up;
      if (force < -down) force = -down;
      const double change = force - old_force;
      if (change == 0) continue;
      w.slip_force[slot] = force;
      clamp_move(m, s, w, parts, -change * dt2, ++w.clamp.events);
      const double scale = up > down ? up : down;
      const double size = change > 0 ? change : -change;
      const double rel = scale > 0 ? size / scale : size;
      if (rel > largest) largest = rel;
    }
  }
  return largest;
}

}  // namespace detail

// The slip stage (ntn_exact's stops stage, before the stops' clamp): the forces of the slip
// directions, then each direction that is at a yield takes its new slip and the work done.
template <Sizes S>
void slip_stage(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (S.hinges > 0 && S.hystereses > 0) {
    if (m.num_slip_hinges == 0) return;
    for (int sweep = 0; sweep < kSlipSweeps; ++sweep) {
      if (!(detail::slip_sweep(m, s, w, sweep == 0) > kSlipTolerance)) break;
    }
    for (int i = 0; i < m.num_slip_hinges; ++i) {
      const HingeData& h =
          m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(i)])];
      const bool ground = h.node2 == kGround;
      double d[6];
      hinge_relative(h, &s.u[static_cast<std::size_t>(kDofsPerNode * h.node1)],
                     ground ? nullptr : &s.u[static_cast<std::size_t>(kDofsPerNode * h.node2)], d);
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!((h.slip >> k) & 1U)) continue;
        const auto slot = static_cast<std::size_t>(h.history[k]);
        const HysteresisData& law = m.hystereses[slot];
        const double f = w.slip_force[slot];
        double up = law.yield_pos, down = law.yield_neg;
        if (law.normal >= 0) up = down = friction_limit(law, w.slip_normal[slot]);
        if (f != up && f != -down) continue;  // it sticks: s stays
        const double ds = d[k] - s.plastic[slot];
        s.dissipated[slot] += f * ds;  // >= 0: it slides the way its force resists
        s.plastic[slot] = d[k];
        const double size = d[k] < 0 ? -d[k] : d[k];
        if (size > s.plastic_peak[slot]) s.plastic_peak[slot] = size;
      }
    }
  }
}

// The hinge-force channels of slip directions: the slip stage's force at t_n (sample_outputs ran
// before it).
template <Sizes S>
void slip_outputs(const Model<S>& m, Scratch<S>& w) {
  if constexpr (S.hinges > 0 && S.hystereses > 0 && S.outputs > 0) {
    if (m.num_slip_hinges == 0) return;
    for (std::size_t c = 0; c < S.outputs; ++c) {
      const OutputSpec& o = m.outputs[c];
      if (o.kind != OutputKind::kHingeForce) continue;
      const HingeData& h = m.hinges[static_cast<std::size_t>(o.hinge)];
      if (!((h.slip >> o.dof) & 1U)) continue;
      w.outputs[c] =
          w.slip_force[static_cast<std::size_t>(h.history[static_cast<std::size_t>(o.dof)])];
    }
  }
}

}  // namespace ntn
