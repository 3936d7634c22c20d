// Damped dynamic relaxation with the kernel itself: run ntn::step with mass-proportional damping
// until the structure is at rest under its (constant) loads. No heap, no exceptions.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "ntn/integrator.hpp"

namespace ntn_test {

struct RelaxationResult {
  bool converged = false;
  std::int64_t steps = 0;
  double residual = 0;  // ||P - F|| / ||P|| over free DOFs at the last step
  double motion = 0;    // sqrt(sum m v^2 / sum P u): kinetic energy against the work of the loads
  ntn::StepStatus status = ntn::StepStatus::kOk;
};

// Out-of-balance measures after a step: w holds P_n and F_n, s holds u_{n+1} and v_{n+1/2}.
template <ntn::Sizes S>
void relaxation_measures(const ntn::Model<S>& m, const ntn::State<S>& s, const ntn::Scratch<S>& w,
                         double& residual, double& motion) {
  double rr = 0, pp = 0, kin = 0, work = 0;
  for (std::size_t j = 0; j < ntn::Model<S>::kDofs; ++j) {
    if (m.inv_mass[j] == 0.0) continue;  // supported DOF: its residual is the reaction
    const double p = ntn::external_load(m, w, j);
    const double r = p - w.f[j];
    rr += r * r;
    pp += p * p;
    kin += m.mass[j] * s.v[j] * s.v[j];
    work += p * s.u[j];
  }
  residual = pp > 0 ? std::sqrt(rr / pp) : std::sqrt(rr);
  motion = work > 0 ? std::sqrt(kin / work) : std::sqrt(kin);
}

// Starts from the state's u, v (usually zero) and steps until both measures are below
// `tolerance`, or `max_steps` have run (then converged = false). The convergence is measured,
// not assumed: the step count is whatever the damping needs.
template <ntn::Sizes S>
RelaxationResult relax(const ntn::Model<S>& m, ntn::State<S>& s, ntn::Scratch<S>& w,
                       double tolerance, std::int64_t max_steps,
                       const std::array<double, S.inputs>& in = {}) {
  RelaxationResult r;
  r.status = ntn::start(m, s, w, in);
  if (r.status == ntn::StepStatus::kDiverged) return r;
  while (r.steps < max_steps) {
    r.status = ntn::step(m, s, w, in);
    ++r.steps;
    if (r.status == ntn::StepStatus::kDiverged) return r;
    relaxation_measures(m, s, w, r.residual, r.motion);
    if (r.residual < tolerance && r.motion < tolerance) {
      r.converged = true;
      break;
    }
  }
  return r;
}

// The same for models with hinges, where a node's own P - F is not its out-of-balance force (a
// rigid hinge direction carries a constraint force, and ntn_exact's tree nodes have no inverse
// mass of their own): the residual is the inertia force of the coupled accelerations,
// ||M a_n|| / ||P|| over the DOFs without a support, and the motion measure takes every DOF's
// lumped mass. At rest under constant loads both vanish whatever the hinge method.
template <ntn::Sizes S>
void hinged_relaxation_measures(const ntn::Model<S>& m, const ntn::State<S>& s,
                                const ntn::Scratch<S>& w, double& residual, double& motion) {
  double rr = 0, pp = 0, kin = 0, work = 0;
  for (std::size_t j = 0; j < ntn::Model<S>::kDofs; ++j) {
    if ((m.fixed[j / ntn::kDofsPerNode] >> (j % ntn::kDofsPerNode)) & 1U) continue;
    const double r = m.mass[j] * w.a[j];
    const double p = ntn::external_load(m, w, j);
    rr += r * r;
    pp += p * p;
    kin += m.mass[j] * s.v[j] * s.v[j];
    work += p * s.u[j];
  }
  residual = pp > 0 ? std::sqrt(rr / pp) : std::sqrt(rr);
  motion = work > 0 ? std::sqrt(kin / work) : std::sqrt(kin);
}

template <ntn::Sizes S>
RelaxationResult relax_hinged(const ntn::Model<S>& m, ntn::State<S>& s, ntn::Scratch<S>& w,
                              double tolerance, std::int64_t max_steps,
                              const std::array<double, S.inputs>& in = {}) {
  RelaxationResult r;
  r.status = ntn::start(m, s, w, in);
  if (r.status == ntn::StepStatus::kDiverged) return r;
  while (r.steps < max_steps) {
    r.status = ntn::step(m, s, w, in);
    ++r.steps;
    if (r.status == ntn::StepStatus::kDiverged) return r;
    hinged_relaxation_measures(m, s, w, r.residual, r.motion);
    if (r.residual < tolerance && r.motion < tolerance) {
      r.converged = true;
      break;
    }
  }
  return r;
}

}  // namespace ntn_test
