// Stage add_member_loads: each [[member_loads]] table as the consistent nodal loads of the
// elements its loaded part overlaps, and each element's share as an ntn::ElementLoadSpec (the
// element-force outputs subtract it: K_L T u - f). On each element (local axes, length l, xi = s /
// l) the load q(s), per unit length along the member and linear between q_start at `from` and q_end
// at `to`, gives f = integral of N^T q ds over the overlap: the linear functions 1 - xi, xi for the
// axial force, the cubic Hermite functions of the kernel's bending DOFs for the transverse forces
// and end moments (plane x-y: v, theta_z = dv/dx; plane x-z: w, theta_y = -dw/dx; beam.hpp),
//   N1 = 1 - 3 xi^2 + 2 xi^3, N2 = l (xi - 2 xi^2 + xi^3), N3 = 3 xi^2 - 2 xi^3,
//   N4 = l (xi^3 - xi^2),
// integrated by 3-point Gauss-Legendre (exact to degree 5: a linear load times a cubic). Timoshenko
// elements get the same (Hermite) loads. The forces are rotated to global (the element's
// rotation, ntn::beam_geometry) and added as kernel loads on the element's nodes (at a released
// end: the release node), with the table's time function.
#include <array>
#include <cmath>

#include "compile.hpp"
#include "messages.hpp"
#include "ntn/beam.hpp"

