// Stable time step of the central difference method (DESIGN §6, seed S 9-10).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "ntn/beam.hpp"
#include "ntn/hinge.hpp"
#include "ntn/hinge_methods.hpp"
#include "ntn/model_spec.hpp"

namespace ntn {

// Largest circular frequency of one free element: omega_e^2 = lambda_max(M_e^-1 K_e), with the
// element's own lumped mass in global axes (the same mass that is assembled). By the element
// eigenvalue theorem max_e omega_e bounds the assembled model's omega_max: added point masses
// and supports only lower it. Returns 0 for an invalid element, +inf for one beyond double.
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
  // A stiffness or mass so extreme that M^-1/2 K M^-1/2 overflows (or underflows to a division
  // by zero) has no finite frequency: +inf, so that the stable step becomes 0 and is refused,
  // never a silently dropped element.
  if (!A.allFinite()) return std::numeric_limits<double>::infinity();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eig(A, Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return std::sqrt(eig.eigenvalues().maxCoeff());
}

// Delta t_stable = (2 / omega)(sqrt(1 + xi^2) - xi), xi = alpha / (2 omega) for C = alpha M.
// The same bound holds with the damping velocity lagged to n - 1/2 as in (S 3). Computed as
// 2 / (omega (sqrt(1 + xi^2) + xi)), the same number without the cancellation of the first form
// (which gives 0 for xi above about 1e8 and inf once xi^2 overflows). For xi > 1e150, where xi^2
// would overflow, sqrt(1 + xi^2) = xi to the last bit and the step is 1 / (omega xi) = 2 / alpha
// (written so, as xi itself may be inf). 0 for omega <= 0 or NaN, a NaN alpha, omega = inf or
// alpha = inf.
inline double damped_stable_step(double omega, double alpha) {
  if (!(omega > 0) || !(alpha >= 0)) return 0;
  const double xi = alpha / (2.0 * omega);
  if (xi > 1e150) return 2.0 / alpha;
  return 2.0 / (omega * (std::sqrt(1.0 + xi * xi) + xi));
}

// Why a stable step is 0 (StableStepReport::issue).
enum class StepIssue : std::uint8_t {
  kNone,
  kMassless,   // a spring or dashpot on a free DOF without mass (its frequency is infinite)
  kNonFinite,  // an intermediate result overflowed (omega^2, K / m, k g |b^|^2, ...) at the
               // governing element or hinge direction: the numbers are beyond double
};

struct StableStepReport {
  double dt_stable = 0;        // s, from the element eigenvalue bound with damping
  double omega_max = 0;        // rad/s, max over elements of omega_e
  int governing_element = -1;  // element that sets omega_max
  double dt_cfl = 0;           // s, the seed's estimate min_e l / sqrt(E / rho) (S 9-10)
  int cfl_element = -1;        // element that sets dt_cfl
  double dt_elements = 0;      // s, the elements' bound alone
  double dt_hinges = 1e300;    // s, the hinges' springs' bound alone (1e300: no spring)
  int governing_hinge = -1;    // hinge with the largest share of the governing node's bound,
                               // or -1 when the elements' part is the larger
  int hinge_direction = -1;    // its local direction 0..5
  StepIssue issue = StepIssue::kNone;  // dt_stable = 0 because of ... (governing_* name where)
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
  // An element without a finite frequency, or damping that leaves no step: refused, never
  // dropped (a model without elements has omega_max = 0 and dt_stable = 0, no issue).
  if (!(r.omega_max < std::numeric_limits<double>::infinity()) ||
      (r.omega_max > 0 && !(r.dt_stable > 0))) {
    r.issue = StepIssue::kNonFinite, r.dt_stable = 0, r.dt_elements = 0;
  }
  return r;
}

// ---- The hinges' springs (DESIGN §6) --------------------------------------------------------
//
// Each spring direction s (linear, curve at its steepest slope, a rigid direction under
// `penalty`) adds k_s b_s b_s^T to the stiffness and c_s b_s b_s^T to the damping, b_s its row of
// B (node 1's part -[t ; e x t] or -[0 ; t], node 2's [t ; 0] or [0 ; t]). In mass-scaled
// coordinates y = M^1/2 u it is b^ = M^-1/2 b, with node parts b^1, b^2 (supported DOFs left
// out: they do not move), n_i = |b^i|^2, w = n_1 + n_2 = b^T M^-1 b. For any tau > 0,
// (p + q)^2 <= (1 + tau) p^2 + (1 + 1/tau) q^2, so
//     k (b^ . y)^2 <= k g_1 (b^1 . y_1)^2 + k g_2 (b^2 . y_2)^2,   g_1 = 1 + tau, g_2 = 1 + 1/tau:
// each spring is bounded by two one-node springs, and the springs together by one 6x6 block per
// node, P_n = sum_{s at n} k_s g_s,n b^n b^n^T (Q_n the same with the dashpots c_s). Every
// spring on a node counts: a shared joint, an eccentric hinge's translations and rotations on
// node 1's rotations, turned frames. tau only sets how tight this is (any tau > 0 is a bound, as
// long as a spring has the same tau at both of its nodes): tau = (n_2 L_2) / (n_1 L_1), i.e.
// g_i = (n_1 L_1 + n_2 L_2) / (n_i L_i), with L_i = u_i^T L_n u_i the load along the spring at
// its node i, L_n = sum_{s at n} k_s w_s u u^T (u = b^n / |b^n|). An isolated hinge then gets
// exactly its two-node frequency k w on both nodes, and N equal springs on one node along the
// same direction exactly the star's k (N n_joint + n_end).
//
// The elements, by the element eigenvalue theorem node by node: u_e^T K_e u_e <= omega_e^2
// u_e^T M_e u_e and M_n >= sum_{e at n} M_e,n (diagonal), so with the diagonal
// E_n = diag_j(sum_{e at n} omega_e^2 m_e,j / m_n,j) (a mass-weighted mean of the omega_e^2 at
// node n, at most Omega^2 = max_e omega_e^2)
//     u^T (K_el + K_s) u <= sum_n y_n^T (E_n + P_n) y_n,
//     u^T C u <= sum_n y_n^T (alpha I + Q_n) y_n.
// Central difference with the damping lagged to v_{n-1/2} (S 3, the dashpots too) keeps
// F = 1/2 v^T (M - dt/2 C - dt^2/4 K) v + 1/2 u_bar^T K u_bar non-increasing
// (F_{n+1/2} - F_{n-1/2} = -dt/4 (v+ + v-)^T C (v+ + v-), u_bar = (u_n + u_{n+1}) / 2), so
// 4 M - 2 dt C - dt^2 K > 0 is sufficient for stability with any symmetric C >= 0, K >= 0. It
// holds when, at every node n with a spring,
//     dt^2 omega_n^2 + 2 dt eta_n < 4,
//     omega_n^2 = lambda_max(E_n + P_n),   eta_n = alpha + lambda_max(Q_n),
// i.e. dt < dt_n = (2 / omega_n) (sqrt(1 + xi_n^2) - xi_n), xi_n = eta_n / (2 omega_n), and
// below the elements' own step at the others: dt_stable = min(dt_elements, min_n dt_n). A
// strict bound on the assembled system, with or without NTN coupling (constraints only lower
// omega_max), and never above a spring's own two-node step (one of its two nodes gets g n >= w).

// The largest dt with dt^2 omega2 + 2 dt eta <= 4 (1e300 when both are zero; 0 when either is
// NaN or inf).
inline double quadratic_step(double omega2, double eta) {
  if (!(omega2 >= 0 && omega2 <= std::numeric_limits<double>::max()) ||
      !(eta >= 0 && eta <= std::numeric_limits<double>::max()))
    return 0;
  if (omega2 > 0) return damped_stable_step(std::sqrt(omega2), eta);
  if (eta > 0) return 2.0 / eta;
  return 1e300;
}

// lambda_max of a symmetric positive semidefinite 6x6 block and its eigenvector; the trace
// (>= lambda_max) and a zero vector if the solver fails.
inline double top_eigen(const Eigen::Matrix<double, 6, 6>& a, Eigen::Matrix<double, 6, 1>& v) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(a);
  if (eig.info() != Eigen::Success) {
    v.setZero();
    return a.trace();
  }
  v = eig.eigenvectors().col(5);
  return std::max(eig.eigenvalues()(5), 0.0);
}

