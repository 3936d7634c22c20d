// Figures about a loaded model for people: masses, time step, sizes (used by ntn-model info).
#pragma once

#include <array>
#include <string>

#include "ntn/modelc/model_description.hpp"

namespace ntn::modelc {

struct MassTotals {
  std::array<double, 6> all{};   // sum over nodes per DOF direction: kg (ux,uy,uz), kg m^2
  std::array<double, 6> free{};  // the same over free (unsupported) DOFs only
  double elements = 0;           // kg, translational mass of the elements (sum of rho A l)
  double point_masses = 0;       // kg, sum of point masses
  int free_dofs = 0;
};

// From the kernel's own lumped mass (ntn::assemble_lumped_mass), summed in node order.
MassTotals mass_totals(const ModelDescription& model);

// The kernel's stable step report of the same model with another hinge method (the
// ntn_exact / penalty ratio).
StableStepReport stable_step_with(const ModelDescription& model, HingeMethod method);

// The multi-line text that `ntn-model info` prints.
std::string info_text(const ModelDescription& model);

}  // namespace ntn::modelc
