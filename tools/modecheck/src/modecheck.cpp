#include "ntn/modecheck/modecheck.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <tuple>

#include <Eigen/SVD>

#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/spectral/error.hpp"
#include "ntn/spectral/fdd.hpp"
#include "ntn/spectral/significance.hpp"
#include "ntn/spectral/welch.hpp"
#include "options.hpp"

namespace ntn::modecheck {

using detail::num;

namespace {

constexpr std::array<const char*, 6> kDofNames = {"ux", "uy", "uz", "rx", "ry", "rz"};
constexpr std::array<const char*, 3> kAxes = {"x", "y", "z"};

Kind kind_of(OutputKind k) {
  switch (k) {
    case OutputKind::kDisplacement:
      return Kind::kDisplacement;
    case OutputKind::kVelocity:
      return Kind::kVelocity;
    case OutputKind::kAcceleration:
    case OutputKind::kAbsoluteAcceleration:
      return Kind::kAcceleration;
    default:
      return Kind::kOther;
  }
}

std::string list_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names)
    s += (s.empty() ? "" : ", ") + n;
  return s;
}

// Every sample of a selected channel finite, and not constant: a channel that does not move (a
// dead sensor, a channel of zeros) has no spectrum, and the mean removal leaves its rounding
// residue, whose local maxima would pass for peaks. Constant: max - min within 4 rounding units
// of the largest |value| (the same value written and read back, or rounded differently).
void check_channel(const spectral::Channels& data, const ChannelInfo& ci) {
  const std::vector<double>& x = data.data[ci.column];
  if (x.empty()) throw InputError("channel '" + ci.name + "' has no samples");
  double lo = x.front(), hi = x.front(), top = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!std::isfinite(x[k])) {
      throw InputError("channel '" + ci.name + "' is " + num(x[k]) + " at sample " +
                       std::to_string(k) + " (t = " + num(static_cast<double>(k) / data.fs) +
                       " s)");
    }
    lo = std::min(lo, x[k]);
    hi = std::max(hi, x[k]);
    top = std::max(top, std::abs(x[k]));
  }
  if (hi - lo <= 4 * std::numeric_limits<double>::epsilon() * top) {
    throw InputError("channel '" + ci.name + "' is constant (a dead sensor?): every sample is " +
                     num(x.front(), "%.9g") + (ci.unit.empty() ? "" : " " + ci.unit) + " over " +
                     num(static_cast<double>(x.size()) / data.fs) +
                     " s; leave it out with --channels");
  }
}

// The spectrum the noise test reads: the PSD (one channel), or the trace of the spectral matrix
// (the channels' auto-spectra added up), whose lines are chi-square at any coherence.
spectral::Spectrum noise_test_spectrum(const Identification& id) {
  if (id.auto_psd.size() <= 1) return id.auto_psd.empty() ? id.spectrum : id.auto_psd.front();
  spectral::Spectrum trace = id.auto_psd.front();
  for (std::size_t c = 1; c < id.auto_psd.size(); ++c)
    for (std::size_t k = 0; k < trace.values.size(); ++k)
      trace.values[k] += id.auto_psd[c].values[k];
  return trace;
}

}  // namespace

const char* to_string(Kind kind) {
  switch (kind) {
    case Kind::kDisplacement:
      return "displacement";
    case Kind::kVelocity:
      return "velocity";
    case Kind::kAcceleration:
      return "acceleration";
    case Kind::kOther:
      break;
  }
  return "other";
}

