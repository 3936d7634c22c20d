// Stable time step of the central difference method (DESIGN §6, seed S 9-10).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "ntn/beam.hpp"
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
