// The hinge methods (DESIGN §7) behind one interface, and the one place that picks a method from
// HingeMethod. Each method is a struct of static functions in its own header:
//
//   rigid_direction(settings, k, h)   init: what a rigid direction becomes (coupled, or a spring)
//   slip_direction(settings, k, h)    init: what a rigid-plastic direction becomes (slip.hpp)
//   init(spec, model, work)           init: what the method precomputes
//   residual(m, s, w)                 step: the residual pass R_n - C v (S 2-3), a_n where
//   uncoupled couple(m, s, w)                   step: the NTN coupling, R -> a at coupled DOFs
//   stops(m, s, w)                    step: rigid branches after the update (clamp.hpp)
//   start_forces(m, s, w)             start: the slip and stop forces at t_0 (on a trial u_1)
//   project(m, s, w)                  step: the constraint projection after the update
//   project_initial(m, s)             start: u_0, v_0 onto the constraints
//   constraint_force(m, s, w, hinge, k, coupled_tree)   output: the force of a coupled direction
//
// A new method is one header with such a struct, one HingeMethod value (model_spec.hpp) and one
// case in with_hinge_method() below (and its name in the model compiler).
#pragma once

#include <cstddef>
#include <span>

#include "ntn/dashpot.hpp"
#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/ntn_exact.hpp"
#include "ntn/ntn_paper.hpp"
#include "ntn/penalty.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp
template <Sizes S>
struct InitWorkspace;  // model.hpp

// Calls fn with the method's struct (a value of an empty type) and returns what it returns.
template <class Fn>
decltype(auto) with_hinge_method(HingeMethod method, Fn&& fn) {
  switch (method) {
    case HingeMethod::kPenalty:
      return fn(PenaltyMethod{});
    case HingeMethod::kNtnPaper:
      return fn(NtnPaperMethod{});
    case HingeMethod::kNtnExact:
      break;
  }
  return fn(NtnExactMethod{});
}

// Resolves a hinge spec for the model's method (resolve_hinge, hinge.hpp): which directions are
// coupled (`rigid`), which carry a spring force (`springs`, penalty's rigid directions among
// them), and where curves have rigid branches. False for a bad spec (resolve_hinge).
inline bool make_hinge_data(const HingeSpec& spec, const Settings& settings, std::size_t node_count,
                            std::span<const CurveSpec> curves, std::span<const CurvePoint> points,
                            HingeData& h) {
  return with_hinge_method(settings.hinge_method, [&](auto method) {
    return resolve_hinge(
        spec, settings, node_count, curves, points, h,
        [&](std::size_t k) { return method.rigid_direction(settings, k, h); },
        [&](std::size_t k) { return method.slip_direction(settings, k, h); });
  });
}

// What a hinge that turns with its nodes (HingeData::turns) may not hold: the stages whose rows
// are built once at init keep the reference axes (the forest's matrices, ntn_paper's hinge-frame
// masses, the clamp's, the slips' and the central dashpots' directions). The forest's rows do
// not depend on the axes where a block's directions are all coupled or none is (the coupled
// space is then all of it or nothing) and a coupled translation has no offset; a spring's rows
// are the pose's in every stage (hinge_turned).
enum class TurnRefusal : std::uint8_t {
  kNone,
  kPartCoupled,       // ntn_exact: some of a block's three directions coupled, not all
  kEccentricCoupled,  // ntn_exact: coupled translations of an eccentric hinge (its arm turns)
  kPaperCoupled,      // ntn_paper: a coupled direction
  kStop,              // a curve with a rigid branch (the clamp)
  kSlip,              // a rigid-plastic direction held by the slip stage
  kCentralDashpot,    // a dashpot under damping_velocity = "central" (the dashpot stage)
};

struct TurnCheck {
  TurnRefusal why = TurnRefusal::kNone;
  int direction = -1;  // the direction that breaks it (0..5), the first
  constexpr bool ok() const { return why == TurnRefusal::kNone; }
};

