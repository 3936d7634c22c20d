// Numbers beyond double, checked as the kernel computes them: stages
// check_element_numbers (stiffness terms, end masses and highest frequency of every element),
// assemble_mass (the lumped mass, finite and normal), check_force_numbers (gravity and loads as
// forces) and check_hinge_spring_numbers (k / m and c / m of every hinge spring).
#include "compile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "check_numbers.hpp"
#include "messages.hpp"
#include "ntn/beam.hpp"
#include "ntn/hinge.hpp"
#include "ntn/modal/assembly.hpp"
#include "ntn/model.hpp"

namespace ntn::modelc::compile {

bool check_derived(DiagnosticSink& L, double v, const std::string& what,
                   const std::vector<Factor>& f, bool normal) {
  const bool over = !std::isfinite(v);
  const bool under = normal && !over && !(std::abs(v) >= std::numeric_limits<double>::min());
  if (!over && !under) return true;
  std::size_t blame = 0;
  double worst = -std::numeric_limits<double>::infinity();
  std::string all;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double c = f[i].power * std::log10(std::abs(f[i].value)) * (under ? -1.0 : 1.0);
    if (c > worst) worst = c, blame = i;
    all += (i > 0 ? ", " : "") + f[i].name + " = " + num(f[i].value) + f[i].unit;
  }
  const Factor& b = f[blame];
  L.error(b.at, b.name + " = " + num(b.value) + b.unit +
                    (over ? " gives a non-finite " + what + " (" + all +
                                "): beyond the largest double, 1.8e308"
                          : " is too small: it gives a zero or subnormal " + what + " (" + all +
                                "), below the smallest normal double 2.2e-308"));
  return false;
}
// What the kernel derives from each element, checked before anything uses it: length,
// stiffness terms, end masses, the element's highest frequency (one error per member).
void check_element_numbers(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  const ModelDescription& d = comp.d;
  for (std::size_t mi = 0; mi < p.members.size(); ++mi) {
    const Member& m = p.members[mi];
    const MemberInfo& info = d.members[mi];
    const Material& ma =
        p.materials[static_cast<std::size_t>(comp.ids.materials.at(m.material.id))];
    const Section se =
        m.leaning_area ? leaning_section(m)
                       : p.sections[static_cast<std::size_t>(comp.ids.sections.at(m.section.id))];
    const std::string of = " of member " + m.id.id;
    for (int k = 0; k < info.element_count; ++k) {
      const ElementSpec& e = d.elements[static_cast<std::size_t>(info.first_element + k)];
      const NodeSpec& na = d.nodes[static_cast<std::size_t>(e.node_i)];
      const NodeSpec& nb = d.nodes[static_cast<std::size_t>(e.node_j)];
      const BeamGeometry g = beam_geometry(na, nb, e);
      const double l = g.length;
      if (!std::isfinite(l)) {
        L.error(m.nodes_at, "the length of member " + m.id.id +
                                " is beyond the largest double (1.8e308 m): its nodes' "
                                "coordinates are too far apart");
        break;
      }
      const Factor E{"E", e.E, 1, ma.E_at, " Pa"}, G{"G", e.G, 1, ma.G_at, " Pa"};
      const Factor rho{"rho", e.rho, 1, ma.rho_at, " kg/m^3"}, A{"A", e.A, 1, se.A_at, " m^2"};
      const Factor Iy{"Iy", e.Iy, 1, se.Iy_at, " m^4"}, Iz{"Iz", e.Iz, 1, se.Iz_at, " m^4"};
      const Factor J{"J", e.J, 1, se.J_at, " m^4"};
      auto len = [&](int power) {
        return Factor{"l", l, power, m.nodes_at, " m (element length)"};
      };
      auto inv = [](Factor f) {
        f.power = -f.power;
        return f;
      };
      const BeamStiffness ks = beam_stiffness(e, l);
      bool ok =
          check_derived(L, ks.axial, "axial stiffness E A / l" + of, {E, A, len(-1)}, false) &&
          check_derived(L, ks.torsion, "torsional stiffness G J / l" + of, {G, J, len(-1)}, false);
      for (int plane = 0; ok && plane < 2; ++plane) {
        const auto& t = plane == 0 ? ks.xy : ks.xz;
        const Factor& I = plane == 0 ? Iz : Iy;
        const double shear = plane == 0 ? e.shear_area_y : e.shear_area_z;
        std::vector<Factor> f{E, I, len(-3)};
        if (shear > 0)
          f.push_back(inv(G)), f.push_back(inv(Factor{"kappa A", shear, 1, se.shear_at, " m^2"}));
        double worst = 0;
        for (double v : t)
          worst = std::isfinite(v) ? std::max(worst, std::abs(v)) : v;
        ok = check_derived(L, worst, "bending stiffness 12 E " + I.name + " / (l^3 (1 + Phi))" + of,
                           f, false);
      }
      if (!ok) break;
      const auto me = beam_end_mass(e, g, d.settings.rotary_inertia);
      ok = check_derived(L, me[0], "end mass rho A l / 2" + of, {rho, A, len(1)}, true);
      const bool rotations = e.geometry != Geometry::kLeaning;  // a leaning column's may be 0
      for (std::size_t c = 3; ok && rotations && c < 6; ++c) {
        Factor I{"Iy + Iz", e.Iy + e.Iz, 1, se.Iy_at, " m^4"};
        ok =
            check_derived(L, me[c], "rotational end mass rho (Iy + Iz) l / 2 + rho A l^3 / 78" + of,
                          {rho, A, I, len(1)}, true);
      }
      if (!ok) break;
      const double w = element_omega_max(e, na, nb, d.settings.rotary_inertia);
      if (!check_derived(
              L, w, "highest frequency sqrt(lambda_max(M^-1 K)) (about sqrt(E / rho) / l)" + of,
              {E, inv(rho), len(-1)}, true))
        break;
    }
  }
}

