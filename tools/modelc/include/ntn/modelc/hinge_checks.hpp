// Model-level checks of NTN hinges (DESIGN §7, §7.1) that need the whole model: cycles of rigid
// connections, and DOFs without effective mass (mechanisms, or massless springs).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "ntn/model_spec.hpp"
#include "ntn/modelc/model_description.hpp"

namespace ntn::modelc {

// A hinge whose rigid directions close a cycle, by the kernel's rule (ntn::for_each_rigid_cycle,
// constraint_forest.hpp) with every hinge that declares a rigid direction: one entry per closing
// hinge, in hinge order.
struct RigidCycle {
  int hinge = 0;
  std::vector<int> nodes;  // the cycle from the hinge's node 1 to its node 2 (kGround: ground)
};
std::vector<RigidCycle> rigid_cycles(const SpecView& spec);

// A set of DOFs of one node (bits as NodeSpec::fixed, global axes) that has no effective mass.
struct MassProblem {
  int node = 0;
  std::uint8_t dofs = 0;
  bool penalty = false;  // a penalty spring (a rigid direction under hinge_method = "penalty")
                         // acts there
};

struct MassCheck {
  std::vector<Mechanism> mechanisms;  // zero effective mass, no stiffness: held at zero
  std::vector<MassProblem> springs;   // zero effective mass with a spring or dashpot: an error
};

// The effective mass with the hinge constraints applied exactly (config/README.md, "Mass and
// mechanisms"). Motions of zero kinetic energy move only DOFs whose lumped mass (`mass`, per
// DOF as ntn::assemble_lumped_mass) is zero; among those, the ones the rigid hinge directions
// allow (ntn_exact, ntn_paper: rigid rows of B are constraints; penalty: they are springs) and no
// spring, dashpot or curve resists are mechanisms, the others are errors.
MassCheck hinge_mass_check(const SpecView& spec, std::span<const double> mass);

}  // namespace ntn::modelc
