// The stable step's eigenvalue bounds (time_step.hpp, DESIGN §6): the 12x12 element and 6x6
// node eigenvalue problems, solved once at init with Eigen's SelfAdjointEigenSolver. Compiled
// once here, so that the step's headers do not carry Eigen into every program that includes them.
#include "ntn/time_step.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

namespace ntn {

namespace {

// lambda_max of a symmetric positive semidefinite 6x6 block and its eigenvector; the trace
// (>= lambda_max) and a zero vector if the solver fails.
double top_eigen(const Eigen::Matrix<double, 6, 6>& a, Eigen::Matrix<double, 6, 1>& v) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(a);
  if (eig.info() != Eigen::Success) {
    v.setZero();
    return a.trace();
  }
  v = eig.eigenvectors().col(5);
  return std::max(eig.eigenvalues()(5), 0.0);
}

}  // namespace

double element_omega_max(const ElementSpec& e, const NodeSpec& a, const NodeSpec& b,
                         bool rotary_inertia) {
  const BeamGeometry g = beam_geometry(a, b, e);
  if (g.check != ElementCheck::kOk || !beam_properties_valid(e)) return 0;
  BeamData data;
  data.rotation = g.rotation;
  data.k = beam_stiffness(e, g.length);
  const Matrix12 K = beam_global_stiffness(data);
  const auto m = beam_end_mass(e, g, rotary_inertia);
  // A DOF without stiffness in this element (a leaning column's rotations, which may have no mass
  // either) has no frequency of its own: its row and column of A are 0.
  std::array<bool, 12> stiff{};
  for (int r = 0; r < 12; ++r)
    for (int c = 0; c < 12; ++c)
      stiff[static_cast<std::size_t>(r)] =
          stiff[static_cast<std::size_t>(r)] || K[static_cast<std::size_t>(r * 12 + c)] != 0.0;
  Eigen::Matrix<double, 12, 12> A;  // M^-1/2 K M^-1/2, symmetric
  for (int r = 0; r < 12; ++r) {
    for (int c = 0; c < 12; ++c) {
      const double mr = m[static_cast<std::size_t>(r % 6)], mc = m[static_cast<std::size_t>(c % 6)];
      const bool both = stiff[static_cast<std::size_t>(r)] && stiff[static_cast<std::size_t>(c)];
      A(r, c) = both ? K[static_cast<std::size_t>(r * 12 + c)] / std::sqrt(mr * mc) : 0.0;
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

StableStepReport stable_time_step(const SpecView& spec) {
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
  // No element (a model of point masses and hinges): K_el = 0, so what is left of the bound is
  // the mass-proportional damping's, 2 alpha dt < 4 (quadratic_step: 2 / alpha, or 1e300 when
  // nothing bounds the step); the hinges' springs add theirs below.
  const double alpha = stable_step_alpha(spec.settings);  // 0 with central damping
  r.dt_stable = r.omega_max > 0 ? damped_stable_step(r.omega_max, alpha, spec.settings.beta)
                                : quadratic_step(0.0, alpha);
  r.dt_elements = r.dt_stable;
  // An element without a finite frequency, or damping that leaves no step: refused, never
  // dropped.
  if (!(r.omega_max < std::numeric_limits<double>::infinity()) || !(r.dt_stable > 0)) {
    r.issue = StepIssue::kNonFinite, r.dt_stable = 0, r.dt_elements = 0;
  }
  return r;
}

namespace {

using Block6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// The hinges' part of the stable step (DESIGN §6): per pass of kStepChunk nodes, the springs' and
// dashpots' bound at each node with the elements' terms there, its lowest step and the spring
// that governs it. The workspace is fixed in size (kStepChunk nodes, kStepPartners partners a
// window), on the caller's stack: no heap.
struct HingeStepPasses {
  HingeStepPasses(const SpecView& s, std::span<const double> m, StableStepReport& report)
      : spec(s),
        mass(m),
        r(report),
        nodes(static_cast<int>(s.nodes.size())),
        rot(s.settings.rotary_inertia),
        alpha(stable_step_alpha(s.settings)),
        beta(s.settings.beta) {}

  const SpecView& spec;
  std::span<const double> mass;
  StableStepReport& r;
  const int nodes;
  const bool rot;
  const double alpha, beta;
  // An intermediate result beyond double (a spring of 1e308, a mass of 1e-300): the step is 0
  // with the first hinge direction or element where it showed, never a term left out.
  bool overflow = false;
  int lo = 0, hi = -1;  // the range of nodes that springs touch
  // L = sum of k w u u^T over the springs at a node (u their unit direction there): the pass's
  // nodes first, then the window's partners (ascending).
  std::array<Block6, kStepChunk + kStepPartners> load;
  std::array<int, kStepPartners> partner;
  int first = 0, count = 0, partners = 0;
  double dt_best = 1e300, dt_springs = 1e300;
  std::array<Block6, kStepChunk> P, Q;  // springs, dashpots
  std::array<Vec6, kStepChunk> E;       // elements (the diagonal E_n)
  std::array<bool, kStepChunk> touched;
  std::array<std::array<int, 2>, kStepChunk> strongest;  // hinge, direction: largest term
  std::array<double, kStepChunk> strongest_term;

  static bool finite(double v) { return std::isfinite(v); }

  void overflow_at(int hinge, int direction, int element) {
    if (overflow) return;
    overflow = true;
    r.governing_hinge = hinge, r.hinge_direction = direction;
    if (element >= 0) r.governing_element = element;
  }

  // Calls f(i, h, k, s1, s2, n1, n2) for every spring direction k (k or c > 0) of hinge i if
  // it is valid; false at a massless DOF (issue kMassless) or where k w or c w is not finite
  // (kNonFinite, w = n1 + n2), with the report set to 0 and that hinge and direction.
  template <class F>
  bool springs_of(std::size_t i, F f) {
    HingeData h;
    if (!make_hinge_data(spec.hinges[i], spec.settings, spec.nodes.size(), spec.curves,
                         spec.curve_points, h))
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
  }

  // A massless DOF under a spring (false: the report is final), and the range of nodes that
  // springs touch [lo, hi] (hi < 0: no spring).
  bool find_spring_nodes() {
    lo = nodes, hi = -1;
    for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
      bool any = false;
      if (!springs_of(i, [&](std::size_t, const HingeData&, std::size_t, const double*,
                             const double*, double, double) { any = true; }))
        return false;
      if (!any) continue;
      const HingeSpec& hs = spec.hinges[i];
      lo = std::min(lo, hs.node1), hi = std::max(hi, hs.node1);
      if (hs.node2 != kGround) lo = std::min(lo, hs.node2), hi = std::max(hi, hs.node2);
    }
    return true;
  }

  bool in_pass(int n) const { return n >= first && n < first + count; }
  int load_index(int n) const {
    if (in_pass(n)) return n - first;
    const int* begin = partner.data();
    const int* end = begin + partners;
    const int* p = std::lower_bound(begin, end, n);
    return p != end && *p == n ? kStepChunk + static_cast<int>(p - begin) : -1;
  }
  // The other node of a hinge of the pass: the ground or a node of the pass give -1.
  int other_of(const HingeSpec& hs) const {
    const int o = in_pass(hs.node1) ? hs.node2 : hs.node1;
    return o == kGround || in_pass(o) ? -1 : o;
  }
  bool touches(const HingeSpec& hs) const {
    return in_pass(hs.node1) || (hs.node2 != kGround && in_pass(hs.node2));
  }

  // Adds k w u u^T of hinge i's springs at the nodes that have a load slot.
  void add_load(std::size_t i) {
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
  }

  // The window: the kStepPartners smallest partners above `after`.
  void next_window(int after) {
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
  }

  // The window's partners' loads (a partner of a hinge without springs just gets a slot).
  void add_partner_loads() {
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
  }

  // Calls f(i, h, k, s1, s2, n1, n2, g) for the springs at the pass's nodes whose other node is
  // the ground or a node of the pass (window 0 only) or a partner of this window, with g_1, g_2
  // from tau = n_2 L_2 / (n_1 L_1), L_i = u^T L u along the spring at node i (equal loads if one
  // is zero: a dashpot alone).
  template <class F>
  void visit_window_springs(int window, F f) {
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
  }

  // Calls f(i, h, k, s1, s2, n1, n2, g) once for every spring direction at the pass's nodes:
  // the pass's loads, then window by window the partners' loads and the springs to them.
  template <class F>
  void pass_springs(F f) {
    partners = 0;
    for (int j = 0; j < kStepChunk; ++j)
      load[static_cast<std::size_t>(j)].setZero();
    for (std::size_t i = 0; i < spec.hinges.size(); ++i) {
      if (touches(spec.hinges[i])) add_load(i);
    }
    for (int after = -1, window = 0;; ++window) {
      next_window(after);
      add_partner_loads();
      visit_window_springs(window, f);
      if (partners < kStepPartners) break;
      after = partner[static_cast<std::size_t>(partners - 1)];
    }
  }

  // P_n = sum k g u u^T and Q_n = sum c g u u^T over the springs at each node of the pass, and
  // the spring with the largest term there.
  void add_spring_blocks() {
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
  }

  // E_n: the elements' omega_max^2 m_e / m at the pass's nodes that springs touch.
  void add_element_terms() {
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
  }

  // Each touched node's step from lambda_max(P_n + E_n) and lambda_max(beta E_n + Q_n); the
  // node that lowers dt_best (-1: none) with the eigenvectors of its bound.
  int lower_step(Vec6& top_k, Vec6& top_c) {
    int best = -1;
    for (int j = 0; j < count; ++j) {
      const auto js = static_cast<std::size_t>(j);
      if (!touched[js]) continue;
      Vec6 v, vk, vc;
      const double springs = top_eigen(P[js], v);
      Block6 all = P[js];
      all.diagonal() += E[js];
      const double omega2 = top_eigen(all, vk);
      const double dashpots = top_eigen(Q[js], vc);
      double eta = dashpots;  // lambda_max(beta E_n + Q_n): the dashpots alone when beta = 0
      if (beta != 0) {
        Block6 damp = Q[js];
        damp.diagonal() += beta * E[js];
        eta = top_eigen(damp, vc);
      }
      if (!finite(springs) || !finite(omega2) || !finite(alpha + eta)) {  // sums of huge terms
        overflow_at(strongest[js][0], strongest[js][1], -1);
        break;
      }
      dt_springs = std::min(dt_springs, quadratic_step(springs, dashpots));
      const double dt = quadratic_step(omega2, alpha + eta);
      if (dt < dt_best) dt_best = dt, best = first + j, top_k = vk, top_c = vc;
    }
    return best;
  }

  // The spring with the largest share of node best's bound governs.
  void find_governing_spring(int best, const Vec6& top_k, const Vec6& top_c) {
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

  // One pass over the nodes [first, first + count).
  void pass() {
    add_spring_blocks();
    if (overflow) return;
    add_element_terms();
    Vec6 top_k, top_c;
    const int best = lower_step(top_k, top_c);
    if (overflow || best < 0) return;
    find_governing_spring(best, top_k, top_c);
  }
};

}  // namespace

StableStepReport stable_time_step(const SpecView& spec, std::span<const double> mass) {
  StableStepReport r = stable_time_step(spec);
  if (r.issue != StepIssue::kNone) return r;
  HingeStepPasses h(spec, mass, r);
  if (!h.find_spring_nodes()) return r;
  if (h.hi < 0) return r;  // no spring: the elements' bound as it is
  for (h.first = h.lo; h.first <= h.hi && !h.overflow; h.first += h.count) {
    h.count = std::min(kStepChunk, h.hi - h.first + 1);
    h.pass();
  }
  if (h.overflow) {
    r.dt_stable = 0, r.dt_hinges = 0, r.issue = StepIssue::kNonFinite;
    return r;
  }
  r.dt_hinges = h.dt_springs;
  r.dt_stable = std::min(h.dt_best, r.dt_elements);
  if (!(r.dt_hinges < r.dt_elements)) r.governing_hinge = -1, r.hinge_direction = -1;
  return r;
}

}  // namespace ntn
