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

// The input the records feed: named, or the model's first ground acceleration; it must be a
// ground acceleration. Its index into `input`, or the message.
std::optional<std::string> choose_input(const modelc::ModelDescription& d, const std::string& name,
                                        std::size_t& input) {
  const auto& names = d.input_names;
  if (name.empty()) {
    const auto it = std::find_if(d.inputs.begin(), d.inputs.end(), [](const InputSpec& in) {
      return in.kind == InputKind::kGroundAcceleration;
    });
    if (it == d.inputs.end())
      return "the model has no ground acceleration input; name one with --input";
    input = static_cast<std::size_t>(it - d.inputs.begin());
  } else {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) return "--input: the model has no input channel '" + name + "'";
    input = static_cast<std::size_t>(it - names.begin());
  }
  if (d.inputs[input].kind != InputKind::kGroundAcceleration) {
    return "input '" + names[input] +
           "' is not a ground acceleration: an intensity measure scales ground motions";
  }
  return std::nullopt;
}

// The outputs the standard demands read: storey drifts, floor (translational absolute)
// accelerations.
struct DemandOutputs {
  bool drifts = false;
  bool floor_accelerations = false;
};

DemandOutputs demand_outputs(const modelc::ModelDescription& d) {
  DemandOutputs has;
  for (const OutputSpec& out : d.outputs) {
    if (out.kind == OutputKind::kDrift) has.drifts = true;
    if (out.kind == OutputKind::kAbsoluteAcceleration && out.dof < 3)
      has.floor_accelerations = true;
  }
  return has;
}

// The demands to write: those asked for, with peak_drift first when the model has drifts (the
// IDA curve's demand: always written); none asked: the standard ones the model has.
std::vector<std::string> wanted_demands(const std::vector<std::string>& asked,
                                        const DemandOutputs& has, bool plastic) {
  std::vector<std::string> wanted = asked;
  if (wanted.empty()) {
    if (has.drifts) wanted.insert(wanted.end(), {"peak_drift", "residual_drift"});
    if (has.floor_accelerations) wanted.emplace_back("peak_floor_acceleration");
    if (plastic) wanted.emplace_back("hinge_level");
  } else if (has.drifts && std::find(wanted.begin(), wanted.end(), "peak_drift") == wanted.end()) {
    wanted.insert(wanted.begin(), "peak_drift");
  }
  return wanted;
}

// The column of demand `w` into `col`, or the message when the model has no output it reads.
std::optional<std::string> demand_column(const modelc::ModelDescription& d, const std::string& w,
                                         const DemandOutputs& has, EdpColumn& col) {
  using Kind = EdpColumn::Kind;
  col.name = w;
  if (w == "peak_drift" || w == "residual_drift") {
    if (!has.drifts) return "--edp " + w + ": the model has no output of kind \"drift\"";
    col.kind = w == "peak_drift" ? Kind::kPeakDrift : Kind::kResidualDrift;
    col.unit = "-";
  } else if (w == "peak_floor_acceleration") {
    if (!has.floor_accelerations)
      return "--edp " + w + ": the model has no output of kind \"absolute_acceleration\"";
    col.kind = Kind::kPeakFloorAcceleration;
    col.unit = "g";
  } else if (w == "hinge_level") {
    col.kind = Kind::kHingeLevel;
    col.unit = "-";
  } else {
    const auto it = std::find(d.output_names.begin(), d.output_names.end(), w);
    if (it == d.output_names.end()) {
      return "--edp " + w +
             ": neither peak_drift, residual_drift, peak_floor_acceleration, "
             "hinge_level nor an output channel of the model";
    }
    col.kind = Kind::kPeak;
    col.output = static_cast<int>(it - d.output_names.begin());
    col.name = "peak_" + w;
    col.unit = d.output_units[static_cast<std::size_t>(col.output)];
  }
  return std::nullopt;
}

// The demand columns (wanted_demands) into `columns`, or the message for the first the model
// cannot give.
std::optional<std::string> demand_columns(const modelc::ModelDescription& d,
                                          const std::vector<std::string>& asked,
                                          const DemandOutputs& has,
                                          std::vector<EdpColumn>& columns) {
  for (const std::string& w : wanted_demands(asked, has, !d.hystereses.empty())) {
    EdpColumn col;
    if (const auto e = demand_column(d, w, has, col)) return e;
    columns.push_back(col);
  }
  return std::nullopt;
}

// T1: the period of the mode with the largest effective mass along the input's direction into
// `period`, and a note saying which mode; or the message when the modal analysis gives none.
std::optional<std::string> first_period(const modelc::ModelDescription& d, const InputSpec& in,
                                        double& period, std::vector<std::string>& notes) {
  modal::ModalOptions options;
  options.modes = 12;
  const modal::ModalResult m = modal::modal_analysis(d.view(), options);
  if (!m.ok() || m.effective_mass.rows() == 0) {
    return "the model's first period: modal analysis: " +
           (m.ok() ? std::string("no modes") : m.error) + " (give --period)";
  }
  Eigen::Index best = 0;
  const auto dir = static_cast<Eigen::Index>(in.dof);
  for (Eigen::Index k = 1; k < m.effective_mass.rows(); ++k)
    if (m.effective_mass(k, dir) > m.effective_mass(best, dir)) best = k;
  period = m.period(best);
  const double share =
      100 * m.effective_mass(best, dir) / m.total_mass[static_cast<std::size_t>(in.dof)];
  notes.push_back("T1 = " + short_number(period) + " s: mode " + std::to_string(best + 1) + ", " +
                  short_number(share) + " % of the mass along the input's direction");
  return std::nullopt;
}