Selection select_channels(const modelc::ModelDescription* model, const spectral::Channels& data,
                          const std::vector<std::string>& names) {
  // What each channel of the file is, by the model output of the same name.
  std::vector<ChannelInfo> all(data.names.size());
  for (std::size_t c = 0; c < data.names.size(); ++c) {
    all[c].name = data.names[c];
    all[c].column = c;
    if (c < data.units.size()) all[c].unit = data.units[c];
    if (model == nullptr) continue;
    for (std::size_t o = 0; o < model->output_names.size(); ++o) {
      if (model->output_names[o] != data.names[c]) continue;
      const OutputSpec& spec = model->outputs[o];
      all[c].kind = kind_of(spec.kind);
      if (all[c].kind != Kind::kOther) {
        all[c].node = spec.node;
        all[c].dof = spec.dof;
        all[c].location =
            model->describe_node(spec.node) + " " + kDofNames[static_cast<std::size_t>(spec.dof)];
      }
    }
  }

  Selection sel;
  if (!names.empty()) {
    for (const std::string& n : names) {
      const auto it = std::find(data.names.begin(), data.names.end(), n);
      if (it == data.names.end()) {
        throw InputError("unknown channel '" + n + "': " + data.source + " has the channels " +
                         list_names(data.names));
      }
      const auto c = static_cast<std::size_t>(it - data.names.begin());
      for (const ChannelInfo& s : sel.channels)
        if (s.column == c) throw InputError("channel '" + n + "' is given twice");
      sel.channels.push_back(all[c]);
    }
  } else {
    // The most common kind among the channels that map to a node DOF.
    std::array<int, 3> count{};
    for (const ChannelInfo& ci : all)
      if (ci.kind != Kind::kOther) ++count[static_cast<std::size_t>(ci.kind)];
    const auto best =
        static_cast<std::size_t>(std::max_element(count.begin(), count.end()) - count.begin());
    if (count[best] == 0) {
      sel.channels = all;
      if (model != nullptr) {
        sel.notes.push_back(
            "no channel of the response maps to a node DOF of the model: every "
            "channel used, no mode shapes (no MAC)");
      }
    } else {
      for (const ChannelInfo& ci : all)
        if (static_cast<std::size_t>(ci.kind) == best) sel.channels.push_back(ci);
      for (std::size_t k = 0; k < count.size(); ++k) {
        if (k != best && count[k] > 0) {
          sel.notes.push_back(std::to_string(count[k]) + " " + to_string(static_cast<Kind>(k)) +
                              " channel(s) left out: one kind at a time (give --channels)");
        }
      }
    }
  }

  bool mapped = sel.channels.size() >= 2;
  for (const ChannelInfo& ci : sel.channels)
    mapped = mapped && ci.kind != Kind::kOther && ci.kind == sel.channels.front().kind;
  sel.shapes = mapped;
  if (!mapped && sel.channels.size() >= 2 && model != nullptr) {
    sel.notes.push_back(
        "no MAC: the channels are not all node DOFs of one kind (displacement, velocity or "
        "acceleration)");
  }
  if (sel.channels.size() == 1) sel.notes.push_back("one channel: its PSD, no mode shapes");
  return sel;
}

ModelModes model_modes(const modelc::ModelDescription& model, const Selection& selection,
                       const Options& options) {
  if (options.modes < 1) throw InputError("the number of modes to check must be at least 1");
  const int n = options.modes;
  ModelModes out;
  // The lowest few modes first; all of them when a direction filter leaves too few.
  for (const int wanted : {std::max(12, 4 * n), 0}) {
    modal::ModalOptions mo;
    mo.modes = wanted;
    const modal::ModalResult r = modal::modal_analysis(model.view(), mo);
    if (!r.ok()) throw InputError("modal analysis of the model failed: " + r.error);
    out = {};
    std::vector<int> skipped;
    for (int m = 0; m < r.modes() && static_cast<int>(out.number.size()) < n; ++m) {
      double mass = 0;
      if (options.direction >= 0) {
        mass = r.mass_fraction(m, options.direction);
        if (mass < options.min_mass_fraction) {
          skipped.push_back(m + 1);
          continue;
        }
      } else {
        for (int d = 0; d < 3; ++d)
          mass = std::max(mass, r.mass_fraction(m, d));
      }
      out.number.push_back(m + 1);
      out.frequency.push_back(r.frequency(m));
      out.damping.push_back(r.damping_ratio.size() > m ? r.damping_ratio(m) : 0.0);
      out.mass_percent.push_back(100 * mass);
    }
    if (static_cast<int>(out.number.size()) == n || wanted == 0 || r.modes() < wanted) {
      if (!skipped.empty()) {
        std::string s;
        for (int k : skipped)
          s += (s.empty() ? "" : ", ") + std::to_string(k);
        out.notes.push_back("model mode(s) " + s + " left out: effective mass along " +
                            kAxes[static_cast<std::size_t>(options.direction)] + " below " +
                            num(100 * options.min_mass_fraction) + " %");
      }
      if (static_cast<int>(out.number.size()) < n) {
        throw InputError("the model has only " + std::to_string(out.number.size()) + " mode(s)" +
                         (options.direction >= 0
                              ? std::string(" with effective mass along ") +
                                    kAxes[static_cast<std::size_t>(options.direction)] +
                                    " of at least " + num(100 * options.min_mass_fraction) + " %"
                              : std::string()) +
                         "; " + std::to_string(n) + " asked for");
      }
      bool all_mapped = !selection.channels.empty();
      for (const ChannelInfo& ci : selection.channels)
        all_mapped = all_mapped && ci.kind != Kind::kOther;
      if (all_mapped) {
        const int nodes = r.dofs / 6;
        for (int k = 0; k < n; ++k) {
          const int m = out.number[static_cast<std::size_t>(k)] - 1;
          std::array<double, 2> largest{};  // translations, rotations
          for (int node = 0; node < nodes; ++node) {
            for (int d = 0; d < 6; ++d) {
              double& l = largest[d < 3 ? 0 : 1];
              l = std::max(l, std::abs(r.shape(m, node, d)));
            }
          }
          double ratio = 0;
          for (const ChannelInfo& ci : selection.channels) {
            const double top = largest[ci.dof < 3 ? 0 : 1];
            if (top > 0) ratio = std::max(ratio, std::abs(r.shape(m, ci.node, ci.dof)) / top);
          }
          out.visibility.push_back(ratio);
        }
      }
      if (selection.shapes) {
        std::vector<modal::Channel> ch;
        for (const ChannelInfo& ci : selection.channels)
          ch.push_back({ci.node, ci.dof});
        const Eigen::MatrixXd at = modal::shapes_at(r, ch);
        out.shapes.resize(at.rows(), n);
        for (int k = 0; k < n; ++k)
          out.shapes.col(k) = at.col(out.number[static_cast<std::size_t>(k)] - 1);
      }
      return out;
    }
  }
  return out;  // not reached
}

