// The energy books of a run: the discrete work-energy identity of the central difference scheme,
// accumulated step by step from what each step used, one account per mechanism. With the step's
// final velocities (after the stops, the slips and the projection) and
// Delta_n = (u_{n+1} - u_{n-1}) / 2 = dt (v_{n+1/2} + v_{n-1/2}) / 2,
//     K_{n+1/2} - K_{n-1/2} = Delta_n . (P_n - F_n - alpha M v_d) - sum f (b Delta_n),
// v_d = v_{n-1/2} with damping_velocity = "lagged", v_n = (v_{n-1/2} + v_{n+1/2}) / 2 with
// "central" (the step mass M_e = (1 + alpha dt/2) M moves alpha M dt/2 a_n to the damping),
// K = 1/2 v^T M v at the half steps, the last sum over the slip and stop directions (their forces
// act as moves of u_{n+1}, du = -f dt^2 M_c^-1 b; the constraint forces of rigid directions do no
// work on a compatible Delta). F_n is split by what produced it: each hinge spring direction's
// spring force and dashpot force times (B Delta)_k, the elements' force the rest. The accounts
// (EnergyAccounts) are changes since the start:
//   kinetic     K - K_0
//   elastic     the elements' strain energy (their work, or with beta > 0 the staggered
//               1/2 u_n^T K u_{n+1}), the elastic hinge springs' work (linear, curve, penalty) and
//               the energy still stored in plastic, backbone and breaking springs
//   viscous     alpha M, the hinge dashpots, and beta K (the elements' work less their strain
//               energy)
//   hysteretic  the work on plastic and backbone directions less what they still store (strength
//               drops and failure past E release it here)
//   friction    the slip directions' work (rigid_plastic, friction, fixed_if): f times the slide
//   impacts     the stops' clamp forces' work: what a stop takes from a body it stops
//   fracture    breaking springs' work less what they store, and rigid failure directions' slide
// and external = kinetic + elastic + viscous + hysteretic + friction + impacts + fracture +
// residual, the residual rounding. The sums over every DOF (P, F, alpha M, the kinetic energy)
// are the kernel's, made in the step's own passes (Model::books, books.hpp); the hinges' shares
// are added here, hinge by hinge, with v_{n-1/2} = v_{n+1/2} - dt a_n.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string_view>
#include <vector>

#include "ntn/hinge.hpp"
#include "ntn/kernel.hpp"

namespace ntn::hil {

// The accounts as channels (EnergyAccounts::channels), in this order: what ntn-run --energy
// names its CSV columns `energy_<name>` and Python's run() its "energy" arrays.
inline constexpr std::array<std::string_view, 9> kEnergyChannels = {
    "external", "kinetic", "elastic",  "viscous", "hysteretic",
    "friction", "impacts", "fracture", "residual"};

// One account per mechanism, J (the header's list).
struct EnergyAccounts {
  double external = 0;
  double kinetic = 0;
  double elastic = 0;
  double viscous = 0;
  double hysteretic = 0;
  double friction = 0;
  double impacts = 0;
  double fracture = 0;
  double residual = 0;     // external - the others: rounding
  double input_scale = 0;  // the largest |external| reached: the residual's scale
  double relative_residual() const {
    return input_scale > 0 ? std::fabs(residual) / input_scale : 0.0;
  }
  // The accounts in kEnergyChannels' order.
  std::array<double, kEnergyChannels.size()> channels() const {
    return {external, kinetic, elastic, viscous, hysteretic, friction, impacts, fracture, residual};
  }
};

// The works the steps add up (EnergyBalance keeps them; a run's result holds a copy).
class EnergyTotals {
 public:
  double kinetic() const { return kinetic_; }    // J, at the last half step
  double kinetic0() const { return kinetic0_; }  // J, at v_{-1/2}
  double external() const { return external_; }  // J
  double internal() const { return internal_; }  // J: Delta . F_n (elements, hinge springs)
  double damping() const { return damping_; }    // J, C = alpha M
  double input_scale() const { return input_scale_; }
  // (kinetic - kinetic0) - (external - internal - damping - slip and stop work): rounding.
  double residual() const {
    return (kinetic_ - kinetic0_) -
           (external_ - internal_ - damping_ - friction_ - fracture_slip_ - impacts_);
  }

