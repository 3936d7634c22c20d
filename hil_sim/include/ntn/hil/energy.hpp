// The energy balance of a run (issue 15): the discrete work-energy identity of the central
// difference scheme, accumulated step by step from what each step used. With
// Delta_n = (u_{n+1} - u_{n-1}) / 2 = dt (v_{n+1/2} + v_{n-1/2}) / 2 and M (v_{n+1/2} - v_{n-1/2})
// = dt (P_n - F_n - C v_{n-1/2}) (+ constraint forces, which do no work on a compatible motion):
//     K_{n+1/2} - K_{n-1/2} = Delta_n . P_n - Delta_n . F_n - Delta_n . alpha M v_{n-1/2},
// K = 1/2 v^T M v at the half steps. Summed over a run: kinetic energy now minus at the start =
// external work (gravity, base excitation -M iota a_g, loads, force inputs) - internal work (the
// elements' elastic and beta K forces, hinge springs, plastic directions and dashpots) - the
// mass-proportional damping's work; the residual is rounding (and the work of rigid stops' clamps,
// which are impulses). The internal work includes the rigid-plastic directions' forces (slip.hpp:
// they act through the slip stage, not F_n): f (B Delta_n)_k each. The internal work's
// hysteretic share is the plastic directions' own record, State::dissipated (the plastic work
// integral f dd_p; for a rigid-plastic direction the friction work f ds).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "ntn/hinge.hpp"
#include "ntn/model.hpp"
#include "ntn/residual.hpp"
#include "ntn/state.hpp"

namespace ntn::hil {

// The balance's totals (EnergyBalance keeps them; a run's result holds a copy).
class EnergyTotals {
 public:
  double kinetic() const { return kinetic_; }    // J, at the last half step
  double kinetic0() const { return kinetic0_; }  // J, at v_{-1/2}
  double external() const { return external_; }  // J
  double internal() const { return internal_; }  // J
  double damping() const { return damping_; }    // J, C = alpha M
  // The largest |external work| reached so far: the scale of the balance's residual.
  double input_scale() const { return input_scale_; }
  // (kinetic - kinetic0) - (external - internal - damping): rounding, plus the stops' work.
  double residual() const { return (kinetic_ - kinetic0_) - (external_ - internal_ - damping_); }

 protected:
  double kinetic0_ = 0, kinetic_ = 0, external_ = 0, internal_ = 0, damping_ = 0;
  double input_scale_ = 0;
};

template <Sizes S>
class EnergyBalance : public EnergyTotals {
 public:
  // Room for v_{-1/2} of `dofs` DOFs, so that begin() allocates nothing (call before the run).
  void reserve(std::size_t dofs) { v_prev_.reserve(dofs); }
  EnergyTotals numbers() const { return *this; }
  // Call after start(): takes v_{-1/2} and the kinetic energy at the start.
  void begin(const Model<S>& m, const State<S>& s) {
    v_prev_.assign(s.v.begin(), s.v.end());
    kinetic0_ = kinetic_ = kinetic_energy(m, s);
    external_ = internal_ = damping_ = 0;
    input_scale_ = 0;
  }
  // Call after each step(): `s` holds u_{n+1}, v_{n+1/2}; `w` the step's P_n and F_n.
  void after_step(const Model<S>& m, const State<S>& s, const Scratch<S>& w) {
    const double half_dt = 0.5 * m.dt;
    double ext = 0, in = 0, damp = 0;
    for (std::size_t n = 0; n < m.sizes.nodes; ++n) {
      for (std::size_t d = 0; d < kDofsPerNode; ++d) {
        const std::size_t j = kDofsPerNode * n + d;
        const double delta = half_dt * (s.v[j] + v_prev_[j]);
        ext += delta * m.mass[j] * w.load_g[d];
        in += delta * w.f[j];
        damp += delta * m.alpha * m.mass[j] * v_prev_[j];
      }
    }
    if constexpr (kMayHaveHystereses<S>) {  // rigid-plastic directions: f (B Delta)_k
      for (int i = 0; i < m.num_slip_hinges; ++i) {
        const HingeData& h =
            m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(i)])];
        double delta1[6], delta2[6], bd[6];
        for (std::size_t c = 0; c < 6; ++c) {
          const auto j1 = static_cast<std::size_t>(kDofsPerNode * h.node1) + c;
          delta1[c] = half_dt * (s.v[j1] + v_prev_[j1]);
          if (h.node2 != kGround) {
            const auto j2 = static_cast<std::size_t>(kDofsPerNode * h.node2) + c;
            delta2[c] = half_dt * (s.v[j2] + v_prev_[j2]);
          }
        }
        hinge_relative(h, delta1, h.node2 == kGround ? nullptr : delta2, bd);
        for (std::size_t k = 0; k < kDofsPerNode; ++k) {
          if ((h.slip >> k) & 1U)
            in += w.slip_force[static_cast<std::size_t>(h.history[k])] * bd[k];
        }
      }
    }
    for (int k = 0; k < m.num_slots; ++k) {  // where P_n is not m g: the load slots
      const auto j = static_cast<std::size_t>(m.slot_dof[static_cast<std::size_t>(k)]);
      const double delta = half_dt * (s.v[j] + v_prev_[j]);
      ext +=
          delta * (w.p_slot[static_cast<std::size_t>(k)] - m.mass[j] * w.load_g[j % kDofsPerNode]);
    }
    external_ += ext, internal_ += in, damping_ += damp;
    input_scale_ = std::fmax(input_scale_, std::fabs(external_));
    for (std::size_t j = 0; j < v_prev_.size(); ++j)
      v_prev_[j] = s.v[j];
    kinetic_ = kinetic_energy(m, s);
  }

  static double kinetic_energy(const Model<S>& m, const State<S>& s) {
    double k = 0;
    for (std::size_t j = 0; j < s.v.size(); ++j)
      k += 0.5 * m.mass[j] * s.v[j] * s.v[j];
    return k;
  }

 private:
  std::vector<double> v_prev_;
};

// The hysteretic energy of a state: the plastic work of every plastic hinge direction, J.
template <Sizes S>
double hysteretic_energy(const State<S>& s) {
  double e = 0;
  for (double x : s.dissipated)
    e += x;
  return e;
}

}  // namespace ntn::hil