Identification identify(const spectral::Channels& data, const Selection& selection,
                        double resolution_hz, double f_min, double f_max, const Options& options) {
  validate(options);
  if (selection.channels.empty()) throw InputError("no channels to analyse");
  // The numerical floor (README, "Dead channels and the numerical floor"): white rounding noise of
  // one rounding unit (eps |x|max) per channel has the one-sided density 2 (eps |x|max)^2 / fs; s1
  // and the PSD are at most the sum over the channels. A peak must be 1000 times above that.
  double noise = 0;
  for (const ChannelInfo& ci : selection.channels) {
    if (ci.column >= data.data.size()) throw InputError("channel '" + ci.name + "' has no data");
    check_channel(data, ci);
    double top = 0;
    for (const double v : data.data[ci.column])
      top = std::max(top, std::abs(v));
    const double unit = std::numeric_limits<double>::epsilon() * top;
    noise += 2 * unit * unit / data.fs;
  }
  Identification id;
  id.floor = 1e3 * noise;
  // Local maxima below the floor are rounding noise: out, counted, with a note.
  const auto drop_below_floor = [&id] {
    const auto low = [&id](const IdentifiedPeak& p) { return !(p.peak.value >= id.floor); };
    id.below_floor = static_cast<int>(std::count_if(id.peaks.begin(), id.peaks.end(), low));
    id.peaks.erase(std::remove_if(id.peaks.begin(), id.peaks.end(), low), id.peaks.end());
    if (id.below_floor > 0) {
      id.notes.push_back(std::to_string(id.below_floor) +
                         " local maxima left out: below the numerical floor " +
                         num(id.floor, "%.3g") + " u^2/Hz (rounding noise, README)");
    }
  };
  for (const ChannelInfo& ci : selection.channels)
    id.channels.push_back(ci.name);
  spectral::WelchOptions wo;
  const double seg = detail::segment_samples(data.fs, resolution_hz);
  if (!(seg >= 2 && seg <= static_cast<double>(data.samples()))) {
    throw InputError("a resolution of " + num(resolution_hz) + " Hz needs segments of " +
                     detail::count(seg) + " samples; the record has " +
                     std::to_string(data.samples()) + " (at least 2 are needed)");
  }
  wo.segment = static_cast<std::size_t>(seg);
  wo.overlap = options.overlap;
  wo.window = options.window;
  id.f_min = std::max(0.0, f_min);
  id.f_max = std::min(f_max, data.fs / 2);
  spectral::PeakOptions po;
  po.f_min = id.f_min;
  po.f_max = id.f_max;
  po.min_prominence = options.min_prominence;
  po.relative_threshold = options.min_level;
  try {
    spectral::Welch welch(data.fs, wo);
    if (selection.channels.size() == 1) {
      id.method = "PSD";
      id.spectrum = welch.psd(data.data[selection.channels.front().column]);
      id.grid = id.spectrum.grid;
      id.auto_psd.push_back(id.spectrum);
      for (const spectral::Peak& p : spectral::find_peaks(id.spectrum, po))
        id.peaks.push_back({p, spectral::half_power(id.spectrum, p), {}, 0});
      drop_below_floor();
      return id;
    }
    std::vector<std::vector<double>> x;
    for (const ChannelInfo& ci : selection.channels)
      x.push_back(data.data[ci.column]);
    const spectral::CrossSpectralMatrix g = welch.matrix(x);
    const spectral::Fdd f = spectral::fdd(g);
    id.method = "FDD";
    id.grid = g.grid;
    for (std::size_t i = 0; i < g.channels; ++i) {
      id.auto_psd.push_back(g.auto_spectrum(i));
      id.singular.push_back(f.singular_spectrum(i));
    }
    id.spectrum = id.singular.front();
    for (const spectral::OperationalMode& m : spectral::fdd_modes(f, po))
      id.peaks.push_back({m.peak, m.half_power, m.shape, 1});
    // Closely spaced modes: where one mode's tail dominates s1, a weaker neighbour with another
    // shape shows as a peak of s2 (Brincker et al. 2001). s2 peaks count when they reach
    // min_level of the largest s1 value in the range and lie outside the half-power band (at
    // least 2 lines either side) of every s1 peak, where s2 only echoes s1's mode.
    if (g.channels >= 2) {
      const spectral::Spectrum& s1 = id.singular[0];
      const spectral::Spectrum& s2 = id.singular[1];
      double s1_max = 0;
      for (std::size_t k = 0; k < s1.values.size(); ++k) {
        const double fk = id.grid.frequency(k);
        if (fk >= po.f_min && fk <= po.f_max) s1_max = std::max(s1_max, s1.values[k]);
      }
      spectral::PeakOptions po2 = po;
      po2.relative_threshold = 0;
      const std::size_t first_count = id.peaks.size();
      for (const spectral::Peak& p : spectral::find_peaks(s2, po2)) {
        if (p.value < options.min_level * s1_max) continue;
        bool echo = false;
        for (std::size_t q = 0; q < first_count; ++q) {
          const IdentifiedPeak& a = id.peaks[q];
          const double two_lines = 2 * id.grid.df();
          const double lo = std::min(a.peak.frequency - two_lines,
                                     a.half_power ? a.half_power->f_low : a.peak.frequency);
          const double hi = std::max(a.peak.frequency + two_lines,
                                     a.half_power ? a.half_power->f_high : a.peak.frequency);
          echo = echo || (p.frequency >= lo && p.frequency <= hi);
        }
        if (echo) continue;
        Eigen::JacobiSVD<Eigen::MatrixXcd> svd(g.at(p.line), Eigen::ComputeFullU);
        id.peaks.push_back(
            {p, spectral::half_power(s2, p), spectral::real_shape(svd.matrixU().col(1)), 2});
      }
      std::stable_sort(id.peaks.begin(), id.peaks.end(),
                       [](const IdentifiedPeak& a, const IdentifiedPeak& b) {
                         return a.peak.frequency < b.peak.frequency;
                       });
    }
    drop_below_floor();
  } catch (const spectral::Error& e) {
    throw InputError(e.what());
  }
  return id;
}

