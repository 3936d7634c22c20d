// One incremental dynamic analysis: a model file, a suite of records and a tracing
// plan. Each (record, intensity) pair is one kernel run of the model in run-time storage
// (ntn::hil::LoadedModel, the run of ntn-run), the record scaled so that its intensity measure
// (PGA or Sa(T1)) equals the intensity. A run gives the engineering demands (peak storey drift,
// residual drift, peak floor acceleration, the hinges' performance level, any output's peak) and
// whether the frame collapsed (a drift past the limit, a run that diverged: the kernel's safe
// state, or one that passed the stable step's bound of second-order geometry: under P-Delta the
// sidesway, whose results past the bound are not valid, so the run ends there). A record's runs
// depend on its own earlier runs only (trace.hpp), so a record's result is the same whatever
// process traces it; ntn-ida spreads the records over MPI processes.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ntn/ida/trace.hpp"
#include "record.hpp"

namespace ntn::hil {
class LoadedModel;
}

namespace ntn::ida {

enum class Measure { kPga, kSaT1 };

struct StudyConfig {
  std::string model_path;
  std::vector<std::string> record_paths;
  std::string input;  // the input channel the records feed; empty: the model's first
  Measure measure = Measure::kSaT1;
  double period = 0;      // s, for Sa; 0: the model's first period along the input's direction
  double damping = 0.05;  // for Sa
  TracePlan plan;
  double tail = 10;               // s of free vibration after each record (residual drift)
  double collapse_drift = 0.10;   // a peak storey drift ratio above this is a collapse (+inf: none)
  std::vector<std::string> edps;  // the demand columns; empty: the standard ones the model has
  int threads = 1;                // workers per run (the kernel's team)
};

// What a demand column holds.
struct EdpColumn {
  enum class Kind { kPeakDrift, kResidualDrift, kPeakFloorAcceleration, kHingeLevel, kPeak };
  Kind kind = Kind::kPeak;
  std::string name;  // column name
  std::string unit;  // "-", "g", or the output's unit
  int output = -1;   // kPeak: the output channel
};

struct RecordEntry {
  std::string name;   // the file's name
  std::string path;   // as given
  io::Record record;  // in the input's unit, as read
  double im = 0;      // the intensity measure of the record as read, g
  double pga = 0;     // g
};

// One run's result.
struct RunRow {
  std::size_t record = 0;
  double im = 0;     // g
  double scale = 0;  // the factor the record was multiplied by
  bool collapse = false;
  double peak_drift = 0;     // the largest |drift ratio| of any storey (NaN: the model has none)
  std::vector<double> edps;  // one per column
  // "ok", "diverged", "geometry_bound" (past the stable step's bound of second-order geometry:
  // the run ended after that frame) or "error: ..."
  std::string status = "ok";
  std::int64_t steps = 0;
  std::string hash;    // ntn-run's output hash of the run
  double seconds = 0;  // wall time of the run (not written to the results)
  bool error() const { return status.rfind("error", 0) == 0; }
};

class Study {
 public:
  // Loads the model, reads and converts the records, finds T1 (modal analysis) and every
  // record's intensity measure. nullptr, the messages and the exit code on failure (1: the model
  // has errors; 2: a file cannot be read or an option does not fit the model).
  static std::unique_ptr<Study> open(const StudyConfig& config, std::vector<std::string>& errors,
                                     std::vector<std::string>& notes, int& exit_code);
  ~Study();
  Study(const Study&) = delete;
  Study& operator=(const Study&) = delete;

  const StudyConfig& config() const { return config_; }
  const std::vector<RecordEntry>& records() const { return records_; }
  const std::vector<EdpColumn>& columns() const { return columns_; }
  double period() const { return period_; }  // s, T1 (0 with PGA and no modes asked)
  std::string measure_name() const;          // "PGA" or "Sa(T1 = 0.532 s, 5 %)"
  bool has_drifts() const { return has_drifts_; }

  // One run of record `r` scaled to intensity `im` (g).
  RunRow run(std::size_t r, double im);
  // Traces record `r` by the plan: for each intensity the plan asks for, the row of `known`
  // with exactly that intensity if there is one (a resumed study), else a new run, which is
  // passed to `on_run` as soon as it is done. The record's rows in the order they ran. A run
  // that could not be made (an error) ends the record's trace.
  std::vector<RunRow> trace(std::size_t r, const std::vector<RunRow>& known,
                            const std::function<void(const RunRow&)>& on_run);

  // The results table: its header and one row (no newline); numbers as %.17g, so that a row
  // read back (parse_row) is the same run bit for bit.
  std::string csv_header() const;
  std::string csv_row(const RunRow& row) const;
  std::optional<RunRow> parse_row(std::string_view line) const;

 private:
  Study() = default;
  StudyConfig config_;
  std::unique_ptr<hil::LoadedModel> model_;
  std::vector<RecordEntry> records_;
  std::vector<EdpColumn> columns_;
  std::size_t input_ = 0;
  double period_ = 0;
  bool has_drifts_ = false;
};

// The record files of --records: a directory (its *.AT2 files, by name) or a list file (one path
// per line, relative to the list's directory; '#' starts a comment). Paths, or the message.
std::vector<std::string> record_files(const std::string& where, std::string& error);

}  // namespace ntn::ida