// Spring direction k of hinge h in mass-scaled coordinates: s1 = M1^-1/2 b1, s2 = M2^-1/2 b2
// (zero at supported DOFs and for the ground) and n1 = |s1|^2, n2 = |s2|^2. False when b
// touches a free DOF without mass (an infinitely fast mode).
inline bool scaled_spring_direction(const HingeData& h, std::size_t k,
                                    std::span<const NodeSpec> nodes, std::span<const double> mass,
                                    double* s1, double* s2, double& n1, double& n2) {
  double b[2][6];
  hinge_direction(h, k, b[0], b[1]);
  double* s[2] = {s1, s2};
  double* n[2] = {&n1, &n2};
  const int node[2] = {h.node1, h.node2};
  for (int t = 0; t < 2; ++t) {
    *n[t] = 0;
    for (std::size_t c = 0; c < 6; ++c) {
      s[t][c] = 0;
      if (node[t] == kGround || b[t][c] == 0) continue;
      const auto i = static_cast<std::size_t>(node[t]);
      if ((nodes[i].fixed >> c) & 1U) continue;
      const double m = mass[kDofsPerNode * i + c];
      if (!(m > 0)) return false;
      s[t][c] = b[t][c] / std::sqrt(m);
      *n[t] += s[t][c] * s[t][c];
    }
  }
  return true;
}