std::vector<int> match_peaks(const std::vector<double>& model_hz,
                             const std::vector<double>& peak_hz, double search_band) {
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // distance, mode, peak
  for (std::size_t m = 0; m < model_hz.size(); ++m) {
    for (std::size_t p = 0; p < peak_hz.size(); ++p) {
      const double d = std::abs(peak_hz[p] - model_hz[m]) / model_hz[m];
      if (d <= search_band) pairs.emplace_back(d, m, p);
    }
  }
  std::sort(pairs.begin(), pairs.end());  // ties: lower mode, then lower peak first
  std::vector<int> match(model_hz.size(), -1);
  std::vector<bool> used(peak_hz.size(), false);
  for (const auto& [d, m, p] : pairs) {
    if (match[m] >= 0 || used[p]) continue;
    match[m] = static_cast<int>(p);
    used[p] = true;
  }
  return match;
}

Report compare(const ModelModes& model, const Identification& identification,
               const Selection& selection, const Options& options) {
  validate(options);
  Report rep;
  rep.selection = selection;
  rep.identification = identification;
  rep.model = model;
  rep.options = options;
  std::vector<double> peak_hz;
  for (const IdentifiedPeak& p : identification.peaks)
    peak_hz.push_back(p.peak.frequency);
  // Modes the channels do not see take no peak from the others.
  std::vector<double> seen_hz = model.frequency;
  for (std::size_t k = 0; k < seen_hz.size() && k < model.visibility.size(); ++k)
    if (model.visibility[k] < options.min_visibility) seen_hz[k] = std::nan("");
  const std::vector<int> match = match_peaks(seen_hz, peak_hz, options.search_band);
  const bool shapes =
      selection.shapes && model.shapes.cols() == static_cast<Eigen::Index>(model.frequency.size());
  std::string failed;
  int passed = 0;
  const spectral::Spectrum test = noise_test_spectrum(identification);
  for (std::size_t k = 0; k < model.frequency.size(); ++k) {
    ModeCheck c;
    c.number = model.number[k];
    c.model_hz = model.frequency[k];
    c.model_damping = model.damping[k];
    c.mass_percent = model.mass_percent[k];
    std::vector<std::string> why;
    const bool unseen = k < model.visibility.size() && model.visibility[k] < options.min_visibility;
    if (unseen) {
      why.push_back("not seen by the channels: they move " +
                    num(100 * model.visibility[k], "%.2g") +
                    " % of the mode's largest motion (choose other channels, or --direction)");
    } else if (match[k] < 0) {
      why.push_back("not found: no peak within +-" + num(100 * options.search_band, "%.3g") +
                    " % (" + num(c.model_hz * (1 - options.search_band), "%.4f") + "-" +
                    num(c.model_hz * (1 + options.search_band), "%.4f") + " Hz)");
    } else {
      const IdentifiedPeak& p = identification.peaks[static_cast<std::size_t>(match[k])];
      c.found = true;
      c.identified_hz = p.peak.frequency;
      c.error = (c.identified_hz - c.model_hz) / c.model_hz;
      c.frequency_ok = std::abs(c.error) <= options.tolerance;
      if (p.half_power) {
        c.damping = p.half_power->damping;
        c.resolution_ratio = p.half_power->resolution_ratio;
      }
      if (!c.frequency_ok) {
        why.push_back("frequency error " + num(100 * c.error, "%+.2f") + " % exceeds " +
                      num(100 * options.tolerance, "%.3g") + " %");
      }
      const double df = identification.grid.df();
      // Noise or a mode: the peak line over its local floor against the chi-square threshold.
      const std::size_t line = p.peak.line;
      const std::size_t exclude =
          2 + (p.half_power ? static_cast<std::size_t>(
                                  std::ceil((p.half_power->f_high - p.half_power->f_low) / df))
                            : 1);
      const double floor = spectral::local_floor(test, line, exclude);
      const double lines = std::max(1.0, 2 * options.search_band * c.model_hz / df);
      const double dof = spectral::welch_dof(identification.grid);
      c.noise_threshold = spectral::noise_threshold(dof, lines, options.false_alarm);
      c.above_floor = floor > 0 && line < test.values.size()
                          ? test.values[line] / floor
                          : std::numeric_limits<double>::infinity();
      if (!(*c.above_floor >= *c.noise_threshold)) {
        why.push_back("not above the noise: the peak is " + num(*c.above_floor, "%.3g") +
                      " x its local floor, and noise reaches " + num(*c.noise_threshold, "%.3g") +
                      " x in " + num(lines, "%.0f") + " lines with probability " +
                      num(100 * options.false_alarm, "%.3g") + " % (" + num(dof, "%.3g") +
                      " degrees of freedom)");
      }
      if (shapes && p.shape.size() == model.shapes.rows()) {
        c.mac = modal::mac(p.shape, model.shapes.col(static_cast<Eigen::Index>(k)));
        c.mac_ok = *c.mac >= options.min_mac;
        if (!c.mac_ok) {
          why.push_back("MAC " + num(*c.mac, "%.3f") + " below " + num(options.min_mac, "%.3g"));
        }
      }
    }
    c.pass = why.empty();
    if (c.pass) {
      c.verdict = "ok";
      ++passed;
    } else {
      std::string w;
      for (const auto& s : why)
        w += (w.empty() ? "" : "; ") + s;
      c.verdict = w;
      failed += (failed.empty() ? "" : ", ") + std::string("mode ") + std::to_string(c.number) +
                " (" + w + ")";
    }
    rep.modes.push_back(c);
  }
  rep.pass = failed.empty();
  const std::string n = std::to_string(model.frequency.size());
  if (rep.pass) {
    rep.summary = "PASS: " + n + " of " + n + " modes within " +
                  num(100 * options.tolerance, "%.3g") + " %" +
                  (shapes ? ", MAC >= " + num(options.min_mac, "%.3g") : std::string(", no MAC"));
  } else {
    rep.summary = "FAIL: " + std::to_string(passed) + " of " + n + " modes pass; " + failed;
  }
  return rep;
}

