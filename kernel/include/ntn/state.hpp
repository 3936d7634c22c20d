// State<S>: what a replay must restore. Scratch<S>: recomputed every step, never saved.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ntn/dof_pass.hpp"
#include "ntn/laws/law.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/rotation.hpp"

namespace ntn {

// The six DOFs of one node in a per-DOF array (u, v, a, F, R ...), in DOF order (DESIGN §3).
using NodeBlock = std::span<double, kDofsPerNode>;
using ConstNodeBlock = std::span<const double, kDofsPerNode>;

template <std::size_t N>
NodeBlock node_block(std::array<double, N>& x, int node) {
  return NodeBlock(x.data() + kDofsPerNode * node, kDofsPerNode);
}
template <std::size_t N>
ConstNodeBlock node_block(const std::array<double, N>& x, int node) {
  return ConstNodeBlock(x.data() + kDofsPerNode * node, kDofsPerNode);
}
inline NodeBlock node_block(Slice<double>& x, int node) {
  return NodeBlock(x.data() + kDofsPerNode * node, kDofsPerNode);
}
inline ConstNodeBlock node_block(const Slice<double>& x, int node) {
  return ConstNodeBlock(x.data() + kDofsPerNode * node, kDofsPerNode);
}

template <Sizes S>
struct State : SizesOf<S> {
  static constexpr std::size_t kDofs = kDofsPerNode * S.nodes;
  Array<double, S, kDofs> u{};               // m, rad: displacements u_n relative to the ground
  Array<double, S, kDofs> v{};               // m/s, rad/s: v_{n-1/2} once started (S 5-6)
  Array<double, S, S.inputs> held_inputs{};  // last accepted value of each input channel
  std::int64_t tick = 0;                     // step counter: t_n = tick * dt, never summed
  std::uint64_t inputs_held = 0;             // non-finite inputs replaced by the held value
  std::uint64_t inputs_out_of_range = 0;     // inputs outside [min, max], held likewise
  std::uint32_t faults = 0;                  // Fault bits, sticky
  // Element-steps past the stable step's bound of second-order geometry (geometry.hpp).
  std::uint64_t geometry_bound = 0;
  // The history of the hysteretic hinge directions (kPlastic, hysteresis.hpp), by slot
  // (HingeSpec::hysteresis): plastic deformation d_p (m or rad: the force is k (d - d_p)) and
  // energy dissipated (J).
  Array<double, S, S.hystereses> plastic{};
  Array<double, S, S.hystereses> dissipated{};
  Array<double, S, S.hystereses> plastic_peak{};  // the largest |d_p| so far
  // Each law's own history values (laws/law.hpp; the law's header names them: the backbone's
  // excursions and reloading anchors, the brittle direction's broken flag, ...).
  Array<LawState, S, S.hystereses> law_state{};
  // Rigid-plastic and brittle directions (slip.hpp, brittle.hpp): 1 + the tick of the step in
  // which the direction first slid or broke (0: never); a `failure` direction has broken from
  // then on.
  Array<std::int64_t, S, S.hystereses> first_slip{};
  // Rigid-plastic directions under ntn_exact (slip.hpp): how the last step left each one: 0
  // stuck, +1 / -1 at its limit in the positive / negative sense (sliding), 2 free (broken, or
  // a fixed_if released). The next step's solve starts from it.
  Array<std::int8_t, S, S.hystereses> slip_state{};
  // In a model with corotational elements, each node's total rotation Q_n from the reference
  // (corotational.hpp), updated multiplicatively with the step's spin, q_{n+1} = exp(dt w) q_n;
  // the rotational DOFs of u hold the spins' sum, w dt over the steps.
  Array<Quaternion, S, (S.corotational > 0 ? S.nodes : 0)> rotation{};
};

// The momentum clamp's workspace (clamp.hpp, DESIGN §7.1), in models with hinges: an impulse b
// along a stop direction and the constrained system's response M_c^-1 b to it, over the nodes of
// the parts that respond, and the bookkeeping that lets a sweep skip the stops nothing moved.
template <Sizes S>
struct ClampWork {
  static constexpr std::size_t kDofs = S.hinges > 0 ? kDofsPerNode* S.nodes : 0;
  // written by clamp_response (b, then the forest's upward pass in place), read by it
  Array<double, S, kDofs> impulse{};
  // written by clamp_response (M_c^-1 b), read by clamp_projection and clamp_move
  Array<double, S, kDofs> response{};
  // Event counts, not state (only their order within a step counts): when each node was last
  // moved by a clamp (written by clamp_move), when each stop hinge was last looked at (written
  // by the sweeps; index into Model::branch_hinges); both read by clamp_due.
  Array<std::int64_t, S, (S.hinges > 0 ? S.nodes : 0)> moved{};
  Array<std::int64_t, S, S.hinges> checked{};
  std::int64_t events = 0;
  // `events` when the step's constraint stages began (the stops, the slip stage, the
  // projection, which all mark the nodes they move in `moved`): a node with moved > step_events
  // was moved this step, and its velocity and acceleration channels are taken after them.
  std::int64_t step_events = 0;
  // The time weights of a move (clamp_move, the slip solves): a force f on a direction at t_n
  // moves u_{n+1} by du = -f h2 M_c^-1 b, which changes v by du v_rate and a_n by du / dt^2
  // times a_scale. A step: dt^2, 1/dt, 1 (set by the stops stage). start(): the forces at t_0
  // from a trial u_1 = u_0 + dt v_0 + dt^2/2 a_0, so dt^2/2, 0 and 2 (a_0 takes the forces,
  // v_0 stays).
  double h2 = 0;
  double v_rate = 0;
  double a_scale = 1;
  // u_0 while start() runs the trial (written and read by start() alone).
  Array<double, S, kDofs> start_u{};
};

// Each field: what it holds, the stage that writes it and the stages that read it (the stages
// of step(), integrator.hpp).
template <Sizes S>
struct Scratch : SizesOf<S> {
  static constexpr std::size_t kDofs = kDofsPerNode * S.nodes;
  // External load P_n (DESIGN §5): M g at every DOF (load_g per DOF direction, computed in the
  // residual pass), except at the model's load slots, whose P_n is here (external_load()).
  // load_g, p_slot: written by loads, read by the residual stage, hinge-force and reaction
  // outputs (external_load).
  std::array<double, kDofsPerNode> load_g{};      // m/s^2: gravity - a_g on x, y, z; 0, 0, 0
  Array<double, S, S.loads + S.inputs> p_slot{};  // N or N m, P_n at Model::slot_dof
  // Internal force F_n: written by element forces and hinge springs, read by the residual stage
  // and the reaction and hinge-force outputs.
  Array<double, S, kDofs> f{};
  // The second-order chord forces (geometry.hpp) on the SIMD path: each element's g in global axes,
  // (g_x, g_y, g_z, 0.0) in Model::geometric's order, written by the lanes (which take the
  // elements in the model's order) and added to F from here (geometric_stage).
  Array<double, S, 4 * S.geometric> geometric_rows{};
  // Acceleration a_n: written by the residual stage (a_n at DOFs no hinge couples) and the NTN
  // coupling stage (the coupled DOFs), read by outputs and the update; the stops and the
  // constraint projection add their S 35-37 increments. A model without hinges: written at the
  // outputs' DOFs before the outputs (output_accelerations), then everywhere, with the same
  // values, by the fused DOF pass (residual_update). Between the residual and the coupling
  // stage its storage is the coupling's input, coupling_input() (ntn_exact: R_n - C v at tree
  // DOFs), never read as `a`.
  Array<double, S, kDofs> a{};
  // The coupled R_n - C v (models with hinges): ntn_paper's at every DOF, written by its
  // residual and coupling stages (S 17-21) and read by them; ntn_exact's of one rigid tree,
  // written and read by the hinge-force output of that tree (forest_hinge_force).
  Array<double, S, (S.hinges > 0 ? kDofs : 0)> r{};
  Array<double, S, S.outputs> outputs{};  // channels at t_n: written by outputs (a slip direction's
                                          // force by the slip stage), read by the caller
  // N or N m, by history slot: the force of each rigid-plastic direction at t_n (the slip
  // stage's, slip.hpp; 0 for the other slots): written by the slip stage, read by it and by the
  // hinge-force outputs it then writes.
  Array<double, S, S.hystereses> slip_force{};
  // N or N m, by history slot: a friction direction's normal force N at t_n (slip.hpp): written
  // by the slip-normal stage (after the coupling), read by the slip stage.
  Array<double, S, S.hystereses> slip_normal{};
  // N or N m, by hinge and direction: the force of each stop (a rigid branch under the momentum
  // clamp) at t_n, on node 1 in the hinge frame like a spring's: the clamp's impulse over dt
  // (a move du = -f dt^2 M_c^-1 b). Written by the stops stage (0 where no stop acts), read by
  // the hinge-force and reaction outputs after it.
  Array<std::array<double, kDofsPerNode>, S, S.hinges> stop_force{};
  // The energy books (books.hpp, Model::books on): each book group's sums, written by the DOF
  // pass (a model without hinges) or the books stage after the constraint stages, and the step's
  // totals from them, written last in the step and read by the caller.
  Array<GroupBooks, S, book_groups(S.nodes)> group_books{};
  StepBooks books{};
  // N or N m, by hinge and direction: with damping_velocity = "central", what a dashpot's force
  // adds to c d_dot_{n-1/2} for the relative velocity at t_n (dashpot.hpp; 0 elsewhere and in
  // start()). Written by the dashpot stage (after the coupling), read by the hinge-force and
  // reaction outputs.
  Array<std::array<double, kDofsPerNode>, S, S.hinges> dashpot_force{};
  ClampWork<S> clamp;              // the momentum clamp's (the stops stage)
  std::array<double, 3> ground{};  // m/s^2, a_g at t_n (x, y, z): written by loads, read by outputs
  double time = 0;                 // s, t_n of `outputs`: written by outputs, read by the caller

  // The residual stage's output where the NTN coupling finishes it in place (ntn_exact): the
  // storage of `a`, holding R_n - C v_{n-1/2} at the DOFs of rigid trees (a_n elsewhere) until
  // the coupling stage has turned them into a_n. A name of its own, so that `a` always means a_n.
  std::span<double, S.runtime ? std::dynamic_extent : kDofs> coupling_input() {
    return std::span < double, S.runtime ? std::dynamic_extent : kDofs > (a);
  }
};

}  // namespace ntn
