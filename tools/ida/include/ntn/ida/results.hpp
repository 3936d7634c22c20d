// What an IDA gives once every record is traced: the results table, each record's
// capacities (the intensity at which it first exceeds each performance level and at which it
// collapses), lognormal fragility curves fitted to them, and the plots (IDA curves with their
// 16/50/84 % fractiles, fragility curves), as files in one output folder.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ntn/ida/fragility.hpp"
#include "ntn/ida/study.hpp"

namespace ntn::ida {

// The limit states a fragility curve is fitted for: the hinges' performance levels exceeded
// (hinge_level >= 2: beyond IO; >= 3: beyond LS; >= 4: beyond CP; a collapsed run counts as
// beyond every level) and collapse.
enum class LimitState { kIO, kLS, kCP, kCollapse };
inline constexpr LimitState kLimitStates[] = {LimitState::kIO, LimitState::kLS, LimitState::kCP,
                                              LimitState::kCollapse};
const char* limit_state_name(LimitState s);

// A record's capacity for one limit state: the intensity (g) at which it was first reached, or
// nothing, with `highest` the highest intensity run (the record's capacity lies above it).
struct Capacity {
  std::optional<double> im;
  double highest = 0;
};

struct RecordCapacities {
  Capacity io, ls, cp, collapse;
  const Capacity& of(LimitState s) const;
  bool traced = true;  // false: an error ended the trace (left out of the fits)
  bool levels = true;  // false: no hinge_level column (IO, LS and CP unknown, not fitted)
};

// `rows`: every run of the study, in any order. The capacities of each record: for each limit
// state the lowest intensity whose run reached it (the bracket that hunt and fill closes to its
// resolution lies just below it for collapse; a collapsed run has reached every level).
std::vector<RecordCapacities> capacities(const Study& study, const std::vector<RunRow>& rows);

struct Fragility {
  LimitState state = LimitState::kCollapse;
  LognormalFit fit;
};
std::vector<Fragility> fragilities(const std::vector<RecordCapacities>& caps);

// The rows sorted by record (the study's order), then intensity: the order of results.csv.
void sort_rows(std::vector<RunRow>& rows);

// What write_results wrote and lost. A file is written whole or not at all (written beside
// itself and renamed; an earlier study's file of the same name is removed first, so nothing
// stale passes for a result).
struct Written {
  std::vector<std::string> files;       // the files written, as DIR/NAME
  std::vector<std::string> lost;        // a result file that could not be written: the message
  std::vector<std::string> plots_lost;  // a plot that was not made (gnuplot missing, failed or
                                        // cut short by the disk): the message
};

// Writes DIR/results.csv, DIR/capacities.csv, DIR/fragility.csv and, when `plots` and every
// result file is written, the plots DIR/ida.{png,svg} and DIR/fragility.{png,svg} (gnuplot).
// gnuplot's warnings and plots there is nothing to draw for go to `notes`.
Written write_results(const Study& study, const std::vector<RunRow>& rows, const std::string& dir,
                      bool plots, std::vector<std::string>& notes);

// The summary printed after the runs: counts, fragility medians and dispersions.
std::string summary_text(const Study& study, const std::vector<RunRow>& rows);

}  // namespace ntn::ida
