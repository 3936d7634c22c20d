// State<S>: what a replay must restore. Scratch<S>: recomputed every step, never saved.
#pragma once

#include <array>
#include <cstdint>

#include "ntn/model_spec.hpp"

namespace ntn {

template <Sizes S>
struct State {
  static constexpr int kDofs = kDofsPerNode * S.nodes;
  std::array<double, kDofs> u{};               // m, rad: displacements u_n relative to the ground
  std::array<double, kDofs> v{};               // m/s, rad/s: v_{n-1/2} once started (S 5-6)
  std::array<double, S.inputs> held_inputs{};  // last accepted value of each input channel
  std::int64_t tick = 0;                       // step counter: t_n = tick * dt, never summed
  std::uint64_t inputs_held = 0;               // non-finite inputs replaced by the held value
  std::uint64_t inputs_out_of_range = 0;       // inputs outside [min, max], held likewise
  std::uint32_t faults = 0;                    // Fault bits, sticky
};

template <Sizes S>
struct Scratch {
  static constexpr int kDofs = kDofsPerNode * S.nodes;
  // External load P_n (DESIGN §5): M g at every DOF (load_g per DOF direction, computed in the
  // residual pass), except at the model's load slots, whose P_n is here (external_load()).
  std::array<double, kDofsPerNode> load_g{};           // m/s^2: gravity - a_g on x, y, z; 0, 0, 0
  std::array<double, S.loads + S.inputs> p_slot{};     // N or N m, P_n at Model::slot_dof
  std::array<double, kDofs> f{};                       // internal force F_n
  std::array<double, kDofs> a{};                       // acceleration a_n
  std::array<double, (S.hinges > 0 ? kDofs : 0)> r{};  // R_n - C v, coupled (models with hinges)
  std::array<double, S.outputs> outputs{};             // output channels at t_n
  // Momentum clamp bookkeeping (integrator.hpp): the event count when each node was last moved
  // by a clamp and when each stop hinge was last checked; only their order within a step counts.
  std::array<std::int64_t, (S.hinges > 0 ? S.nodes : 0)> clamp_moved{};
  std::array<std::int64_t, S.hinges> clamp_checked{};
  std::int64_t clamp_events = 0;
  std::array<double, 3> ground{};  // m/s^2, ground acceleration a_g at t_n (x, y, z)
  double time = 0;                 // s, t_n of `outputs`
};

}  // namespace ntn