namespace ntn::modelc::compile {
namespace {

using Vec3 = std::array<double, 3>;

// The local end forces [F_i, M_i, F_j, M_j] of a load q_local(s) (linear in s) on an element of
// length l over its part [s0, s1] (0 <= s0 < s1 <= l).
template <class Q>
std::array<double, 12> consistent_forces(double l, double s0, double s1, Q q_local) {
  constexpr double g = 0.7745966692414834;  // sqrt(3 / 5)
  const double pts[3] = {-g, 0.0, g};
  const double wts[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double mid = 0.5 * (s0 + s1), half = 0.5 * (s1 - s0);
  std::array<double, 12> f{};
  for (int k = 0; k < 3; ++k) {
    const double s = mid + half * pts[k];
    const double w = wts[k] * half;
    const double xi = s / l;
    const double n1 = 1 - 3 * xi * xi + 2 * xi * xi * xi;
    const double n2 = l * (xi - 2 * xi * xi + xi * xi * xi);
    const double n3 = 3 * xi * xi - 2 * xi * xi * xi;
    const double n4 = l * (xi * xi * xi - xi * xi);
    const Vec3 q = q_local(s);
    f[0] += w * (1 - xi) * q[0];
    f[6] += w * xi * q[0];
    f[1] += w * n1 * q[1], f[5] += w * n2 * q[1], f[7] += w * n3 * q[1], f[11] += w * n4 * q[1];
    f[2] += w * n1 * q[2], f[4] -= w * n2 * q[2], f[8] += w * n3 * q[2], f[10] -= w * n4 * q[2];
  }
  return f;
}

}  // namespace

void add_member_loads(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  ModelDescription& d = comp.d;
  for (const MemberLoad& ml : p.member_loads) {
    const int mi = comp.ref(comp.ids.members, ml.member, "member");
    int fn = kConstant;
    if (ml.function) fn = comp.ref(comp.ids.functions, *ml.function, "time function");
    if (mi < 0 || (ml.function && fn < 0)) continue;
    const int di = comp.member_index[static_cast<std::size_t>(mi)];
    if (di < 0) continue;  // not meshed: its error was reported
    const MemberInfo& info = d.members[static_cast<std::size_t>(di)];
    const NodeSpec& a = d.nodes[static_cast<std::size_t>(info.start_node)];
    const NodeSpec& b = d.nodes[static_cast<std::size_t>(info.end_node)];
    const double len = std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);

    // The loaded part in metres from the member's start.
    double from = ml.from, to = ml.to;
    if (ml.in_metres) {
      if (to < 0) to = len;  // to_m not given: the end
      bool ok = true;
      for (const auto& [v, w] : {std::pair{from, ml.from_at}, std::pair{ml.to, ml.to_at}}) {
        if (v > len * (1 + kSamePoint)) {
          L.error(w, "must be between 0 and the length of member " + ml.member.id +
                         ", L = " + num(len) + " m (got " + num(v) + " m)");
          ok = false;
        }
      }
      if (!ok) continue;
      to = std::min(to, len);
      if (!(from < to)) {
        L.error(ml.from_at, "from_m = " + num(from) + " must be less than to_m = " + num(to) +
                                " m (the member's length when to_m is not given)");
        continue;
      }
    } else {
      from *= len, to *= len;
    }
    const bool zero = ml.q_start == Vec3{} && ml.q_end == Vec3{};
    if (zero) L.note(ml.at, "the load is zero everywhere: it adds no forces");

    const ElementSpec& first = d.elements[static_cast<std::size_t>(info.first_element)];
    const std::array<double, 9> R0 =
        beam_geometry(d.nodes[static_cast<std::size_t>(first.node_i)],
                      d.nodes[static_cast<std::size_t>(first.node_j)], first)
            .rotation;
    MemberLoadInfo li;
    li.member = di;
    li.first_load = static_cast<int>(d.loads.size());
    // The total force: the integral of q over [from, to] (trapezoid, exact), in global axes.
    Vec3 total;
    for (std::size_t c = 0; c < 3; ++c)
      total[c] = 0.5 * (ml.q_start[c] + ml.q_end[c]) * (to - from);
    if (ml.member_axes) {
      rotate_to_global(R0, total.data(), li.total.data());
    } else {
      li.total = total;
    }
    auto q_at = [&](double s) {  // s: metres from the member's start
      const double r = (s - from) / (to - from);
      Vec3 q;
      for (std::size_t c = 0; c < 3; ++c)
        q[c] = ml.q_start[c] + r * (ml.q_end[c] - ml.q_start[c]);
      return q;
    };
    for (int k = 0; k < info.element_count && !zero; ++k) {
      const ElementSpec& el = d.elements[static_cast<std::size_t>(info.first_element + k)];
      const NodeSpec& ni = d.nodes[static_cast<std::size_t>(el.node_i)];
      const NodeSpec& nj = d.nodes[static_cast<std::size_t>(el.node_j)];
      const BeamGeometry g = beam_geometry(ni, nj, el);
      const double e0 = std::hypot(ni.x - a.x, ni.y - a.y, ni.z - a.z);
      const double s0 = std::max(from, e0), s1 = std::min(to, e0 + g.length);
      if (!(s1 - s0 > kSamePoint * len)) continue;
      const std::array<double, 12> fl =
          consistent_forces(g.length, s0 - e0, s1 - e0, [&](double s) {
            const Vec3 q = q_at(e0 + s);
            if (ml.member_axes) return q;
            Vec3 loc;
            rotate_to_local(g.rotation, q.data(), loc.data());
            return loc;
          });
      d.element_loads.push_back({info.first_element + k, fn, fl});
      for (int end = 0; end < 2; ++end) {
        const int node = end == 0 ? el.node_i : el.node_j;
        for (int part = 0; part < 2; ++part) {
          Vec3 glob;
          rotate_to_global(g.rotation, fl.data() + 6 * end + 3 * part, glob.data());
          for (int c = 0; c < 3; ++c) {
            const double v = glob[static_cast<std::size_t>(c)];
            if (v == 0.0) continue;
            d.loads.push_back({node, 3 * part + c, v, fn});
            comp.load_at.push_back(ml.at);
            if (part == 0) li.nodal[static_cast<std::size_t>(c)] += v;
          }
        }
      }
    }
    li.load_count = static_cast<int>(d.loads.size()) - li.first_load;
    d.member_loads.push_back(li);
  }
}

}  // namespace ntn::modelc::compile
