// The modal check's outputs: the table a person reads, the JSON summary, the spectrum as CSV.
#include <cstdio>
#include <fstream>
#include <string>

#include "json.hpp"  // tools/io
#include "ntn/modecheck/modecheck.hpp"
#include "options.hpp"

namespace ntn::modecheck {

using detail::num;

namespace {

constexpr const char* kAxes[] = {"x", "y", "z"};

std::string json_string(const std::string& s) {
  return json::quoted(s);
}

std::string json_number(double v) {
  return num(v, "%.10g");
}

template <class T>
std::string json_optional(const std::optional<T>& v, double scale = 1) {
  return v ? json_number(scale * *v) : std::string("null");
}

std::string spectrum_text(const Report& r) {
  const Identification& id = r.identification;
  const std::size_t n = id.channels.size();
  std::string s = id.method == "FDD" ? "FDD: first singular value of the " + std::to_string(n) +
                                           " x " + std::to_string(n) + " cross-spectral matrix"
                                     : "PSD of " + id.channels.front();
  s += "; " + std::string(spectral::to_string(id.grid.window)) + " window, line spacing " +
       num(id.grid.df(), "%.4g") + " Hz, " + std::to_string(id.grid.segments) + " segment" +
       (id.grid.segments == 1 ? "" : "s") + " of " +
       num(static_cast<double>(id.grid.segment) / id.grid.fs, "%.4g") + " s; peaks searched in " +
       num(id.f_min, "%.4g") + "-" + num(id.f_max, "%.4g") + " Hz";
  return s;
}

}  // namespace

std::string format_table(const Report& r) {
  const Options& o = r.options;
  std::string s = "ntn-check-modes  model " + r.model_name + " (" + r.model_file + "), response " +
                  r.response_file + "\n";
  s += "  record    " + num(r.duration, "%.4g") + " s at " + num(r.fs, "%.6g") + " Hz; " +
       std::to_string(r.selection.channels.size()) + " channel" +
       (r.selection.channels.size() == 1 ? "" : "s") +
       (r.kind != Kind::kOther ? std::string(" (") + to_string(r.kind) + ")" : std::string()) + ":";
  for (const ChannelInfo& c : r.selection.channels)
    s += " " + c.name + (c.location.empty() ? "" : " [" + c.location + "]");
  s += "\n";
  s += "  spectrum  " + spectrum_text(r) + "\n";
  s += "  modes     the first " + std::to_string(r.modes.size()) + " of the model" +
       (o.direction >= 0 ? std::string(" with effective mass along ") + kAxes[o.direction] +
                               " >= " + num(100 * o.min_mass_fraction, "%.3g") + " %"
                         : std::string()) +
       "\n";
  s += "  rule      nearest peak within +-" + num(100 * o.search_band, "%.3g") +
       " % of the model frequency; pass: |error| <= " + num(100 * o.tolerance, "%.3g") + " %" +
       (r.selection.shapes ? ", MAC >= " + num(o.min_mac, "%.3g") : std::string(" (no shapes)")) +
       ", above noise at a false alarm of " + num(100 * o.false_alarm, "%.3g") + " %\n\n";
  s += " mode   model Hz  ident. Hz   error %  damping %  model zeta %    MAC  mass %  x floor "
       "(noise)  verdict\n";
  for (const ModeCheck& c : r.modes) {
    char line[256];
    std::snprintf(line, sizeof line, " %4d  %9.4f  %9s  %8s  %9s  %12.2f  %5s  %6.1f  ", c.number,
                  c.model_hz, c.found ? num(c.identified_hz, "%.4f").c_str() : "-",
                  c.found ? num(100 * c.error, "%+.3f").c_str() : "-",
                  c.damping ? (num(100 * *c.damping, "%.2f") +
                               (c.resolution_ratio && *c.resolution_ratio > 0.25 ? "*" : ""))
                                  .c_str()
                            : "-",
                  100 * c.model_damping, c.mac ? num(*c.mac, "%.3f").c_str() : "-", c.mass_percent);
    s += line;
    char noise[48] = "                 ";
    if (c.above_floor && c.noise_threshold) {
      std::snprintf(noise, sizeof noise, "%7s (%5s)  ", num(*c.above_floor, "%.3g").c_str(),
                    num(*c.noise_threshold, "%.3g").c_str());
    }
    s += noise;
    s += c.pass ? "ok" : "FAIL: " + c.verdict;
    s += "\n";
  }
  s += "\n";
  for (const std::string& n : r.notes)
    s += "  note: " + n + "\n";
  s += r.summary + "\n";
  return s;
}

std::string to_json(const Report& r) {
  const Options& o = r.options;
  const Identification& id = r.identification;
  std::string s = "{\n";
  s += "  \"model\": " + json_string(r.model_name) + ",\n";
  s += "  \"model_file\": " + json_string(r.model_file) + ",\n";
  s += "  \"response_file\": " + json_string(r.response_file) + ",\n";
  s += "  \"fs_hz\": " + json_number(r.fs) + ",\n";
  s += "  \"duration_s\": " + json_number(r.duration) + ",\n";
  s += "  \"method\": " + json_string(id.method) + ",\n";
  s += "  \"kind\": " + json_string(to_string(r.kind)) + ",\n";
  s += "  \"channels\": [";
  for (std::size_t k = 0; k < r.selection.channels.size(); ++k)
    s += (k ? ", " : "") + json_string(r.selection.channels[k].name);
  s += "],\n";
  s += "  \"shapes\": " + std::string(r.selection.shapes ? "true" : "false") + ",\n";
  s += "  \"window\": " + json_string(std::string(spectral::to_string(id.grid.window))) + ",\n";
  s += "  \"resolution_hz\": " + json_number(id.grid.df()) + ",\n";
  s += "  \"segments\": " + std::to_string(id.grid.segments) + ",\n";
  s += "  \"tolerance_percent\": " + json_number(100 * o.tolerance) + ",\n";
  s += "  \"min_mac\": " + json_number(o.min_mac) + ",\n";
  s += "  \"search_band_percent\": " + json_number(100 * o.search_band) + ",\n";
  s += "  \"false_alarm_percent\": " + json_number(100 * o.false_alarm) + ",\n";
  s += "  \"direction\": " +
       (o.direction >= 0 ? json_string(kAxes[o.direction]) : std::string("null")) + ",\n";
  s += "  \"modes\": [";
  for (std::size_t k = 0; k < r.modes.size(); ++k) {
    const ModeCheck& c = r.modes[k];
    s += k ? ",\n" : "\n";
    s += "    {\"mode\": " + std::to_string(c.number) +
         ", \"model_hz\": " + json_number(c.model_hz) +
         ", \"identified_hz\": " + (c.found ? json_number(c.identified_hz) : "null") +
         ", \"error_percent\": " + (c.found ? json_number(100 * c.error) : "null") +
         ", \"damping_percent\": " + json_optional(c.damping, 100) +
         ", \"model_damping_percent\": " + json_number(100 * c.model_damping) +
         ", \"mac\": " + json_optional(c.mac) +
         ", \"mass_percent\": " + json_number(c.mass_percent) +
         ", \"above_floor\": " + json_optional(c.above_floor) +
         ", \"noise_threshold\": " + json_optional(c.noise_threshold) +
         ", \"pass\": " + (c.pass ? "true" : "false") + ", \"verdict\": " + json_string(c.verdict) +
         "}";
  }
  s += "\n  ],\n  \"notes\": [";
  for (std::size_t k = 0; k < r.notes.size(); ++k)
    s += (k ? ", " : "") + json_string(r.notes[k]);
  s += "],\n";
  s += "  \"pass\": " + std::string(r.pass ? "true" : "false") + ",\n";
  s += "  \"summary\": " + json_string(r.summary) + "\n}\n";
  return s;
}

std::string modes_csv_path(const std::string& spectrum_path) {
  std::string stem = spectrum_path;
  const auto slash = stem.find_last_of('/');
  const auto dot = stem.find_last_of('.');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) stem.resize(dot);
  return stem + "_modes.csv";
}

