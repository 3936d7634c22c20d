#include "ntn/modelc/modes_report.hpp"

#include <cstdio>
#include <string>

#include "json.hpp"  // tools/io
#include "ntn/modal/constraints.hpp"

namespace ntn::modelc {
namespace {

const char* const kDirection[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
const char* const kAxis[3] = {"x", "y", "z"};

std::string g(double v) {
  char b[48];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

const char* solver_name(modal::Solver s) {
  return s == modal::Solver::kSparse ? "sparse" : "dense";
}

// {"x": a[0], "y": a[1], "z": a[2]}
template <class Get>
std::string xyz(Get&& get) {
  std::string s = "{";
  for (int d = 0; d < 3; ++d)
    s += std::string(d ? ", " : "") + "\"" + kAxis[d] + "\": " + json::number(get(d));
  return s + "}";
}

// "tied ux, uy; spring rz 2e+07 N m/rad; free ry"
std::string directions_text(const HingeDirections& h) {
  std::string s;
  for (const HingeTreatment t :
       {HingeTreatment::kTied, HingeTreatment::kSpring, HingeTreatment::kFree}) {
    std::string part;
    for (int k = 0; k < 6; ++k) {
      if (h.treatment[static_cast<std::size_t>(k)] != t) continue;
      part += std::string(part.empty() ? "" : ", ") + kDirection[k];
      if (t == HingeTreatment::kSpring)
        part += " " + g(h.stiffness[static_cast<std::size_t>(k)]) + (k < 3 ? " N/m" : " N m/rad");
    }
    if (!part.empty()) s += (s.empty() ? "" : "; ") + std::string(to_string(t)) + " " + part;
  }
  return s;
}

}  // namespace

const char* to_string(HingeTreatment t) {
  switch (t) {
    case HingeTreatment::kTied:
      return "tied";
    case HingeTreatment::kSpring:
      return "spring";
    case HingeTreatment::kFree:
      break;
  }
  return "free";
}

ModesReport modes_report(const ModelDescription& model, int requested) {
  ModesReport rep;
  rep.model_name = model.name;
  rep.model_file = model.source_file;
  rep.requested = requested;
  rep.alpha = model.settings.alpha;
  rep.beta = model.settings.beta;
  modal::ModalOptions o;
  o.modes = requested;
  rep.result = modal::modal_analysis(model.view(), o);
  if (!rep.result.ok()) return rep;
  for (const modal::Mechanism& m : rep.result.mechanisms)
    rep.mechanism_nodes.push_back(model.describe_node(m.node));
  // The same linearization modal_analysis used (exact ties, no penalty springs).
  const modal::HingeLinearization lin = modal::linearize_hinges(model.view());
  for (std::size_t h = 0; h < lin.hinges.size(); ++h) {
    HingeDirections hd;
    if (h < model.hinge_info.size()) hd.name = model.hinge_info[h].name;
    hd.description = model.describe_hinge(static_cast<int>(h));
    for (std::size_t k = 0; k < 6; ++k) {
      const double s = lin.hinges[h].stiffness[k];
      if ((lin.hinges[h].rigid >> k) & 1U) {
        hd.treatment[k] = HingeTreatment::kTied;
      } else if (s > 0) {  // as modal_analysis adds a spring: s > 0
        hd.treatment[k] = HingeTreatment::kSpring;
        hd.stiffness[k] = s;
      } else {
        hd.treatment[k] = HingeTreatment::kFree;
      }
    }
    rep.hinges.push_back(std::move(hd));
  }
  return rep;
}

std::string modes_text(const ModesReport& rep) {
  const modal::ModalResult& r = rep.result;
  std::string s = rep.model_file + ": ";
  if (!r.ok()) return s + "modal analysis failed: " + r.error + "\n";
  s += std::to_string(r.modes()) + " lowest mode" + (r.modes() == 1 ? "" : "s") +
       ", supports and rigid hinge directions tied exactly";
  if (r.modes() < rep.requested)
    s += " (" + std::to_string(rep.requested) + " asked for: the eigenproblem has " +
         std::to_string(r.reduced) + ")";
  s += "\n";
  if (rep.alpha > 0 || rep.beta > 0) {
    s += "damping C = alpha M + beta K_el: alpha = " + g(rep.alpha) +
         " 1/s, beta = " + g(rep.beta) +
         " s (each mode's ratio alpha / (2 omega) + beta omega / 2)\n";
  }
  s += modal::mode_table(r);
  if (!rep.hinges.empty()) {
    s += "hinges (directions in hinge axes, as the modes use them):\n";
    for (const HingeDirections& h : rep.hinges)
      s += "  " + h.description + ": " + directions_text(h) + "\n";
  }
  return s;
}

std::string modes_json(const ModesReport& rep) {
  const modal::ModalResult& r = rep.result;
  std::string s = "{\n";
  s += "  \"schema\": " + json::quoted(kModesSchema) + ",\n";
  s += "  \"model\": " + json::quoted(rep.model_name) + ",\n";
  s += "  \"model_file\": " + json::quoted(rep.model_file) + ",\n";
  s += "  \"requested_modes\": " + std::to_string(rep.requested) + ",\n";
  if (!r.ok()) {
    s += "  \"error\": " + json::quoted(r.error) + "\n}\n";
    return s;
  }
  s += "  \"dofs\": " + std::to_string(r.dofs) + ",\n";
  s += "  \"coordinates\": " + std::to_string(r.coordinates) + ",\n";
  s += "  \"eigenproblem_size\": " + std::to_string(r.reduced) + ",\n";
  s += "  \"rigid_trees\": " + std::to_string(r.trees) + ",\n";
  s += "  \"mechanism_dofs\": " + std::to_string(r.mechanism_dofs) + ",\n";
  s += "  \"condensed\": " + std::to_string(r.condensed) + ",\n";
  s += "  \"solver\": " + json::quoted(solver_name(r.solver)) + ",\n";
  s += "  \"total_mass_kg\": " +
       xyz([&r](int d) { return r.total_mass[static_cast<std::size_t>(d)]; }) + ",\n";
  s += "  \"reachable_mass_kg\": " +
       xyz([&r](int d) { return r.reachable_mass[static_cast<std::size_t>(d)]; }) + ",\n";
  s += "  \"alpha_per_s\": " + json::number(rep.alpha) + ",\n";
  s += "  \"beta_s\": " + json::number(rep.beta) + ",\n";
  s += "  \"modes\": [";
  double cum[3] = {0, 0, 0};
  for (int i = 0; i < r.modes(); ++i) {
    double pct[3];
    for (int d = 0; d < 3; ++d) {
      pct[d] = 100.0 * r.mass_fraction(i, d);
      cum[d] += pct[d];
    }
    s +=
        std::string(i ? "," : "") + "\n    {\"mode\": " + std::to_string(i + 1) +
        ", \"frequency_hz\": " + json::number(r.frequency(i)) +
        ", \"period_s\": " + json::number(r.period(i)) +
        ", \"omega_rad_s\": " + json::number(r.omega(i)) +
        ", \"damping_ratio\": " + json::number(r.damping_ratio(i)) +
        ",\n     \"effective_mass_kg\": " + xyz([&r, i](int d) { return r.effective_mass(i, d); }) +
        ",\n     \"effective_mass_percent\": " + xyz([&pct](int d) { return pct[d]; }) +
        ",\n     \"cumulative_percent\": " + xyz([&cum](int d) { return cum[d]; }) + "}";
  }
  s += r.modes() > 0 ? "\n  ],\n" : "],\n";
  s += "  \"hinges\": [";
  for (std::size_t h = 0; h < rep.hinges.size(); ++h) {
    const HingeDirections& hd = rep.hinges[h];
    s += std::string(h ? "," : "") + "\n    {\"index\": " + std::to_string(h) +
         ", \"name\": " + json::quoted(hd.name) +
         ", \"description\": " + json::quoted(hd.description) + ",\n     \"directions\": {";
    for (std::size_t k = 0; k < 6; ++k) {
      const bool spring = hd.treatment[k] == HingeTreatment::kSpring;
      s += std::string(k ? ", " : "") + "\"" + kDirection[k] +
           "\": {\"treatment\": " + json::quoted(to_string(hd.treatment[k])) +
           ", \"stiffness\": " + (spring ? json::number(hd.stiffness[k]) : "null") + "}";
    }
    s += "}}";
  }
  s += rep.hinges.empty() ? "],\n" : "\n  ],\n";
  s += "  \"mechanisms\": [";
  for (std::size_t m = 0; m < r.mechanisms.size(); ++m) {
    s += std::string(m ? ", " : "") + "{\"node\": " + std::to_string(r.mechanisms[m].node) +
         ", \"description\": " +
         json::quoted(m < rep.mechanism_nodes.size() ? rep.mechanism_nodes[m] : "") +
         ", \"dofs\": [";
    bool first = true;
    for (int k = 0; k < 6; ++k) {
      if (!((r.mechanisms[m].dofs >> k) & 1U)) continue;
      s += std::string(first ? "" : ", ") + json::quoted(kDirection[k]);
      first = false;
    }
    s += "]}";
  }
  s += "],\n  \"notes\": [";
  for (std::size_t k = 0; k < r.notes.size(); ++k)
    s += std::string(k ? ", " : "") + json::quoted(r.notes[k]);
  s += "]\n}\n";
  return s;
}

}  // namespace ntn::modelc