// The stable step with the hinges' springs (DESIGN §6), `mass` the lumped mass per DOF: the
// bound above. Rigid NTN directions add no stiffness. dt_hinges is the springs' part alone
// (dt^2 lambda_max(P_n) + 2 dt lambda_max(Q_n) < 4). When it is below dt_elements, the governing
// hinge and direction are the spring with the largest share of the governing node's bound,
// dt^2 k g (b^n . v)^2 + 2 dt c g (b^n . v_c)^2 (v, v_c the top eigenvectors of E_n + P_n, Q_n).
// A spring (k or c > 0) on a free DOF without mass gives 0, naming the first such hinge and
// direction.
//
// No heap. The nodes are taken kStepChunk at a time (a pass). A pass needs L at its own nodes
// and at the other nodes of their springs (partners); those are taken kStepPartners at a time in
// increasing node order (a window; one window unless the pass's springs reach more nodes), each
// window a few scans of the hinges, then one scan of the elements. Each spring gets the same g
// in the passes of its two nodes, and each hinge's and element's own work (6x6 and 12x12
// eigenvalues) is done in those passes.
inline constexpr int kStepChunk = 16;
inline constexpr int kStepPartners = 32;

inline StableStepReport stable_time_step(const SpecView& spec, std::span<const double> mass) {
  using Block6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  StableStepReport r = stable_time_step(spec);
  if (r.issue != StepIssue::kNone) return r;
  const int nodes = static_cast<int>(spec.nodes.size());
  const bool rot = spec.settings.rotary_inertia;
  // An intermediate result beyond double (a spring of 1e308, a mass of 1e-300): the step is 0
  // with the first hinge direction or element where it showed, never a term left out.
  bool overflow = false;
  auto overflow_at = [&](int hinge, int direction, int element) {
    if (overflow) return;
    overflow = true;
    r.governing_hinge = hinge, r.hinge_direction = direction;
    if (element >= 0) r.governing_element = element;
  };
  auto finite = [](double v) { return std::isfinite(v); };
  // Calls f(i, h, k, s1, s2, n1, n2) for every spring direction k (k or c > 0) of hinge i if
  // it is valid; false at a massless DOF (issue kMassless) or where k w or c w is not finite
  // (kNonFinite, w = n1 + n2), with the report set to 0 and that hinge and direction.
  auto springs_of = [&](std::size_t i, auto f) {
    HingeData h;
    if (!make_hinge_data(spec.hinges[i], spec.settings, nodes, spec.curves, spec.curve_points, h))
      return true;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((h.springs >> k) & 1U) || !(h.stiffness[k] > 0 || h.dashpot[k] > 0)) continue;
      double s1[6], s2[6], n1, n2;
      const bool massless = !scaled_spring_direction(h, k, spec.nodes, mass, s1, s2, n1, n2);
      if (massless || !finite(h.stiffness[k] * (n1 + n2)) || !finite(h.dashpot[k] * (n1 + n2))) {
        r.dt_hinges = 0, r.dt_stable = 0;
        r.governing_hinge = static_cast<int>(i), r.hinge_direction = static_cast<int>(k);
        r.issue = massless ? StepIssue::kMassless : StepIssue::kNonFinite;
        return false;
      }
      f(i, h, k, s1, s2, n1, n2);
    }
    return true;
  };
  // A massless DOF under a spring, and the range of nodes that springs touch.
  int lo = nodes, hi = -1;
  for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
    bool any = false;
    if (!springs_of(i, [&](std::size_t, const HingeData&, std::size_t, const double*, const double*,
                           double, double) { any = true; }))
      return r;
    if (!any) continue;
    const HingeSpec& hs = spec.hinges[i];
    lo = std::min(lo, hs.node1), hi = std::max(hi, hs.node1);
    if (hs.node2 != kGround) lo = std::min(lo, hs.node2), hi = std::max(hi, hs.node2);
  }
  if (hi < 0) return r;  // no spring: the elements' bound as it is

  // L = sum of k w u u^T over the springs at a node (u their unit direction there): the pass's
  // nodes first, then the window's partners (ascending).
  std::array<Block6, kStepChunk + kStepPartners> load;
  std::array<int, kStepPartners> partner;
  int first = 0, count = 0, partners = 0;
  auto in_pass = [&](int n) { return n >= first && n < first + count; };
  auto load_index = [&](int n) {
    if (in_pass(n)) return n - first;
    const int* begin = partner.data();
    const int* end = begin + partners;
    const int* p = std::lower_bound(begin, end, n);
    return p != end && *p == n ? kStepChunk + static_cast<int>(p - begin) : -1;
  };
  // Adds k w u u^T of hinge i's springs at the nodes that have a load slot.
  auto add_load = [&](std::size_t i) {
    (void)springs_of(i, [&](std::size_t, const HingeData& h, std::size_t k, const double* s1,
                            const double* s2, double n1, double n2) {
      const int node[2] = {h.node1, h.node2};
      const double* sv[2] = {s1, s2};
      const double n[2] = {n1, n2};
      for (int t = 0; t < 2; ++t) {
        const int j = n[t] > 0 ? load_index(node[t]) : -1;
        if (j < 0) continue;
        const Eigen::Map<const Vec6> u(sv[t]);
        const double kw = h.stiffness[k] * (n1 + n2) / n[t];
        if (!finite(kw)) overflow_at(static_cast<int>(i), static_cast<int>(k), -1);
        load[static_cast<std::size_t>(j)] += kw * (u * u.transpose());
      }
    });
  };
  // The other node of a hinge of the pass: the ground or a node of the pass give -1.
  auto other_of = [&](const HingeSpec& hs) {
    const int o = in_pass(hs.node1) ? hs.node2 : hs.node1;
    return o == kGround || in_pass(o) ? -1 : o;
  };
  auto touches = [&](const HingeSpec& hs) {
    return in_pass(hs.node1) || (hs.node2 != kGround && in_pass(hs.node2));
  };
  // Calls f(i, h, k, s1, s2, n1, n2, g) once for every spring direction at the pass's nodes,
  // with g_1, g_2 from tau = n_2 L_2 / (n_1 L_1), L_i = u^T L u along the spring at node i
  // (equal loads if one is zero: a dashpot alone).
  auto pass_springs = [&](auto f) {
    partners = 0;
    for (int j = 0; j < kStepChunk; ++j)
      load[static_cast<std::size_t>(j)].setZero();
    for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
      if (touches(spec.hinges[i])) add_load(i);
    }
    for (int after = -1, window = 0;; ++window) {
      // The window: the kStepPartners smallest partners above `after`.
      partners = 0;
      for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
        const HingeSpec& hs = spec.hinges[i];
        if (!touches(hs)) continue;
        const int o = other_of(hs);
        if (o <= after) continue;
        int* end = partner.data() + partners;
        int* p = std::lower_bound(partner.data(), end, o);
        if (p != end && *p == o) continue;
        if (partners == kStepPartners) {
          if (p == end) continue;  // above the window
          --end, --partners;       // drop the largest
        }
        std::copy_backward(p, end, end + 1);
        *p = o, ++partners;
      }
      // Their loads (a partner of a hinge without springs just gets a slot).
      for (int j = kStepChunk; j < kStepChunk + partners; ++j)
        load[static_cast<std::size_t>(j)].setZero();
      for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
        const HingeSpec& hs = spec.hinges[i];
        const bool p1 = !in_pass(hs.node1) && load_index(hs.node1) >= 0;
        const bool p2 = hs.node2 != kGround && !in_pass(hs.node2) && load_index(hs.node2) >= 0;
        if (!p1 && !p2) continue;
        // Add only at the partners: the pass's nodes have their loads already.
        (void)springs_of(i, [&](std::size_t, const HingeData& h, std::size_t k, const double* s1,
                                const double* s2, double n1, double n2) {
          const double* sv[2] = {s1, s2};
          const double n[2] = {n1, n2};
          const bool at[2] = {p1, p2};
          for (int t = 0; t < 2; ++t) {
            if (!at[t] || !(n[t] > 0)) continue;
            const int j = load_index(t == 0 ? h.node1 : h.node2);
            const Eigen::Map<const Vec6> u(sv[t]);
            const double kw = h.stiffness[k] * (n1 + n2) / n[t];
            if (!finite(kw)) overflow_at(static_cast<int>(i), static_cast<int>(k), -1);
            load[static_cast<std::size_t>(j)] += kw * (u * u.transpose());
          }
        });
      }
      for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
        const HingeSpec& hs = spec.hinges[i];
        if (!touches(hs)) continue;
        const int o = other_of(hs);
        if (o < 0 ? window > 0 : load_index(o) < 0) continue;  // another window's
        (void)springs_of(i, [&](std::size_t ii, const HingeData& h, std::size_t k, const double* s1,
                                const double* s2, double n1, double n2) {
          const int node[2] = {h.node1, h.node2};
          const double* sv[2] = {s1, s2};
          const double n[2] = {n1, n2};
          double l[2] = {0, 0};
          for (int t = 0; t < 2; ++t) {
            if (!(n[t] > 0)) continue;
            const Eigen::Map<const Vec6> u(sv[t]);
            l[t] = u.dot(load[static_cast<std::size_t>(load_index(node[t]))] * u) / n[t];
          }
          if (!finite(l[0]) || !finite(l[1])) {
            overflow_at(static_cast<int>(ii), static_cast<int>(k), -1);
            return;
          }
          if ((n1 > 0 && !(l[0] > 0)) || (n2 > 0 && !(l[1] > 0))) l[0] = 1, l[1] = 1;
          const double a = n1 * l[0], b = n2 * l[1];
          const double g[2] = {a > 0 ? (a + b) / a : 0.0, b > 0 ? (a + b) / b : 0.0};
          if (!finite(g[0]) || !finite(g[1])) {
            overflow_at(static_cast<int>(ii), static_cast<int>(k), -1);
            return;
          }
          f(ii, h, k, s1, s2, n1, n2, g);
        });
      }
      if (partners < kStepPartners) break;
      after = partner[static_cast<std::size_t>(partners - 1)];
    }
  };

  const double alpha = spec.settings.alpha;
  double dt_best = 1e300, dt_springs = 1e300;
  std::array<Block6, kStepChunk> P, Q;  // springs, dashpots
  std::array<Vec6, kStepChunk> E;       // elements (the diagonal E_n)
  std::array<bool, kStepChunk> touched;
  std::array<std::array<int, 2>, kStepChunk> strongest;  // hinge, direction: largest term
  std::array<double, kStepChunk> strongest_term;
  for (first = lo; first <= hi && !overflow; first += count) {
    count = std::min(kStepChunk, hi - first + 1);
    for (std::size_t j = 0; j < kStepChunk; ++j) {
      P[j].setZero(), Q[j].setZero(), E[j].setZero(), touched[j] = false;
      strongest[j] = {-1, -1}, strongest_term[j] = -1;
    }
    pass_springs([&](std::size_t i, const HingeData& h, std::size_t k, const double* s1,
                     const double* s2, double n1, double n2, const double* g) {
      const int node[2] = {h.node1, h.node2};
      const double* sv[2] = {s1, s2};
      const double n[2] = {n1, n2};
      for (int t = 0; t < 2; ++t) {
        if (!in_pass(node[t]) || !(g[t] > 0)) continue;
        const auto j = static_cast<std::size_t>(node[t] - first);
        const Eigen::Map<const Vec6> u(sv[t]);
        const double kg = h.stiffness[k] * g[t], cg = h.dashpot[k] * g[t];
        const double term = std::max(kg * n[t], cg * n[t]);  // the largest entry's bound
        if (!finite(term)) overflow_at(static_cast<int>(i), static_cast<int>(k), -1);
        if (term > strongest_term[j]) {
          strongest_term[j] = term;
          strongest[j] = {static_cast<int>(i), static_cast<int>(k)};
        }
        P[j] += kg * (u * u.transpose());
        if (h.dashpot[k] > 0) Q[j] += cg * (u * u.transpose());
        touched[j] = true;
      }
    });
    if (overflow) break;
    for (std::size_t ei = 0; ei < spec.elements.size(); ++ei) {
      const ElementSpec& e = spec.elements[ei];
      const int end[2] = {e.node_i, e.node_j};
      bool near = false;
      for (int t = 0; t < 2; ++t)
        near = near || (in_pass(end[t]) && touched[static_cast<std::size_t>(end[t] - first)]);
      if (!near) continue;
      const NodeSpec& a = spec.nodes[static_cast<std::size_t>(e.node_i)];
      const NodeSpec& b = spec.nodes[static_cast<std::size_t>(e.node_j)];
      const double w = element_omega_max(e, a, b, rot);
      if (!(w > 0)) continue;
      const auto me = beam_end_mass(e, beam_geometry(a, b, e), rot);
      for (int t = 0; t < 2; ++t) {
        if (!in_pass(end[t])) continue;
        const auto n = static_cast<std::size_t>(end[t]);
        for (std::size_t c = 0; c < 6; ++c) {
          if ((spec.nodes[n].fixed >> c) & 1U) continue;
          const double term = w * w * me[c] / mass[kDofsPerNode * n + c];
          if (!finite(term)) overflow_at(-1, -1, static_cast<int>(ei));
          E[n - static_cast<std::size_t>(first)](static_cast<Eigen::Index>(c)) += term;
        }
      }
    }
    int best = -1;  // the pass's node that lowers dt_best
    Vec6 top_k, top_c;
    for (int j = 0; j < count; ++j) {
      const auto js = static_cast<std::size_t>(j);
      if (!touched[js]) continue;
      Vec6 v, vk, vc;
      const double springs = top_eigen(P[js], v);
      Block6 all = P[js];
      all.diagonal() += E[js];
      const double omega2 = top_eigen(all, vk);
      const double eta = top_eigen(Q[js], vc);
      if (!finite(springs) || !finite(omega2) || !finite(alpha + eta)) {  // sums of huge terms
        overflow_at(strongest[js][0], strongest[js][1], -1);
        break;
      }
      dt_springs = std::min(dt_springs, quadratic_step(springs, eta));
      const double dt = quadratic_step(omega2, alpha + eta);
      if (dt < dt_best) dt_best = dt, best = first + j, top_k = vk, top_c = vc;
    }
    if (overflow) break;
    if (best < 0) continue;
    // The spring with the largest share of that node's bound.
    double share_max = -1;
    pass_springs([&](std::size_t i, const HingeData& h, std::size_t k, const double* s1,
                     const double* s2, double, double, const double* g) {
      const int t = h.node1 == best ? 0 : h.node2 == best ? 1 : -1;
      if (t < 0) return;
      const Eigen::Map<const Vec6> u(t == 0 ? s1 : s2);
      const double pk = u.dot(top_k), pc = u.dot(top_c);
      const double share =
          (dt_best * dt_best * h.stiffness[k] * pk * pk + 2.0 * dt_best * h.dashpot[k] * pc * pc) *
          g[t];
      if (share > share_max) {
        share_max = share;
        r.governing_hinge = static_cast<int>(i), r.hinge_direction = static_cast<int>(k);
      }
    });
  }

  if (overflow) {
    r.dt_stable = 0, r.dt_hinges = 0, r.issue = StepIssue::kNonFinite;
    return r;
  }
  r.dt_hinges = dt_springs;
  r.dt_stable = std::min(dt_best, r.dt_elements);
  if (!(r.dt_hinges < r.dt_elements)) r.governing_hinge = -1, r.hinge_direction = -1;
  return r;
}

