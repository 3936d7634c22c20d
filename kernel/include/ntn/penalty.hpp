// penalty (DESIGN §7): a rigid hinge direction is a stiff spring, k_p B^T B, like a `linear`
// direction; nothing couples the nodes, so the residual pass gives a_n directly and there is no
// constraint to project. Its stable step falls as k_p grows (time_step.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "ntn/clamp.hpp"
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

// The method's functions, called only through hinge_methods.hpp.
struct PenaltyMethod {
  // Rigid direction k of a hinge: a spring with the penalty stiffness (translation or rotation).
  static bool rigid_direction(const Settings& settings, std::size_t k, HingeData& h) {
    h.stiffness[k] = penalty_stiffness(settings, k);
    if (!(h.stiffness[k] > 0)) return false;
    h.springs |= static_cast<std::uint8_t>(1U << k);
    return true;
  }

  // Rigid-plastic direction k: an elasto-plastic spring of the penalty stiffness (its yield and
  // hardening with the slip from the direction's law: bilinear, or brittle for `failure`), the
  // comparison the seed's way allows.
  static bool slip_direction(const Settings& settings, std::size_t k, HingeData& h) {
    h.stiffness[k] = penalty_stiffness(settings, k);
    if (!(h.stiffness[k] > 0)) return false;
    h.springs |= static_cast<std::uint8_t>(1U << k);
    h.plastic |= static_cast<std::uint8_t>(1U << k);
    return true;
  }

  // Nothing to precompute: the springs are in Model::spring_hinges like any other.
  template <Sizes S>
  static InitStatus init(const ModelSpec<S>&, Model<S>&, InitWorkspace<S>&) {
    return {};
  }

  // Every DOF is uncoupled: the residual pass divides by the lumped mass (S 3-4).
  template <Sizes S>
  static void residual(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
    detail::residual(m, s, w, m.inv_mass.data(), w.a.data());
  }
  template <Sizes S>
  static void couple(const Model<S>&, const State<S>&, Scratch<S>&) {}

  template <Sizes S>
  static void stops(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    clamp_stops(m, s, w);
  }
  // start(): the stops' forces (the momentum clamp's).
  template <Sizes S>
  static void start_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    clamp_start_forces(m, s, w);
  }
  template <Sizes S>
  static void project(const Model<S>&, State<S>&, Scratch<S>&) {}
  template <Sizes S>
  static void project_initial(const Model<S>&, State<S>&) {}

  // No direction is held by a constraint (HingeData::rigid is empty), so no caller asks.
  template <Sizes S>
  static double constraint_force(const Model<S>&, const State<S>&, Scratch<S>&, int, int, int&) {
    return 0.0;
  }
};

}  // namespace ntn
