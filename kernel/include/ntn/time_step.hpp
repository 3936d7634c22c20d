// Stable time step of the central difference method (DESIGN §6, seed S 9-10).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "ntn/beam.hpp"
#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

// Largest circular frequency of one free element: omega_e^2 = lambda_max(M_e^-1 K_e), with the
// element's own lumped mass in global axes (the same mass that is assembled). By the element
// eigenvalue theorem max_e omega_e bounds the assembled model's omega_max: added point masses
// and supports only lower it. Returns 0 for an invalid element.
inline double element_omega_max(const ElementSpec& e, const NodeSpec& a, const NodeSpec& b,
                                bool rotary_inertia) {
  const BeamGeometry g = beam_geometry(a, b, e);
  if (g.check != ElementCheck::kOk || !beam_properties_valid(e)) return 0;
  BeamData data;
  data.rotation = g.rotation;
  data.k = beam_stiffness(e, g.length);
  const Matrix12 K = beam_global_stiffness(data);
  const auto m = beam_end_mass(e, g, rotary_inertia);
  Eigen::Matrix<double, 12, 12> A;  // M^-1/2 K M^-1/2, symmetric
  for (int r = 0; r < 12; ++r) {
    for (int c = 0; c < 12; ++c) {
      const double mr = m[static_cast<std::size_t>(r % 6)], mc = m[static_cast<std::size_t>(c % 6)];
      A(r, c) = K[static_cast<std::size_t>(r * 12 + c)] / std::sqrt(mr * mc);
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(A, Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return 0;
  return std::sqrt(eig.eigenvalues().maxCoeff());
}

// Delta t_stable = (2 / omega)(sqrt(1 + xi^2) - xi), xi = alpha / (2 omega) for C = alpha M.
// The same bound holds with the damping velocity lagged to n - 1/2 as in (S 3).
inline double damped_stable_step(double omega, double alpha) {
  if (!(omega > 0)) return 0;
  const double xi = alpha / (2.0 * omega);
  return 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
}

struct StableStepReport {
  double dt_stable = 0;        // s, from the element eigenvalue bound with damping
  double omega_max = 0;        // rad/s, max over elements of omega_e
  int governing_element = -1;  // element that sets omega_max
  double dt_cfl = 0;           // s, the seed's estimate min_e l / sqrt(E / rho) (S 9-10)
  int cfl_element = -1;        // element that sets dt_cfl
  double dt_elements = 0;      // s, the elements' bound alone
  double dt_hinges = 1e300;    // s, the hinges' two-node springs alone (1e300: none)
  int governing_hinge = -1;    // hinge that sets dt_stable, or -1 when an element does
  int hinge_direction = -1;    // its local direction 0..5
};

inline StableStepReport stable_time_step(const SpecView& spec) {
  StableStepReport r;
  const bool rot = spec.settings.rotary_inertia;
  for (std::size_t i = 0; i < spec.elements.size(); ++i) {
    const ElementSpec& e = spec.elements[i];
    const NodeSpec& a = spec.nodes[static_cast<std::size_t>(e.node_i)];
    const NodeSpec& b = spec.nodes[static_cast<std::size_t>(e.node_j)];
    const double w = element_omega_max(e, a, b, rot);
    if (w > r.omega_max) r.omega_max = w, r.governing_element = static_cast<int>(i);
    const BeamGeometry g = beam_geometry(a, b, e);
    if (g.check == ElementCheck::kOk && e.E > 0 && e.rho > 0) {
      const double cfl = g.length / std::sqrt(e.E / e.rho);
      if (r.cfl_element < 0 || cfl < r.dt_cfl) r.dt_cfl = cfl, r.cfl_element = static_cast<int>(i);
    }
  }
  r.dt_stable = damped_stable_step(r.omega_max, spec.settings.alpha);
  r.dt_elements = r.dt_stable;
  return r;
}

// The same with the hinges' springs (DESIGN §6): each spring direction (linear, curve, or a
// rigid direction under `penalty`) of hinge stiffness k and dashpot c is a two-node oscillator
// with omega^2 = k w, w = b^T M^-1 b over both nodes (w = 1/m1 + 1/m2 for an aligned, centric
// hinge), and step 2/omega (sqrt(1 + xi^2) - xi), xi = c w / (2 omega); a pure dashpot needs
// dt < 2 / (c w). Rigid NTN directions add no stiffness. `mass` is the lumped mass per DOF.
// This is the seed's per-spring estimate, not a strict bound where springs and elements are
// of similar stiffness; dt = "auto" keeps 10 % of margin.
inline StableStepReport stable_time_step(const SpecView& spec, std::span<const double> mass) {
  StableStepReport r = stable_time_step(spec);
  const int nodes = static_cast<int>(spec.nodes.size());
  for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
    HingeData h;
    if (!make_hinge_data(spec.hinges[i], spec.settings, nodes, spec.curves, spec.curve_points, h))
      continue;
    const double* m1 = mass.data() + kDofsPerNode * h.node1;
    const double* m2 = h.node2 == kGround ? nullptr : mass.data() + kDofsPerNode * h.node2;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((h.springs >> k) & 1U)) continue;
      const double w = hinge_inverse_mass(h, k, m1, m2);
      const double omega = std::sqrt(h.stiffness[k] * w);
      const double eta = h.dashpot[k] * w;
      double dt = 1e300;
      if (omega > 0) {
        const double xi = eta / (2.0 * omega);
        dt = 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
      } else if (eta > 0) {
        dt = 2.0 / eta;
      }
      if (!(dt >= 0)) dt = 0;  // an infinite frequency (a spring on a massless DOF)
      if (dt < r.dt_hinges) {
        r.dt_hinges = dt, r.governing_hinge = static_cast<int>(i);
        r.hinge_direction = static_cast<int>(k);
      }
    }
  }
  if (r.dt_hinges < r.dt_elements) {
    r.dt_stable = r.dt_hinges;
  } else {
    r.governing_hinge = -1, r.hinge_direction = -1;
  }
  return r;
}

// dt = "auto" (DESIGN §6): the largest period / N with N integer and period / N <= 0.9 dt_stable.
inline double auto_time_step(double dt_stable, double frame_period) {
  if (!(dt_stable > 0) || !(frame_period > 0)) return 0;
  double n = std::ceil(frame_period / (0.9 * dt_stable));
  if (n < 1) n = 1;
  return frame_period / n;
}

}  // namespace ntn