 protected:
  double kinetic0_ = 0, kinetic_ = 0, external_ = 0, internal_ = 0, damping_ = 0;
  double springs_ = 0;        // elastic hinge springs: linear, curve, penalty
  double plastic_ = 0;        // plastic and backbone directions' spring work
  double breaking_ = 0;       // breaking springs' work (linear + failure, penalty failure)
  double dashpots_ = 0;       // hinge dashpots
  double friction_ = 0;       // slip directions but rigid failures
  double fracture_slip_ = 0;  // rigid failure directions (slip.hpp, kBrittle)
  double impacts_ = 0;        // the stops' clamp
  double elements0_ = 0;      // the elements' staggered strain energy at the start (beta > 0)
  double input_scale_ = 0;
};

template <Sizes S>
class EnergyBalance : public EnergyTotals {
 public:
  // Room for a DOF-sized work array (the strain energy under beta > 0), so that begin() and
  // the steps allocate nothing (call before the run).
  void reserve(std::size_t dofs) { work_.reserve(dofs); }
  EnergyTotals numbers() const { return *this; }
  // Call after start(): turns the kernel's books on (Model::books: the step's sums over the DOFs,
  // books.hpp) and takes the kinetic energy at the start.
  void begin(Model<S>& m, const State<S>& s) {
    m.books = true;
    work_.assign(s.v.size(), 0.0);
    kinetic0_ = kinetic_ = kinetic_energy(m, s);
    external_ = internal_ = damping_ = 0;
    springs_ = plastic_ = breaking_ = dashpots_ = friction_ = fracture_slip_ = impacts_ = 0;
    input_scale_ = 0;
    // u_{-1} = u_0 - dt v_{-1/2}: the staggered strain energy 1/2 u_{-1}^T K u_0.
    elements0_ = m.beta > 0 ? element_energy(m, s) : 0.0;
  }
  // Call after each step(): `s` holds u_{n+1}, v_{n+1/2}; `w` the step's P_n, F_n, a_n and its
  // books over the DOFs (Scratch::books).
  void after_step(const Model<S>& m, const State<S>& s, const Scratch<S>& w) {
    if constexpr (kMayHaveHinges<S>) hinge_work(m, s, w);
    external_ += w.books.external, internal_ += w.books.internal, damping_ += w.books.damping;
    input_scale_ = std::fmax(input_scale_, std::fabs(external_));
    kinetic_ = w.books.kinetic;
  }

  // The accounts now (the header's list), from the totals and the state after the last step.
  EnergyAccounts accounts(const Model<S>& m, const State<S>& s) {
    EnergyAccounts a;
    double stored_plastic = 0, stored_breaking = 0;
    if constexpr (kMayHaveHystereses<S>) stored_springs(m, s, stored_plastic, stored_breaking);
    const double elements = internal_ - springs_ - plastic_ - breaking_ - dashpots_;
    const double strain = m.beta > 0 ? element_energy(m, s) - elements0_ : elements;
    a.external = external_;
    a.kinetic = kinetic_ - kinetic0_;
    a.elastic = strain + springs_ + stored_plastic + stored_breaking;
    a.viscous = damping_ + dashpots_ + (elements - strain);
    a.hysteretic = plastic_ - stored_plastic;
    a.friction = friction_;
    a.impacts = impacts_;
    a.fracture = fracture_slip_ + breaking_ - stored_breaking;
    a.residual = a.external - (a.kinetic + a.elastic + a.viscous + a.hysteretic + a.friction +
                               a.impacts + a.fracture);
    a.input_scale = input_scale_;
    return a;
  }

  static double kinetic_energy(const Model<S>& m, const State<S>& s) {
    double k = 0;
    for (std::size_t j = 0; j < s.v.size(); ++j)
      k += 0.5 * m.mass[j] * s.v[j] * s.v[j];
    return k;
  }

 private:
  // v_{n-1/2} at DOF j after a step: v_{n+1/2} - dt a_n, the a_n the step ended with (every
  // force of the step in it).
  static double v_before(const Model<S>& m, const State<S>& s, const Scratch<S>& w, std::size_t j) {
    return s.v[j] - m.dt * w.a[j];
  }

  // Delta_n at the six DOFs of `node` (zero for the ground).
  static void node_delta(const Model<S>& m, const State<S>& s, const Scratch<S>& w, int node,
                         double* delta) {
    for (std::size_t c = 0; c < kDofsPerNode; ++c) {
      if (node == kGround) {
        delta[c] = 0;
        continue;
      }
      const auto j = static_cast<std::size_t>(kDofsPerNode * node) + c;
      delta[c] = 0.5 * m.dt * (s.v[j] + v_before(m, s, w, j));
    }
  }