Report check_files(const std::string& model_path, const std::string& response_path,
                   const Options& options) {
  namespace fs = std::filesystem;
  validate(options);
  for (const auto& [what, path] : {std::pair<const char*, const std::string&>{"model", model_path},
                                   {"response", response_path}}) {
    std::error_code ec;
    if (!fs::exists(path, ec))
      throw InputError(std::string("cannot read the ") + what + " file '" + path +
                       "': no such file");
    if (fs::is_directory(path, ec))
      throw InputError(std::string("cannot read the ") + what + " file '" + path +
                       "': it is a directory");
    std::ifstream probe(path);
    if (!probe)
      throw InputError(std::string("cannot read the ") + what + " file '" + path +
                       "': permission denied or unreadable");
  }
  const modelc::LoadResult loaded = modelc::load_model(model_path);
  if (!loaded.ok()) {
    std::string s = modelc::format_all(loaded.errors);
    while (!s.empty() && s.back() == '\n')
      s.pop_back();
    throw InputError(s);
  }
  const modelc::ModelDescription& model = *loaded.model;

  spectral::Channels data;
  try {
    data = spectral::read_channels(response_path);
  } catch (const spectral::Error& e) {
    throw InputError(e.what());
  }
  Report rep = check_data(model, data, options);
  rep.model_file = model_path;
  rep.response_file = response_path;
  return rep;
}

