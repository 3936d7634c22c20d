// Stable time step of the central difference method (DESIGN §6, seed S 9-10).
#pragma once

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
double element_omega_max(const ElementSpec& e, const NodeSpec& a, const NodeSpec& b,
                         bool rotary_inertia);

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

// With C = alpha M + beta K_el as well: a mode of circular frequency omega has the modal damping
// 2 xi omega = alpha + beta omega^2, and the condition 4 M - 2 dt C - dt^2 K > 0 (below) reads
// (4 - 2 dt alpha) > (dt^2 + 2 dt beta) omega^2 mode by mode, hardest at the top mode: so
// dt^2 omega^2 + 2 dt (alpha + beta omega^2) < 4 with omega an upper bound of omega_max (exact for
// one element's top mode, whose damping ratio is alpha / (2 omega) + beta omega / 2). beta = 0
// gives the step above to the bit. 0 for a negative or NaN beta, or an eta beyond double.
inline double damped_stable_step(double omega, double alpha, double beta) {
  if (!(beta >= 0)) return 0;
  if (beta == 0) return damped_stable_step(omega, alpha);
  if (!(omega > 0) || !(alpha >= 0)) return 0;
  const double eta = alpha + beta * (omega * omega);
  if (!(eta <= std::numeric_limits<double>::max())) return 0;
  return damped_stable_step(omega, eta);
}

// The alpha that bounds the step. With damping_velocity = "central" alpha M acts at v_n, so a_n
// solves M_e a_n = R_n - alpha M v_{n-1/2} - C' v_{n-1/2}, M_e = (1 + alpha dt/2) M, C' the lagged
// rest (beta K_el, the dashpots as the bound takes them): the lagged scheme with mass M_e and
// damping alpha M + C', whose condition 4 M_e - 2 dt (alpha M + C') - dt^2 K > 0 (below) is
// 4 M - 2 dt C' - dt^2 K > 0: alpha drops out. One DOF: (1 + c/2) z^2 - (2 - h^2) z + (1 - c/2),
// h = omega dt, c = alpha dt, whose roots lie in the unit circle (Jury: |1 - c/2| < 1 + c/2,
// h^2 > 0, 4 - h^2 > 0) for dt < 2 / omega and any alpha >= 0. The hinge dashpots at t_n
// (dashpot.hpp) keep their lagged term in the bound: exact at t_n, one dashpot drops out the same
// way, so the lagged term is a margin. Lagged: alpha itself (S 3).
constexpr double stable_step_alpha(const Settings& s) {
  return s.damping_velocity == DampingVelocity::kCentral ? 0.0 : s.alpha;
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
  double dt_elements = 0;      // s, the elements' bound alone (no element: 2 / alpha, or 1e300)
  double dt_hinges = 1e300;    // s, the hinges' springs' bound alone (1e300: no spring)
  int governing_hinge = -1;    // hinge with the largest share of the governing node's bound,
                               // or -1 when the elements' part is the larger
  int hinge_direction = -1;    // its local direction 0..5
  StepIssue issue = StepIssue::kNone;  // dt_stable = 0 because of ... (governing_* name where)
};

// The elements' bound alone: max_e omega_e and the damped step (dt_hinges stays 1e300), and the
// seed's CFL estimate beside it. Without elements only alpha bounds it: 2 / alpha, 1e300 for
// alpha = 0 (governing_element and cfl_element stay -1).
StableStepReport stable_time_step(const SpecView& spec);

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
//     u^T C u <= sum_n y_n^T (alpha I + beta E_n + Q_n) y_n     (C = alpha M + beta K_el + C_s).
// Central difference with the damping lagged to v_{n-1/2} (S 3, the dashpots too; alpha is
// stable_step_alpha's) keeps
// F = 1/2 v^T (M - dt/2 C - dt^2/4 K) v + 1/2 u_bar^T K u_bar non-increasing
// (F_{n+1/2} - F_{n-1/2} = -dt/4 (v+ + v-)^T C (v+ + v-), u_bar = (u_n + u_{n+1}) / 2), so
// 4 M - 2 dt C - dt^2 K > 0 is sufficient for stability with any symmetric C >= 0, K >= 0. It
// holds when, at every node n with a spring,
//     dt^2 omega_n^2 + 2 dt eta_n < 4,
//     omega_n^2 = lambda_max(E_n + P_n),   eta_n = alpha + lambda_max(beta E_n + Q_n),
// i.e. dt < dt_n = (2 / omega_n) (sqrt(1 + xi_n^2) - xi_n), xi_n = eta_n / (2 omega_n), and
// below the elements' own step at the others: dt_stable = min(dt_elements, min_n dt_n). A
// strict bound on the assembled system, with or without NTN coupling (constraints only lower
// omega_max), and never above a spring's own two-node step (one of its two nodes gets g n >= w).
// (lambda_max(A + B) <= lambda_max(A) + lambda_max(B) makes the node's two eigenvalues together
// a bound of lambda_max(dt^2 (E_n + P_n) + 2 dt (alpha I + beta E_n + Q_n)). The springs' own
// dashpots are the hinges' c, never scaled by beta: beta multiplies the elements' K_el alone,
// hence beta E_n, not beta (E_n + P_n).)

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

StableStepReport stable_time_step(const SpecView& spec, std::span<const double> mass);

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
