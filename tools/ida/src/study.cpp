#include "ntn/ida/study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "ntn/hil/loaded_model.hpp"
#include "ntn/hil/record_source.hpp"
#include "ntn/hil/yield_report.hpp"
#include "ntn/ida/spectrum.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modelc/diagnostic.hpp"
#include "ntn/modelc/load_model.hpp"
#include "numbers.hpp"
#include "run_driver.hpp"

namespace ntn::ida {
namespace {

constexpr double kG = 9.80665;  // m/s^2 per g
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string number(double v) {
  return detail::exact(v);
}
std::string short_number(double v) {
  return detail::rounded(v, 4);
}

// A status is one CSV field: no commas, no line breaks.
std::string one_field(std::string text) {
  for (char& c : text)
    if (c == ',' || c == '\n' || c == '\r') c = ';';
  return text;
}

std::vector<std::string_view> split(std::string_view line, char sep) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = line.find(sep, start);
    if (at == std::string_view::npos) {
      out.push_back(line.substr(start));
      return out;
    }
    out.push_back(line.substr(start, at - start));
    start = at + 1;
  }
}

std::optional<double> to_double(std::string_view text) {
  if (text.empty()) return std::nullopt;
  const std::string s(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

Study::~Study() = default;

std::unique_ptr<Study> Study::open(const StudyConfig& config, std::vector<std::string>& errors,
                                   std::vector<std::string>& notes, int& exit_code) {
  exit_code = 0;
  std::unique_ptr<Study> s(new Study());
  s->config_ = config;
  if (const auto e = check_plan(config.plan)) {
    errors.push_back(*e);
    exit_code = 2;
    return nullptr;
  }

  modelc::LoadResult loaded = modelc::load_model(config.model_path);
  if (!loaded.ok()) {
    errors.push_back(modelc::format_all(loaded.errors));
    exit_code = loaded.unreadable ? 2 : 1;
    return nullptr;
  }
  if (!loaded.notes.empty()) notes.push_back(modelc::format_all(loaded.notes));
  const modelc::ModelDescription& d = *loaded.model;

  // The input the records feed: named, or the model's first ground acceleration.
  const auto& names = d.input_names;
  if (config.input.empty()) {
    const auto it = std::find_if(d.inputs.begin(), d.inputs.end(), [](const InputSpec& in) {
      return in.kind == InputKind::kGroundAcceleration;
    });
    if (it == d.inputs.end()) {
      errors.push_back("the model has no ground acceleration input; name one with --input");
      exit_code = 2;
      return nullptr;
    }
    s->input_ = static_cast<std::size_t>(it - d.inputs.begin());
  } else {
    const auto it = std::find(names.begin(), names.end(), config.input);
    if (it == names.end()) {
      errors.push_back("--input: the model has no input channel '" + config.input + "'");
      exit_code = 2;
      return nullptr;
    }
    s->input_ = static_cast<std::size_t>(it - names.begin());
  }
  const InputSpec& in = d.inputs[s->input_];
  if (in.kind != InputKind::kGroundAcceleration) {
    errors.push_back("input '" + names[s->input_] +
                     "' is not a ground acceleration: an intensity measure scales ground motions");
    exit_code = 2;
    return nullptr;
  }

  // The demand columns.
  std::vector<int> drifts, floor_accelerations;
  for (std::size_t c = 0; c < d.outputs.size(); ++c) {
    if (d.outputs[c].kind == OutputKind::kDrift) drifts.push_back(static_cast<int>(c));
    if (d.outputs[c].kind == OutputKind::kAbsoluteAcceleration && d.outputs[c].dof < 3)
      floor_accelerations.push_back(static_cast<int>(c));
  }
  s->has_drifts_ = !drifts.empty();
  const bool plastic = !d.hystereses.empty();
  using Kind = EdpColumn::Kind;
  std::vector<std::string> wanted = config.edps;
  if (wanted.empty()) {
    if (s->has_drifts_) wanted.insert(wanted.end(), {"peak_drift", "residual_drift"});
    if (!floor_accelerations.empty()) wanted.emplace_back("peak_floor_acceleration");
    if (plastic) wanted.emplace_back("hinge_level");
  } else if (s->has_drifts_ &&
             std::find(wanted.begin(), wanted.end(), "peak_drift") == wanted.end()) {
    wanted.insert(wanted.begin(), "peak_drift");  // the IDA curve's demand: always written
  }
  for (const std::string& w : wanted) {
    EdpColumn col;
    col.name = w;
    if (w == "peak_drift" || w == "residual_drift") {
      if (!s->has_drifts_) {
        errors.push_back("--edp " + w + ": the model has no output of kind \"drift\"");
        exit_code = 2;
        return nullptr;
      }
      col.kind = w == "peak_drift" ? Kind::kPeakDrift : Kind::kResidualDrift;
      col.unit = "-";
    } else if (w == "peak_floor_acceleration") {
      if (floor_accelerations.empty()) {
        errors.push_back("--edp " + w +
                         ": the model has no output of kind \"absolute_acceleration\"");
        exit_code = 2;
        return nullptr;
      }
      col.kind = Kind::kPeakFloorAcceleration;
      col.unit = "g";
    } else if (w == "hinge_level") {
      col.kind = Kind::kHingeLevel;
      col.unit = "-";
    } else {
      const auto it = std::find(d.output_names.begin(), d.output_names.end(), w);
      if (it == d.output_names.end()) {
        errors.push_back("--edp " + w +
                         ": neither peak_drift, residual_drift, peak_floor_acceleration, "
                         "hinge_level nor an output channel of the model");
        exit_code = 2;
        return nullptr;
      }
      col.kind = Kind::kPeak;
      col.output = static_cast<int>(it - d.output_names.begin());
      col.name = "peak_" + w;
      col.unit = d.output_units[static_cast<std::size_t>(col.output)];
    }
    s->columns_.push_back(col);
  }
  if (!s->has_drifts_)
    notes.push_back("the model has no drift output: a run collapses only when it diverges");

  // T1: the period of the mode with the largest effective mass along the input's direction.
  if (config.measure == Measure::kSaT1) {
    if (config.period > 0) {
      s->period_ = config.period;
    } else {
      modal::ModalOptions options;
      options.modes = 12;
      const modal::ModalResult m = modal::modal_analysis(d.view(), options);
      if (!m.ok() || m.effective_mass.rows() == 0) {
        errors.push_back("the model's first period: modal analysis: " +
                         (m.ok() ? std::string("no modes") : m.error) + " (give --period)");
        exit_code = 2;
        return nullptr;
      }
      Eigen::Index best = 0;
      const auto dir = static_cast<Eigen::Index>(in.dof);
      for (Eigen::Index k = 1; k < m.effective_mass.rows(); ++k)
        if (m.effective_mass(k, dir) > m.effective_mass(best, dir)) best = k;
      s->period_ = m.period(best);
      const double share =
          100 * m.effective_mass(best, dir) / m.total_mass[static_cast<std::size_t>(in.dof)];
      notes.push_back("T1 = " + short_number(s->period_) + " s: mode " + std::to_string(best + 1) +
                      ", " + short_number(share) + " % of the mass along the input's direction");
    }
  }

  // The records, in the input's unit. Their intensity measures are in g, of the motion the model
  // feels (the record times the model file's scale, InputSpec::factor): PGA and Sa are linear in
  // the record, so they are computed on it and converted once (exactly unchanged for an input
  // in g with no scale). |factor|: a negative one reverses the motion, not its intensity.
  const double to_g =
      io::input_unit(true, in.dof, in.scale).si * std::abs(in.factor) / io::parse_unit("g")->si;
  for (const std::string& path : config.record_paths) {
    RecordEntry e;
    e.path = path;
    e.name = std::filesystem::path(path).filename().string();
    if (const auto err = hil::load_input_record(in, names[s->input_], path, "", false, e.record)) {
      errors.push_back(*err);
      exit_code = 2;
      return nullptr;
    }
    e.pga = peak_ground_acceleration(e.record.values) * to_g;
    e.im = config.measure == Measure::kPga
               ? e.pga
               : pseudo_spectral_acceleration(e.record.values, e.record.dt, s->period_,
                                              config.damping) *
                     to_g;
    if (!(e.im > 0) || !std::isfinite(e.im)) {
      errors.push_back(path + ": its intensity measure is " + short_number(e.im) +
                       ": it cannot be scaled to an intensity");
      exit_code = 2;
      return nullptr;
    }
    for (const RecordEntry& other : s->records_) {
      if (other.name == e.name) {
        errors.push_back(path + ": a second record named " + e.name +
                         " (records are named by their file name)");
        exit_code = 2;
        return nullptr;
      }
    }
    s->records_.push_back(std::move(e));
  }
  if (s->records_.empty()) {
    errors.push_back("no records");
    exit_code = 2;
    return nullptr;
  }

  if (const auto refused = hil::storage_memory_refusal(*loaded.model, RunTimeOptions{})) {
    errors.push_back(config.model_path + ": error: " + *refused);
    exit_code = 1;
    return nullptr;
  }
  s->model_ = std::make_unique<hil::LoadedModel>(std::move(*loaded.model), RunTimeOptions{});
  const InitStatus st = s->model_->init();
  if (!st.ok()) {
    errors.push_back(config.model_path + ": " + to_string(st.error) + " (at " +
                     std::to_string(st.where) + ")");
    exit_code = 1;
    return nullptr;
  }
  return s;
}

std::string Study::measure_name() const {
  if (config_.measure == Measure::kPga) return "PGA";
  return "Sa(T1 = " + short_number(period_) + " s, " + short_number(100 * config_.damping) + " %)";
}

RunRow Study::run(std::size_t r, double im) {
  const RecordEntry& e = records_[r];
  hil::LoadedModel& m = *model_;
  const ModelSpec<kRunTime>& spec = m.spec();
  const InputSpec& in = spec.inputs[input_];
  RunRow row;
  row.record = r;
  row.im = im;
  row.scale = im / e.im;
  row.peak_drift = kNaN;
  row.edps.assign(columns_.size(), kNaN);

  // The scaled record, every sample finite and in the input's range (else no run: an error).
  std::vector<io::Record> feed(spec.inputs.size());
  for (std::size_t k = 0; k < feed.size(); ++k) {
    feed[k].dt = e.record.dt;
    feed[k].values.assign(1, 0.0);  // the other inputs at rest
  }
  io::Record& scaled = feed[input_];
  scaled = e.record;
  for (double& v : scaled.values)
    v *= row.scale;
  if (const auto k = hil::first_out_of_range(in, scaled.values)) {
    row.status = "error: scaled by " + short_number(row.scale) + " the record reaches " +
                 short_number(scaled.values[*k]) + " " + scaled.units + "; the input accepts " +
                 short_number(in.min) + " to " + short_number(in.max);
    return row;
  }

  const double seconds = scaled.duration() + config_.tail;
  run::RunRequest request;
  request.steps = static_cast<std::int64_t>(std::ceil(seconds / m.model().dt - 1e-9));
  request.threads = config_.threads;
  const run::RunStorage<kRunTime> storage{m.model(),   m.init_work(), m.state(),
                                          m.scratch(), m.team_work(), &m.loop_buffers()};
  const run::RunResult res = run::simulate(storage, spec, m.info(), feed, request);
  if (!res.error.empty()) {
    row.status = "error: " + one_field(res.error);
    return row;
  }
  row.steps = res.steps;
  row.hash = res.hash;
  row.seconds = res.wall;

  const auto& outputs = spec.outputs;
  double residual = kNaN, floor = kNaN;
  for (std::size_t c = 0; c < outputs.size(); ++c) {
    if (outputs[c].kind == OutputKind::kDrift) {
      row.peak_drift = std::isnan(row.peak_drift) ? res.peaks[c].value
                                                  : std::max(row.peak_drift, res.peaks[c].value);
      const double end = std::abs(res.last[c]);
      residual = std::isnan(residual) ? end : std::max(residual, end);
    }
    if (outputs[c].kind == OutputKind::kAbsoluteAcceleration && outputs[c].dof < 3) {
      const double a = res.peaks[c].value / outputs[c].scale / kG;
      floor = std::isnan(floor) ? a : std::max(floor, a);
    }
  }
  int level = 0;
  for (const hil::YieldedDirection& y : hil::yielded_directions(m.model(), m.state()))
    level = std::max(level, y.level);

  row.collapse = res.diverged || row.peak_drift > config_.collapse_drift;
  row.status = res.diverged ? "diverged" : "ok";
  using Kind = EdpColumn::Kind;
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    const EdpColumn& col = columns_[k];
    switch (col.kind) {
      case Kind::kPeakDrift:
        row.edps[k] = row.peak_drift;
        break;
      case Kind::kResidualDrift:
        row.edps[k] = residual;
        break;
      case Kind::kPeakFloorAcceleration:
        row.edps[k] = floor;
        break;
      case Kind::kHingeLevel:
        row.edps[k] = level;
        break;
      case Kind::kPeak:
        row.edps[k] = res.peaks[static_cast<std::size_t>(col.output)].value;
        break;
    }
  }
  return row;
}

std::vector<RunRow> Study::trace(std::size_t r, const std::vector<RunRow>& known,
                                 const std::function<void(const RunRow&)>& on_run) {
  std::vector<RunRow> rows;
  std::vector<TracePoint> points;
  while (const std::optional<double> im = next_intensity(config_.plan, points)) {
    const auto it = std::find_if(known.begin(), known.end(),
                                 [&](const RunRow& k) { return k.record == r && k.im == *im; });
    if (it != known.end()) {
      rows.push_back(*it);
    } else {
      rows.push_back(run(r, *im));
      if (on_run) on_run(rows.back());
    }
    if (rows.back().error()) break;
    points.push_back({rows.back().im, rows.back().collapse});
  }
  return rows;
}

std::string Study::csv_header() const {
  std::string h = "record,im[g],scale,collapse";
  for (const EdpColumn& c : columns_)
    h += "," + c.name + "[" + c.unit + "]";
  h += ",status,steps,output_hash";
  return h;
}

std::string Study::csv_row(const RunRow& row) const {
  std::string line = records_[row.record].name + "," + number(row.im) + "," + number(row.scale) +
                     "," + (row.collapse ? "1" : "0");
  for (const double v : row.edps)
    line += "," + number(v);
  line += "," + one_field(row.status) + "," + std::to_string(row.steps) + "," + row.hash;
  return line;
}

std::optional<RunRow> Study::parse_row(std::string_view line) const {
  const std::vector<std::string_view> f = split(line, ',');
  if (f.size() != 4 + columns_.size() + 3) return std::nullopt;
  RunRow row;
  const auto it = std::find_if(records_.begin(), records_.end(),
                               [&](const RecordEntry& e) { return e.name == f[0]; });
  if (it == records_.end()) return std::nullopt;
  row.record = static_cast<std::size_t>(it - records_.begin());
  const auto im = to_double(f[1]), scale = to_double(f[2]);
  if (!im || !scale || (f[3] != "0" && f[3] != "1")) return std::nullopt;
  row.im = *im, row.scale = *scale, row.collapse = f[3] == "1";
  row.peak_drift = kNaN;
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    const auto v = to_double(f[4 + k]);
    if (!v) return std::nullopt;
    row.edps.push_back(*v);
    if (columns_[k].kind == EdpColumn::Kind::kPeakDrift) row.peak_drift = *v;
  }
  row.status = std::string(f[4 + columns_.size()]);
  const auto steps = to_double(f[5 + columns_.size()]);
  if (!steps) return std::nullopt;
  row.steps = static_cast<std::int64_t>(*steps);
  row.hash = std::string(f[6 + columns_.size()]);
  return row;
}

std::vector<std::string> record_files(const std::string& where, std::string& error) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  std::error_code ec;
  if (fs::is_directory(where, ec)) {
    for (const auto& entry : fs::directory_iterator(where, ec)) {
      std::string ext = entry.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (entry.is_regular_file() && ext == ".at2") out.push_back(entry.path().string());
    }
    std::sort(out.begin(), out.end());
    if (out.empty()) error = "--records " + where + ": no .AT2 file in the directory";
    return out;
  }
  std::ifstream list(where);
  if (!list) {
    error = "--records " + where + ": neither a directory nor a readable list file";
    return out;
  }
  const fs::path base = fs::path(where).parent_path();
  std::string line;
  while (std::getline(list, line)) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    const fs::path p(line);
    out.push_back(p.is_absolute() ? p.string() : (base / p).string());
  }
  if (out.empty()) error = "--records " + where + ": the list names no record";
  return out;
}

}  // namespace ntn::ida