// dt = "auto" (DESIGN §6): the fewest substeps N (a whole number, as a double: it may be beyond
// any integer type for an absurd model) with period / N <= 0.9 dt_stable, and the step derived
// from it, dt = period / N. 0 when there is no such step (dt_stable or frame_period not positive
// and finite); N is not bounded here: frame_substeps() below judges the result.
inline double auto_substeps(double dt_stable, double frame_period) {
  if (!(dt_stable > 0) || !(frame_period > 0) || !std::isfinite(frame_period)) return 0;
  double n = std::ceil(frame_period / (0.9 * dt_stable));
  if (n < 1) n = 1;
  return n;
}

inline double auto_time_step(double dt_stable, double frame_period) {
  const double n = auto_substeps(dt_stable, frame_period);
  return n > 0 ? frame_period / n : 0;
}

// ---- The frame and its substeps (DESIGN §6, §8) ---------------------------------------------
//
// A model runs in I/O frames of frame_period seconds, each N kernel steps of dt: N is a whole
// number, 1 <= N <= kMaxSubsteps, and N dt equals the period to 1e-9 relative (the same test the
// real-time loop and every tool make, through frame_substeps, the one place the rule lives).
// kMaxSubsteps = 10^6 per frame: at 1 kHz that is a step of 1 ns, 10^9 kernel steps per second,
// beyond any machine (a step of the 104-element demo frame takes about 3 us; the loop runs 9 per
// frame). A model that needs more (nodes 1e-12 m apart want dt = 1e-29 s) cannot run and must
// be refused before it tries; N also has to fit the loop's int and the logs' u32 substeps.
// The frame period itself lies in [kMinFramePeriod, kMaxFramePeriod]: the loop counts whole
// nanoseconds (period * 1e9 in an int64), so 1 us (1 MHz, already beyond a Linux wake-up's
// precision) is the shortest frame and 1000 s (a frame rate of 0.001 Hz) the longest that is
// still an I/O frame of a monitoring loop.
inline constexpr long long kMaxSubsteps = 1000000;
inline constexpr double kMinFramePeriod = 1e-6;    // s
inline constexpr double kMaxFramePeriod = 1e3;     // s
inline constexpr double kSubstepTolerance = 1e-9;  // |N dt - period| <= this x period