Report check_data(const modelc::ModelDescription& model, const spectral::Channels& data,
                  const Options& options) {
  validate(options);
  if (data.data.empty() || !(data.fs > 0))
    throw InputError("the response has no channel, or no sample rate");
  Selection sel = select_channels(&model, data, options.channels);
  ModelModes modes = model_modes(model, sel, options);

  const double lowest = *std::min_element(modes.frequency.begin(), modes.frequency.end());
  const double highest = *std::max_element(modes.frequency.begin(), modes.frequency.end());
  const double nyquist = data.fs / 2;
  if (highest * (1 + options.search_band) >= nyquist) {
    throw InputError("model mode " +
                     std::to_string(modes.number[static_cast<std::size_t>(
                         std::max_element(modes.frequency.begin(), modes.frequency.end()) -
                         modes.frequency.begin())]) +
                     " (" + num(highest) + " Hz, search band up to " +
                     num(highest * (1 + options.search_band)) +
                     " Hz) is not below the record's Nyquist frequency " + num(nyquist) + " Hz");
  }
  std::vector<std::string> notes;
  const double df = resolve_resolution(data, lowest, options, &notes);
  // The lowest mode's search band must hold a spectral line, or no peak can be found in it.
  if (2 * options.search_band * lowest < df) {
    detail::bad_option(options, {"--band", "band", true}, options.search_band, "",
                       ("the search band around mode " +
                        std::to_string(modes.number[static_cast<std::size_t>(
                            std::min_element(modes.frequency.begin(), modes.frequency.end()) -
                            modes.frequency.begin())]) +
                        " (" + num(lowest) + " Hz +- " + num(options.search_band * lowest, "%.3g") +
                        " Hz) is narrower than the line spacing " + num(df) +
                        " Hz; widen --band or refine --resolution")
                           .c_str());
  }
  const Identification id = identify(data, sel, df, lowest * (1 - options.search_band),
                                     highest * (1 + options.search_band), options);
  Report rep = compare(modes, id, sel, options);
  rep.model_name = model.name;
  rep.model_file = model.source_file;
  rep.response_file = data.source;
  rep.fs = data.fs;
  rep.duration = data.duration();
  rep.kind = sel.channels.front().kind;
  rep.notes = sel.notes;
  rep.notes.insert(rep.notes.end(), modes.notes.begin(), modes.notes.end());
  rep.notes.insert(rep.notes.end(), notes.begin(), notes.end());
  rep.notes.insert(rep.notes.end(), id.notes.begin(), id.notes.end());
  for (const ModeCheck& c : rep.modes) {
    if (c.resolution_ratio && *c.resolution_ratio > 0.25) {
      rep.notes.push_back("mode " + std::to_string(c.number) +
                          ": damping marked * is not reliable: a line's bandwidth is " +
                          num(100 * *c.resolution_ratio, "%.0f") +
                          " % of the half-power band (below 25 % needs longer segments)");
    }
  }
  return rep;
}

}  // namespace ntn::modecheck