// The kernel's lumped mass (ntn::assemble_lumped_mass), kept for the later stages.
void assemble_mass(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  const ModelDescription& d = comp.d;
  std::vector<double>& mass = comp.mass;
  mass = modal::lumped_mass(d.view());
  // Point masses add up with the elements' masses on a node: the sum must stay finite, and be
  // 0 (no mass) or a normal number (1 / m finite).
  for (std::size_t i = 0; i < d.nodes.size(); ++i) {
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      const double m = mass[i * kDofsPerNode + k];
      if (m == 0 || (m >= std::numeric_limits<double>::min() && std::isfinite(m))) continue;
      L.error(i < p.nodes.size() ? p.nodes[i].at : Where{},
              "the lumped mass of " + d.describe_node(static_cast<int>(i)) + " in " +
                  std::string(kDofNames[k]) + " (its members' masses and point masses added up) " +
                  (std::isfinite(m) ? "is " + num(m) +
                                          " kg, subnormal: too small to be a mass (give 0 or at "
                                          "least 2.2e-308)"
                                    : std::string("is beyond the largest double, 1.8e308")));
      break;
    }
  }
}

// Gravity and nodal loads as forces: M g f(t) and value f(t) must be finite (f: the largest
// |value| of the time function scaling them, 1 without).
void check_force_numbers(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const SourceModel& p = comp.p;
  const ModelDescription& d = comp.d;
  const Settings& s = comp.d.settings;
  const std::vector<double>& mass = comp.mass;
  auto function_peak = [&](int f) {
    double peak = 1;
    if (f < 0) return peak;
    const TimeFunctionSpec& tf = d.time_functions[static_cast<std::size_t>(f)];
    peak = 0;
    for (int k = 0; k < tf.count; ++k)
      peak = std::max(peak, std::abs(d.time_points[static_cast<std::size_t>(tf.first + k)].value));
    return peak;
  };
  const double g_peak = function_peak(s.gravity_function);
  const double g_max =
      std::max({std::abs(s.gravity[0]), std::abs(s.gravity[1]), std::abs(s.gravity[2])});
  if (g_max > 0) {
    const double m_max = *std::max_element(mass.begin(), mass.end());
    std::vector<Factor> f{{"|gravity|", g_max, 1, p.model.gravity_at, " m/s^2"},
                          {"the largest nodal mass", m_max, 1, p.model.gravity_at, " kg"}};
    if (s.gravity_function >= 0)
      f.push_back({"the largest |value| of gravity_function", g_peak, 1, p.model.gravity_at, ""});
    (void)check_derived(L, g_max * m_max * g_peak, "gravity force M g", f, false);
  }
  for (std::size_t i = 0; i < d.loads.size(); ++i) {
    const LoadSpec& l = d.loads[i];
    (void)check_derived(L, l.value * function_peak(l.time_function),
                        "load (value times the largest |value| of its time function)",
                        {{"value", l.value, 1, comp.load_at[i], " N (or N m)"},
                         {"the largest |value| of its time function",
                          function_peak(l.time_function), 1, comp.load_at[i], ""}},
                        false);
  }
}

