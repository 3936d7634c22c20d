// Model<S>: everything constant during a run, built once by init() (DESIGN §2).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "ntn/beam.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/corotational.hpp"
#include "ntn/dof_pass.hpp"
#include "ntn/element_order.hpp"
#include "ntn/element_pass.hpp"
#include "ntn/geometry.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/hysteresis.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/status.hpp"
#include "ntn/time_step.hpp"

namespace ntn {

template <Sizes S>
struct Model : SizesOf<S> {
  static constexpr Sizes kSizes = S;
  static constexpr std::size_t kDofs = kDofsPerNode * S.nodes;

  // The elements, kBeamLanes to a block in the model's order (element_order.hpp), their
  // rotations block by block and the stiffness table, num_stiffness distinct entries that the
  // blocks share (element_pass.hpp): beam(e) is element e of the model file.
  Array<BeamBlock, S, beam_blocks(S.elements)> beams{};
  Array<BeamRotations, S, beam_blocks(S.elements)> rotations{};
  Array<BeamStiffnessBlock, S, beam_blocks(S.elements)> stiffness{};
  std::size_t num_stiffness = 0;
  // Every node has an element end, so the SIMD element pass writes each node's first end instead
  // of zeroing F first (BeamBlock::first, mark_first_ends).
  bool every_node_in_element = false;
  // Element e of the file -> its place k in the model's order (block k / kBeamLanes, lane
  // k % kBeamLanes).
  Array<std::int32_t, S, S.elements> element_slot{};
  // The elements with second-order geometry (p_delta, leaning columns), in element order: what
  // the step adds after the element pass (geometry.hpp).
  Array<GeometricElement, S, S.geometric> geometric{};
  // The same elements kBeamLanes to a block, and their rotations: what the SIMD pass reads.
  Array<GeometricBlock, S, beam_blocks(S.geometric)> geometric_blocks{};
  Array<BeamRotations, S, beam_blocks(S.geometric)> geometric_rotations{};
  // The corotational elements, in element order: their force is the corotational stage's, the
  // element pass gives them none (their stiffness there is zero).
  Array<CorotationalElement, S, S.corotational> corotational{};
  Array<double, S, kDofs> mass{};  // kg or kg m^2, lumped (HRZ) plus point masses
  // 1/m of the accelerations a_n = (R_n - C v) / m (S 3-4): 1/mass, or under ntn_paper 1 over
  // the hinge-summed mass (S 22-26), times 1 / mass_factor (below); 0 at supported DOFs (which stay
  // at zero), tree DOFs (ntn_exact: the forest gives them) and mechanism DOFs (held at zero).
  Array<double, S, kDofs> inv_mass{};
  // mass and inv_mass again by groups of kMassGroup nodes, equal groups sharing an entry
  // (dof_pass.hpp): what the SIMD DOF pass reads.
  Array<MassBlock, S, mass_groups(S.nodes)> mass_table{};
  Array<std::int32_t, S, mass_groups(S.nodes)> mass_entry{};
  std::size_t num_mass_entries = 0;
  Array<double, S, kDofs> damping{};  // N s/m, diagonal C = alpha M (S 1)
  double alpha = 0;  // 1/s: damping[j] is alpha * mass[j], which the residual pass recomputes
  double beta = 0;   // s: stiffness-proportional damping beta K_el, in the element pass
  // Settings::damping_velocity. "central": alpha M acts at v_n, so a_n solves
  // (M + alpha M dt/2) a_n = R_n - alpha M v_{n-1/2}: every stage that divides by the mass
  // (inv_mass, the forest, the clamp and the slips) takes the step mass M_e = mass_factor M,
  // mass_factor = 1 + alpha dt/2 (1 when lagged); `mass` and `damping` stay M and alpha M.
  DampingVelocity damping_velocity = DampingVelocity::kCentral;
  double mass_factor = 1;
  // The run's initial state u_0, v_0 (NodeSpec::u0, v0; zero by default): initial_state() puts
  // it in a State before start().
  Array<double, S, kDofs> u0{};
  Array<double, S, kDofs> v0{};
  Array<std::uint8_t, S, S.nodes> fixed{};            // support bits per node (bit d: DOF d)
  Array<std::int32_t, S, S.nodes> supported_nodes{};  // nodes with any fixed DOF, ascending
  int num_supported = 0;

  Array<TimePoint, S, S.time_points> time_points{};
  Array<TimeFunctionSpec, S, S.time_functions> time_functions{};
  Array<LoadSpec, S, S.loads> loads{};
  Array<ElementLoadSpec, S, S.element_loads> element_loads{};  // for the element-force outputs
  Array<HysteresisData, S, S.hystereses> hystereses{};         // kPlastic directions, by slot
  // The DOFs that carry a nodal load or a force input ("load slots"), each once: only there does
  // P_n differ from M g (gravity and base excitation), which the residual pass computes on the fly.
  Array<std::int32_t, S, S.loads + S.inputs> slot_dof{};  // slot -> its DOF
  Array<std::int32_t, S, S.loads> load_slot{};            // nodal load -> its slot
  Array<std::int32_t, S, S.inputs> input_slot{};          // force input -> its slot, else -1
  int num_slots = 0;
  Array<InputSpec, S, S.inputs> inputs{};
  Array<OutputSpec, S, S.outputs> outputs{};
  std::array<double, 3> gravity{};  // m/s^2
  int gravity_function = kConstant;

  double dt = 0;  // s, the fixed step
  StableStepReport stable;