  // A hinge's (B x)_k for node values x1, x2 (x2 unused for the ground).
  static void relative(const HingeData& h, const double* x1, const double* x2, double* d) {
    hinge_relative(h, x1, h.node2 == kGround ? nullptr : x2, d);
  }

  // A hinge's pose (hinge.hpp) and its d = B u for node translations u1, u2 (u2 unused for the
  // ground): a hinge that turns with its nodes at their rotations now (`before`: false) or at
  // t_n, Q_n = exp(-dt w_{n+1/2}) Q_{n+1} (true: to rounding the step's Q_n).
  static HingePose pose(const Model<S>& m, const State<S>& s, const HingeData& h, const double* u1,
                        const double* u2, bool before, double* d) {
    if constexpr (kMayTurnHinges<S>) {
      if (h.turns) {
        Quaternion q[2];
        for (std::size_t k = 0; k < 2; ++k) {
          const auto node = static_cast<std::size_t>(k == 0 ? h.node1 : h.node2);
          q[k] = s.rotation[node];
          if (!before) continue;
          const double* w = &s.v[static_cast<std::size_t>(kDofsPerNode) * node + 3];
          q[k] =
              renormalized(product(exp_rotation({-m.dt * w[0], -m.dt * w[1], -m.dt * w[2]}), q[k]));
        }
        return hinge_turned(h, q[0], q[1], u1, u2, d);
      }
    }
    (void)m, (void)s, (void)before;
    relative(h, u1, u2, d);
    return hinge_pose(h);
  }

  // u_n = u_{n+1} - dt v_{n+1/2} and v_{n-1/2} at the six DOFs of `node` (v unused without a
  // step's scratch: w null).
  static void node_before(const Model<S>& m, const State<S>& s, const Scratch<S>* w, int node,
                          double* u, double* v) {
    for (std::size_t c = 0; c < kDofsPerNode; ++c) {
      if (node == kGround) {
        u[c] = v[c] = 0;
        continue;
      }
      const auto j = static_cast<std::size_t>(kDofsPerNode * node) + c;
      u[c] = s.u[j] - m.dt * s.v[j];
      v[c] = w != nullptr ? v_before(m, s, *w, j) : 0.0;
    }
  }