// Hinge springs against the masses they join: k w and c w (w = b^T M^-1 b = n1 + n2 of the
// kernel's scaled_spring_direction) are the spring's own frequency^2 and damping rate, the
// seeds of its stable-step terms: beyond double, there is no step to compute.
void check_hinge_spring_numbers(Compilation& comp) {
  DiagnosticSink& L = comp.L;
  const ModelDescription& d = comp.d;
  const Settings& s = comp.d.settings;
  const std::vector<double>& mass = comp.mass;
  for (std::size_t hi = 0; hi < d.hinges.size(); ++hi) {
    HingeData hd;
    if (!make_hinge_data(d.hinges[hi], s, d.nodes.size(), d.curves, d.curve_points, hd)) continue;
    for (std::size_t k = 0; k < kDofsPerNode; ++k) {
      if (!((hd.springs >> k) & 1U)) continue;
      double s1[6], s2[6], n1 = 0, n2 = 0;
      if (!scaled_spring_direction(hd, k, d.nodes, mass, s1, s2, n1, n2)) continue;  // massless
      const double w = n1 + n2;
      const std::string of = " of " + d.describe_hinge(static_cast<int>(hi)) + ", direction " +
                             std::string(kDofNames[k]);
      const HingeBehaviour b = d.hinges[hi].behaviour[k];
      const std::string unit = k < 3 ? " N/m" : " N m/rad";
      const Factor inv_mass{"1/m1 + 1/m2 (along the direction)", w, 1, comp.dir_at[hi][k], " 1/kg"};
      const Factor stiff{b == HingeBehaviour::kRigid     ? "the penalty stiffness"
                         : b == HingeBehaviour::kCurve   ? "the curve's steepest soft slope"
                         : b == HingeBehaviour::kPlastic ? "plastic (elastic stiffness)"
                         : b == HingeBehaviour::kRigidPlastic
                             ? "the penalty stiffness (rigid-plastic)"
                             : "linear",
                         hd.stiffness[k], 1, comp.dir_at[hi][k], unit};
      if (!check_derived(L, hd.stiffness[k] * w, "frequency^2 k (1/m1 + 1/m2)" + of,
                         {stiff, inv_mass}, false))
        continue;
      (void)check_derived(
          L, hd.dashpot[k] * w, "damping rate c (1/m1 + 1/m2)" + of,
          {{"dashpot", hd.dashpot[k], 1, comp.dir_at[hi][k], k < 3 ? " N s/m" : " N m s/rad"},
           inv_mass},
          false);
    }
  }
}

}  // namespace ntn::modelc::compile