  // Hinges (DESIGN §7). Per-node arrays exist only in models with hinges.
  static constexpr std::size_t kHingeNodes = S.hinges > 0 ? S.nodes : 0;
  Array<HingeData, S, S.hinges> hinges{};
  Array<CurvePoint, S, S.curve_points> curve_points{};
  Array<ForestEdge, S, S.hinges> edges{};  // ntn_exact: rigid trees, parents before children
  Array<ForestEdgeMatrices, S, S.hinges> edge_matrices{};  // ntn_exact: each edge's matrices
  Array<ForestRoot, S, S.hinges> roots{};           // ntn_exact: trees not rooted at the ground
  Array<std::int32_t, S, S.hinges> hinge_edge{};    // hinge -> its forest edge, or -1
  Array<std::int32_t, S, kHingeNodes> node_tree{};  // node -> its rigid tree, or -1
  Array<std::uint8_t, S, kHingeNodes> held{};       // mechanism DOFs held at zero (bits)
  // ntn_exact: what the residual pass multiplies R_n by, per DOF: inv_mass outside the trees, 1
  // in a tree (the forest turns those R into accelerations in place; ntn_exact.hpp).
  Array<double, S, kDofsPerNode * kHingeNodes> residual_scale{};
  Array<std::int32_t, S, S.hinges> spring_hinges{};  // hinges with a spring or dashpot
  Array<std::int32_t, S, S.hinges> branch_hinges{};  // hinges with a rigid branch (a stop)
  Array<std::int32_t, S, S.hinges> project_edges{};  // ntn_exact: edges the step re-projects
  Array<ForestTree, S, S.hinges> trees{};            // ntn_exact: edge range and root per tree
  // ntn_exact: the stop hinges (indices into branch_hinges) whose two nodes lie in one tree,
  // tree by tree (ForestTree::first_stop, end_stop).
  Array<std::int32_t, S, S.hinges> tree_stops{};
  Array<std::int32_t, S, S.hinges> slip_hinges{};  // ntn_exact: hinges with a slip direction
  // ntn_exact: W_ij = b_i^T M_c^-1 b_j between the slip directions of each rigid tree, row by
  // row in the slip stage's order (slip.hpp, init_slip_mobility): constant, so built at init.
  Array<double, S, S.hystereses * kSlipBlock> slip_mobility{};
  // ntn_exact: the L D L^T of each tree's W with every direction sticking, in the same rows
  // (slip.hpp's ldl_factor; 0 in a tree's first entry when W is singular).
  Array<double, S, S.hystereses * kSlipBlock> slip_factor{};
  int num_edges = 0;
  int num_roots = 0;
  int num_spring_hinges = 0;
  int num_branch_hinges = 0;
  int num_project_edges = 0;
  int num_trees = 0;
  int num_slip_hinges = 0;
  int num_slip_normals = 0;    // slip directions whose limit follows another's force
  int held_dofs = 0;           // DOFs held at zero as mechanisms (no mass, no stiffness)
  HingeMethod hinge_method{};  // Settings::hinge_method (hinge_methods.hpp picks the method)
  ClampRule clamp = ClampRule::kMomentum;
  double inv_dt = 0;  // 1/s
  // Kernel steps per I/O frame, N = frame_period / dt by the frame rule (frame_substeps), stored
  // once at init: every driver and test reads N here (count 0 and the reason when dt does not
  // divide the frame; the model compiler refuses such a model).
  Substeps substeps;
  // The element pass's path: the SIMD one where the build has it (the same bits as the scalar
  // reference, element_pass.hpp). Not part of the model file: a driver or a test may switch it.
  ElementPass element_pass = ElementPass::kSimd;
  // The step's energy books over the DOFs into Scratch::books (books.hpp): off unless a driver
  // asks for them (hil::EnergyBalance::begin turns them on); the state's bits are the same
  // either way.
  bool books = false;

  std::size_t dofs() const { return kDofsPerNode * this->sizes.nodes; }  // kDofs, in any storage

  BeamArrays beam_arrays() const { return {beams.data(), rotations.data(), stiffness.data()}; }

  BeamData beam(std::size_t e) const {
    const auto k = static_cast<std::size_t>(element_slot[e]);
    return lane(beam_arrays(), k / kBeamLanes, k % kBeamLanes);
  }
};

// What init() works in and then drops: kept out of the constant Model.
template <Sizes S>
struct InitWorkspace : SizesOf<S> {
  // The mass the accelerations divide by, before init() inverts it into Model::inv_mass: the
  // lumped mass times Model::mass_factor (the forest is built from it), or the hinge-summed one
  // (ntn_paper, S 22-26).
  Array<double, S, Model<S>::kDofs> divided_mass{};
  Array<ForestWork, S, S.hinges> forest{};  // ntn_exact: build_forest's, one per hinge
  // ntn_exact with slip directions: an impulse along one and the trees' response to it, for
  // Model::slip_mobility (init_slip_mobility, slip.hpp).
  Array<double, S, (S.hystereses > 0 ? Model<S>::kDofs : 0)> slip_impulse{};
  Array<double, S, (S.hystereses > 0 ? Model<S>::kDofs : 0)> slip_response{};
  Array<std::uint8_t, S, S.hystereses> slot_used{};  // check_references: each slot used once
  // The element order's (element_order.hpp): each element's nodes and AxisMap, and the order.
  Array<OrderElement, S, S.elements> order_elements{};
  Array<std::int32_t, S, S.elements> order{};
  Array<std::uint8_t, S, S.nodes> touched{};  // mark_first_ends: nodes met so far
};

}  // namespace ntn
