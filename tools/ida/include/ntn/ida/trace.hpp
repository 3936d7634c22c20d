// How one record's IDA curve is traced: which intensities to run, one after the other,
// each chosen from the results of the record's earlier runs only, so that the runs of a record
// are the same whatever process runs them and whenever.
//
// Stepping: the given intensities in ascending order, up to the first collapse (every higher one
// would collapse too: the curve's flatline).
//
// Hunt and fill (Vamvatsikos and Cornell, "Applied incremental dynamic analysis", Earthquake
// Spectra 20(2), 2004): hunt up from `first` with steps that grow by `increment` each run
// (first, 2 first, 3 first + increment, ...) until a run collapses or `max` is reached; then
// bisect the bracket between the highest intensity that did not collapse and the lowest that did
// down to `resolution`; then fill the largest gap between the intensities that did not collapse
// (from 0) with its midpoint, until the gaps are at most `resolution`. At most `runs` runs.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ntn::ida {

enum class TraceMode { kStepping, kHuntFill };

struct TracePlan {
  TraceMode mode = TraceMode::kHuntFill;
  std::vector<double> levels;  // stepping: ascending, > 0
  double first = 0.1;          // hunt and fill: the first intensity and the first step
  double increment = 0.05;     // the step's growth per run
  double resolution = 0.02;    // bracket and gaps are closed down to this
  double max = 5.0;            // the hunt stops here
  int runs = 12;               // at most this many runs per record
};

// One run of a record: its intensity and whether it collapsed.
struct TracePoint {
  double im = 0;
  bool collapse = false;
};

// The plan's first problem, naming ntn-ida's option for the field (nothing: the plan is usable).
std::optional<std::string> check_plan(const TracePlan& plan);

// The next intensity to run after `done` (the record's runs in the order they ran), or nothing
// when the record is traced.
std::optional<double> next_intensity(const TracePlan& plan, std::span<const TracePoint> done);

// The record's collapse capacity: the highest intensity that did not collapse below the lowest
// that did (the start of the IDA curve's flatline, Vamvatsikos and Cornell 2002), or nothing when
// no run collapsed (the capacity lies above every intensity run: a censored value).
std::optional<double> collapse_capacity(std::span<const TracePoint> done);

}  // namespace ntn::ida