  // The hinges' share of the step's work: each spring direction's spring and dashpot force at
  // t_n (from u_n and v_{n-1/2}, as the spring stage made them, the dashpot with the dashpot
  // stage's Scratch::dashpot_force) times (B Delta)_k, by the kind of its law; the slip and stop
  // directions' forces (Scratch::slip_force, stop_force) likewise.
  void hinge_work(const Model<S>& m, const State<S>& s, const Scratch<S>& w) {
    double d1[6], d2[6], bd[6], u1[6], u2[6], v1[6], v2[6], d[6], d_dot[6], f[6];
    const bool central = m.damping_velocity == DampingVelocity::kCentral;
    for (int i = 0; i < m.num_spring_hinges; ++i) {
      const auto hi = static_cast<std::size_t>(m.spring_hinges[static_cast<std::size_t>(i)]);
      const HingeData& h = m.hinges[hi];
      node_delta(m, s, w, h.node1, d1);
      node_delta(m, s, w, h.node2, d2);
      node_before(m, s, &w, h.node1, u1, v1);
      node_before(m, s, &w, h.node2, u2, v2);
      const HingePose p = pose(m, s, h, u1, u2, true, d);  // at t_n, as the spring stage's
      const double* none = h.node2 == kGround ? nullptr : d2;
      hinge_relative(p, d1, none, bd);
      hinge_relative(p, v1, h.node2 == kGround ? nullptr : v2, d_dot);
      hinge_spring_force(h, m.curve_points, s.plastic, d, d_dot, f);
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!((h.springs >> k) & 1U)) continue;
        const bool curve = !((h.plastic >> k) & 1U) && h.behaviour[k] == HingeBehaviour::kCurve;
        const double dash = curve ? 0.0 : h.dashpot[k] * d_dot[k];  // hinge_spring_force's
        dashpots_ += (central ? dash + w.dashpot_force[hi][k] : dash) * bd[k];
        const double work = (f[k] - dash) * bd[k];
        if (!((h.plastic >> k) & 1U)) {
          springs_ += work;
        } else if (law_account(m.hystereses[static_cast<std::size_t>(h.history[k])].rule) ==
                   LawAccount::kBreaking) {
          breaking_ += work;
        } else {
          plastic_ += work;
        }
      }
    }
    if constexpr (kMayHaveHystereses<S>) {
      for (int i = 0; i < m.num_slip_hinges; ++i) {
        const HingeData& h =
            m.hinges[static_cast<std::size_t>(m.slip_hinges[static_cast<std::size_t>(i)])];
        node_delta(m, s, w, h.node1, d1);
        node_delta(m, s, w, h.node2, d2);
        relative(h, d1, d2, bd);
        for (std::size_t k = 0; k < kDofsPerNode; ++k) {
          if (!((h.slip >> k) & 1U)) continue;
          const auto slot = static_cast<std::size_t>(h.history[k]);
          const double work = w.slip_force[slot] * bd[k];
          if (law_account(m.hystereses[slot].rule) == LawAccount::kBreaking) {
            fracture_slip_ += work;
          } else {
            friction_ += work;
          }
        }
      }
    }
    for (int i = 0; i < m.num_branch_hinges; ++i) {
      const auto hi = static_cast<std::size_t>(m.branch_hinges[static_cast<std::size_t>(i)]);
      const HingeData& h = m.hinges[hi];
      node_delta(m, s, w, h.node1, d1);
      node_delta(m, s, w, h.node2, d2);
      relative(h, d1, d2, bd);
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if ((h.branches >> k) & 1U) impacts_ += w.stop_force[hi][k] * bd[k];
      }
    }
  }

  // The energy plastic, backbone and breaking springs still store: 1/2 k (d_n - d_p)(d_{n+1} -
  // d_p), the staggered form whose change the spring force's work is for an elastic spring (a
  // broken spring stores nothing).
  void stored_springs(const Model<S>& m, const State<S>& s, double& plastic,
                      double& breaking) const {
    double u1[6], u2[6], v1[6], v2[6], now[6], before[6];
    for (int i = 0; i < m.num_spring_hinges; ++i) {
      const HingeData& h =
          m.hinges[static_cast<std::size_t>(m.spring_hinges[static_cast<std::size_t>(i)])];
      if (h.plastic == 0) continue;
      node_before(m, s, nullptr, h.node1, u1, v1);
      node_before(m, s, nullptr, h.node2, u2, v2);
      pose(m, s, h, u1, u2, true, before);
      pose(m, s, h, &s.u[static_cast<std::size_t>(kDofsPerNode * h.node1)],
           h.node2 == kGround ? nullptr : &s.u[static_cast<std::size_t>(kDofsPerNode * h.node2)],
           false, now);
      for (std::size_t k = 0; k < kDofsPerNode; ++k) {
        if (!((h.plastic >> k) & 1U)) continue;
        const auto slot = static_cast<std::size_t>(h.history[k]);
        const double dp = s.plastic[slot];
        const double e = 0.5 * h.stiffness[k] * (before[k] - dp) * (now[k] - dp);
        if (law_account(m.hystereses[slot].rule) == LawAccount::kBreaking) {
          breaking += s.first_slip[slot] != 0 ? 0.0 : e;
        } else {
          plastic += e;
        }
      }
    }
  }

  // The elements' staggered strain energy 1/2 u_n^T K u_{n+1}, u_n = u_{n+1} - dt v_{n+1/2}
  // (after start(): u_{-1}^T K u_0): K u_{n+1} by the element pass without damping; plus the
  // second-order part of the elements with nonlinear geometry and the corotational elements'
  // strain energy at u_{n+1} (geometry.hpp, corotational.hpp; their step-to-step work differs from
  // that change by O(dt^2), which the viscous account then holds).
  double element_energy(const Model<S>& m, const State<S>& s) {
    element_forces_into(m.element_pass, m.beam_arrays(), m.sizes.elements, m.every_node_in_element,
                        m.dofs(), s.u.data(), s.v.data(), 0.0, work_.data());
    double e = 0;
    for (std::size_t j = 0; j < work_.size(); ++j)
      e += 0.5 * (s.u[j] - m.dt * s.v[j]) * work_[j];
    for (std::size_t k = 0; k < m.sizes.geometric; ++k)  // second-order geometry, at u_{n+1}
      e += geometric_energy(m.geometric[k], s.u.data());
    for (std::size_t k = 0; k < m.sizes.corotational; ++k)  // corotational, at u_{n+1}, Q_{n+1}
      e += corotational_energy(m.corotational[k], s.u.data(), s.rotation.data());
    return e;
  }

  std::vector<double> work_;
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