void write_spectrum_csv(const std::string& path, const Report& r) {
  const Identification& id = r.identification;
  // Units: a PSD of a channel in u is in u^2/Hz; the singular values share the channels' unit
  // when they all have the same.
  std::string common = r.selection.channels.empty() ? "" : r.selection.channels.front().unit;
  for (const ChannelInfo& c : r.selection.channels)
    if (c.unit != common) common.clear();
  const auto psd_unit = [](const std::string& u) {
    return u.empty() ? std::string("1/Hz") : u + "^2/Hz";
  };
  {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw InputError("cannot write the spectrum file '" + path + "'");
    out << "frequency[Hz]";
    for (std::size_t i = 0; i < id.singular.size(); ++i)
      out << ",s" << (i + 1) << '[' << psd_unit(common) << ']';
    for (std::size_t c = 0; c < id.channels.size(); ++c) {
      out << ",psd_" << id.channels[c] << '['
          << psd_unit(c < r.selection.channels.size() ? r.selection.channels[c].unit : "") << ']';
    }
    out << '\n';
    const std::size_t lines = id.spectrum.values.size();
    for (std::size_t k = 0; k < lines; ++k) {
      out << num(id.grid.frequency(k), "%.10g");
      for (const spectral::Spectrum& sv : id.singular)
        out << ',' << num(sv.values[k], "%.9g");
      for (const spectral::Spectrum& p : id.auto_psd)
        out << ',' << num(p.values[k], "%.9g");
      out << '\n';
    }
    if (!out) throw InputError("cannot write the spectrum file '" + path + "'");
  }
  const std::string modes = modes_csv_path(path);
  std::ofstream out(modes, std::ios::binary);
  if (!out) throw InputError("cannot write the modes file '" + modes + "'");
  out << "mode,model_hz,identified_hz,error_percent,damping_percent,mac,pass\n";
  for (const ModeCheck& c : r.modes) {
    out << c.number << ',' << num(c.model_hz, "%.10g") << ','
        << (c.found ? num(c.identified_hz, "%.10g") : "") << ','
        << (c.found ? num(100 * c.error, "%.6g") : "") << ','
        << (c.damping ? num(100 * *c.damping, "%.6g") : "") << ','
        << (c.mac ? num(*c.mac, "%.6g") : "") << ',' << (c.pass ? 1 : 0) << '\n';
  }
  if (!out) throw InputError("cannot write the modes file '" + modes + "'");
}

}  // namespace ntn::modecheck
