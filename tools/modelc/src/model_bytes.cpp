// Memory of Model<S> + State<S> + Scratch<S> for sizes known at run time: the kernel's own
// footprint functions (kernel/include/ntn/footprint.hpp, checked against sizeof when they build),
// plus the marginal figures per element, node and hinge that ntn-model prints.
#include "ntn/modelc/model_bytes.hpp"

#include <cstdint>

#include "ntn/beam.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/dof_pass.hpp"
#include "ntn/footprint.hpp"
#include "ntn/hinge.hpp"

namespace ntn::modelc {

MemoryFootprint memory_footprint(const Sizes& s) {
  MemoryFootprint f;
  f.model = model_footprint(s);
  f.state = state_footprint(s);
  f.scratch = scratch_footprint(s);
  f.total = f.model + f.state + f.scratch;
  // A block of kBeamLanes elements, its rotations and its entry of the stiffness table (the
  // capacity: every block may have a stiffness of its own), per element, and the element's slot
  // (Model::element_slot).
  f.per_element =
      (sizeof(BeamBlock) + sizeof(BeamRotations) + sizeof(BeamStiffnessBlock)) / kBeamLanes +
      sizeof(std::int32_t);
  // Per node: 6 DOFs x 9 per-DOF double arrays (Model: mass, inv_mass, damping, u0, v0; State:
  // u, v; Scratch: f, a), plus Model::fixed (1 byte) and Model::supported_nodes (4 bytes), and
  // its share of the mass table's capacity (Model::mass_table, mass_entry: one entry per group of
  // kMassGroup nodes) and of the energy books' group sums (Scratch::group_books, one per
  // kBookNodes nodes).
  f.per_node = kDofsPerNode * 9 * sizeof(double) + sizeof(std::uint8_t) + sizeof(std::int32_t) +
               (sizeof(MassBlock) + sizeof(std::int32_t)) / kMassGroup +
               sizeof(GroupBooks) / kBookNodes;
  // Per hinge: its data, its forest slots (edge, root, hinge -> edge), its places in the lists
  // of hinges with springs, with branches, of projected edges, of the trees' stops and with slip
  // directions, a tree slot (a forest has at most one tree per hinge), its clamp check mark and
  // its six stop forces and six dashpot forces (Scratch).
  f.per_hinge = sizeof(HingeData) + sizeof(ForestEdge) + sizeof(ForestEdgeMatrices) +
                sizeof(ForestRoot) + 6 * sizeof(std::int32_t) + sizeof(ForestTree) +
                sizeof(std::int64_t) + 2 * kDofsPerNode * sizeof(double);
  // A model with hinges also has per node a tree index and mechanism bits (Model::node_tree,
  // held), the residual scale of its 6 DOFs (Model::residual_scale), their coupled force
  // (Scratch::r), the clamp's impulse, response and the start's u_0 (Scratch::clamp) and its
  // clamp move mark.
  f.per_node_with_hinges = sizeof(std::int32_t) + sizeof(std::uint8_t) +
                           5 * kDofsPerNode * sizeof(double) + sizeof(std::int64_t);
  f.per_curve_point = sizeof(CurvePoint);
  return f;
}

std::size_t model_bytes(const Sizes& s) {
  return memory_footprint(s).total;
}

}  // namespace ntn::modelc