inline TurnCheck turning_hinge_check(const HingeData& h, const Settings& settings) {
  for (int k = 0; k < static_cast<int>(kDofsPerNode); ++k) {
    const auto uk = static_cast<std::size_t>(k);
    if ((h.branches >> k) & 1U) return {TurnRefusal::kStop, k};
    if ((h.slip >> k) & 1U) return {TurnRefusal::kSlip, k};
    if (settings.damping_velocity == DampingVelocity::kCentral && has_dashpot(h, uk))
      return {TurnRefusal::kCentralDashpot, k};
    if (!((h.rigid >> k) & 1U)) continue;
    if (settings.hinge_method == HingeMethod::kNtnPaper) return {TurnRefusal::kPaperCoupled, k};
  }
  for (int block = 0; block < 2; ++block) {
    const unsigned bits = (static_cast<unsigned>(h.rigid) >> (3 * block)) & 7U;
    if (bits != 0 && bits != 7U) {
      int k = 3 * block;
      while (((bits >> (k - 3 * block)) & 1U) != 0)
        ++k;  // the first direction of the block left free
      return {TurnRefusal::kPartCoupled, k};
    }
  }
  const auto& e = h.eccentricity;
  if ((h.rigid & 7U) != 0 && (e[0] != 0 || e[1] != 0 || e[2] != 0))
    return {TurnRefusal::kEccentricCoupled, 0};
  return {};
}

namespace detail {

// The stages of init() and step() that depend on the method: each picks the method once.

template <Sizes S>
InitStatus hinge_method_init(const ModelSpec<S>& spec, Model<S>& model, InitWorkspace<S>& work) {
  return with_hinge_method(model.hinge_method,
                           [&](auto method) { return method.init(spec, model, work); });
}

// R_n - C v_{n-1/2} (S 2-3): a_n = (R_n - C v) / m at every DOF that no hinge couples.
template <Sizes S>
void residual_stage(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.sizes.hinges > 0) {
      with_hinge_method(m.hinge_method, [&](auto method) { method.residual(m, s, w); });
      return;
    }
  }
  residual(m, s, w, m.inv_mass.data(), w.a.data());
}

// The NTN coupling: a_n at the coupled DOFs (S 17-26; DESIGN §7.1).
template <Sizes S>
void ntn_coupling(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.sizes.hinges > 0)
      with_hinge_method(m.hinge_method, [&](auto method) { method.couple(m, s, w); });
  }
}

// The move weights of a step (ClampWork: dt^2, 1/dt, 1).
// Rigid branches, after the update: the momentum clamp or S 33 (DESIGN §7.1), with the step's
// weights; from here on the constraint stages mark the nodes they move (ClampWork::step_events).
template <Sizes S>
void step_weights(const Model<S>& m, Scratch<S>& w) {
  w.clamp.h2 = m.dt * m.dt, w.clamp.v_rate = m.inv_dt, w.clamp.a_scale = 1.0;
}

template <Sizes S>
void hinge_stops(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.sizes.hinges > 0) {
      step_weights(m, w);
      w.clamp.step_events = w.clamp.events;
      with_hinge_method(m.hinge_method, [&](auto method) { method.stops(m, s, w); });
    }
  }
}

// start(): the slip and stop forces at t_0, found on the trial u_1 that s.u holds (ClampWork's
// weights set by start()).
template <Sizes S>
void hinge_start_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.sizes.hinges > 0)
      with_hinge_method(m.hinge_method, [&](auto method) { method.start_forces(m, s, w); });
  }
}

// The constraint projection, after the stops: S 27-37 or the forest's (DESIGN §7.1).
template <Sizes S>
void constraint_projection(const Model<S>& m, State<S>& s, Scratch<S>& w) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.sizes.hinges > 0)
      with_hinge_method(m.hinge_method, [&](auto method) { method.project(m, s, w); });
  }
}

template <Sizes S>
void project_initial(const Model<S>& m, State<S>& s) {
  if constexpr (kMayHaveHinges<S>) {
    if (m.sizes.hinges > 0)
      with_hinge_method(m.hinge_method, [&](auto method) { method.project_initial(m, s); });
  }
}

template <Sizes S>
double constraint_force(const Model<S>& m, const State<S>& s, Scratch<S>& w, int hinge, int k,
                        int& coupled_tree) {
  return with_hinge_method(m.hinge_method, [&](auto method) {
    return method.constraint_force(m, s, w, hinge, k, coupled_tree);
  });
}

}  // namespace detail
}  // namespace ntn