// The records, in the input's unit, into `records`, or the message for the first that cannot be
// read, has no intensity or repeats a name. Their intensity measures are in g, of the motion the
// model feels (the record times the model file's scale, InputSpec::factor): PGA and Sa are linear
// in the record, so they are computed on it and converted once (exactly unchanged for an input in
// g with no scale). |factor|: a negative one reverses the motion, not its intensity.
std::optional<std::string> read_records(const StudyConfig& config, const InputSpec& in,
                                        const std::string& input_name, double period,
                                        std::vector<RecordEntry>& records) {
  const double to_g =
      io::input_unit(true, in.dof, in.scale).si * std::abs(in.factor) / io::parse_unit("g")->si;
  for (const std::string& path : config.record_paths) {
    RecordEntry e;
    e.path = path;
    e.name = std::filesystem::path(path).filename().string();
    if (const auto err = hil::load_input_record(in, input_name, path, "", false, e.record))
      return err;
    e.pga = peak_ground_acceleration(e.record.values) * to_g;
    e.im =
        config.measure == Measure::kPga
            ? e.pga
            : pseudo_spectral_acceleration(e.record.values, e.record.dt, period, config.damping) *
                  to_g;
    if (!(e.im > 0) || !std::isfinite(e.im)) {
      return path + ": its intensity measure is " + short_number(e.im) +
             ": it cannot be scaled to an intensity";
    }
    for (const RecordEntry& other : records) {
      if (other.name == e.name) {
        return path + ": a second record named " + e.name +
               " (records are named by their file name)";
      }
    }
    records.push_back(std::move(e));
  }
  if (records.empty()) return "no records";
  return std::nullopt;
}

// The model in run-time storage (ntn-run's), initialised, into `model`; or the message when its
// storage is refused or its initialisation fails.
std::optional<std::string> run_time_model(const std::string& path,
                                          modelc::ModelDescription&& description,
                                          std::unique_ptr<hil::LoadedModel>& model) {
  if (const auto refused = hil::storage_memory_refusal(description, RunTimeOptions{}))
    return path + ": error: " + *refused;
  model = std::make_unique<hil::LoadedModel>(std::move(description), RunTimeOptions{});
  const InitStatus st = model->init();
  if (!st.ok()) return path + ": " + to_string(st.error) + " (at " + std::to_string(st.where) + ")";
  return std::nullopt;
}

}  // namespace

Study::~Study() = default;

std::unique_ptr<Study> Study::open(const StudyConfig& config, std::vector<std::string>& errors,
                                   std::vector<std::string>& notes, int& exit_code) {
  exit_code = 0;
  // A refusal: its message and exit code, and no study.
  const auto refuse = [&](std::string message, int code) {
    errors.push_back(std::move(message));
    exit_code = code;
    return nullptr;
  };
  std::unique_ptr<Study> s(new Study());
  s->config_ = config;
  if (const auto e = check_plan(config.plan)) return refuse(*e, 2);

  modelc::LoadResult loaded = modelc::load_model(config.model_path);
  if (!loaded.ok()) return refuse(modelc::format_all(loaded.errors), loaded.unreadable ? 2 : 1);
  if (!loaded.notes.empty()) notes.push_back(modelc::format_all(loaded.notes));
  const modelc::ModelDescription& d = *loaded.model;

  if (const auto e = choose_input(d, config.input, s->input_)) return refuse(*e, 2);
  const InputSpec& in = d.inputs[s->input_];

  const DemandOutputs has = demand_outputs(d);
  s->has_drifts_ = has.drifts;
  if (const auto e = demand_columns(d, config.edps, has, s->columns_)) return refuse(*e, 2);
  if (!s->has_drifts_)
    notes.push_back(
        "the model has no drift output: a run collapses only when it diverges or passes the "
        "stable step's bound of second-order geometry");

  if (config.measure == Measure::kSaT1 && config.period > 0) {
    s->period_ = config.period;
  } else if (config.measure == Measure::kSaT1) {
    if (const auto e = first_period(d, in, s->period_, notes)) return refuse(*e, 2);
  }

  if (const auto e = read_records(config, in, d.input_names[s->input_], s->period_, s->records_))
    return refuse(*e, 2);
  if (const auto e = run_time_model(config.model_path, std::move(*loaded.model), s->model_))
    return refuse(*e, 1);
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
  request.stop_at_geometry_bound = true;  // nothing past it is a result
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

  // Collapse (FEMA P695 counts a run whose analysis fails as one): a divergence, a run past the
  // bound of second-order geometry (it ended in the frame that passed it: a divergence in that
  // frame is said as such), or a drift above the limit.
  const bool past_bound = !res.diverged && res.loop.geometry_bound_frame >= 0;
  row.collapse = res.diverged || past_bound || row.peak_drift > config_.collapse_drift;
  row.status = res.diverged ? "diverged" : past_bound ? "geometry_bound" : "ok";
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