enum class SubstepError : std::uint8_t {
  kNone,
  kBadPeriod,        // frame_period not finite, or outside [kMinFramePeriod, kMaxFramePeriod]
  kBadTimeStep,      // dt not finite and positive
  kLongerThanFrame,  // dt > period (beyond the tolerance): less than one step per frame
  kNotWhole,         // period / dt not a whole number to kSubstepTolerance
  kTooMany,          // period / dt above kMaxSubsteps
};

struct Substeps {
  long long count = 0;  // N, 1..kMaxSubsteps when error == kNone, else 0
  double ratio = 0;     // period / dt as computed (inf or NaN for absurd inputs)
  SubstepError error = SubstepError::kNone;
  constexpr bool ok() const { return error == SubstepError::kNone; }
};

inline Substeps frame_substeps(double dt, double frame_period) {
  Substeps s;
  if (!(frame_period >= kMinFramePeriod && frame_period <= kMaxFramePeriod)) {
    s.error = SubstepError::kBadPeriod;
    return s;
  }
  if (!(dt > 0) || !std::isfinite(dt)) {
    s.error = SubstepError::kBadTimeStep;
    return s;
  }
  s.ratio = frame_period / dt;
  if (!(s.ratio <= static_cast<double>(kMaxSubsteps) + 0.5)) {  // also inf
    s.error = SubstepError::kTooMany;
    return s;
  }
  if (dt > frame_period * (1 + kSubstepTolerance)) {
    s.error = SubstepError::kLongerThanFrame;
    return s;
  }
  const double n = std::round(s.ratio);  // >= 1 here
  if (!(std::abs(n * dt - frame_period) <= kSubstepTolerance * frame_period)) {
    s.error = SubstepError::kNotWhole;
    return s;
  }
  s.count = static_cast<long long>(n);
  return s;
}

constexpr const char* to_string(SubstepError e) {
  switch (e) {
    case SubstepError::kNone:
      return "ok";
    case SubstepError::kBadPeriod:
      return "the frame period is not between 1 us and 1000 s (frame rate 0.001 Hz to 1 MHz)";
    case SubstepError::kBadTimeStep:
      return "dt is not a finite positive number";
    case SubstepError::kLongerThanFrame:
      return "dt is longer than the frame";
    case SubstepError::kNotWhole:
      return "dt does not divide the frame into a whole number of substeps";
    case SubstepError::kTooMany:
      return "more than 1000000 substeps per frame";
  }
  return "unknown";
}

}  // namespace ntn
