#include "ntn/ida/trace.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ntn::ida {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double lowest_collapse(std::span<const TracePoint> done) {
  double lowest = kInf;
  for (const TracePoint& p : done)
    if (p.collapse) lowest = std::min(lowest, p.im);
  return lowest;
}

// The intensities that did not collapse below `below`, ascending, with 0 first.
std::vector<double> standing(std::span<const TracePoint> done, double below) {
  std::vector<double> ims{0.0};
  for (const TracePoint& p : done)
    if (!p.collapse && p.im < below) ims.push_back(p.im);
  std::sort(ims.begin(), ims.end());
  return ims;
}

}  // namespace

std::optional<std::string> check_plan(const TracePlan& plan) {
  if (plan.mode == TraceMode::kStepping) {
    if (plan.levels.empty()) return "--scales: no intensities to step through";
    for (std::size_t k = 0; k < plan.levels.size(); ++k) {
      if (!(plan.levels[k] > 0) || !std::isfinite(plan.levels[k]))
        return "--scales: the intensities must be finite and above 0";
      if (k > 0 && !(plan.levels[k] > plan.levels[k - 1]))
        return "--scales: the intensities must ascend";
    }
    return std::nullopt;
  }
  if (!(plan.first > 0) || !std::isfinite(plan.first))
    return "--first: the first intensity must be above 0";
  if (!(plan.increment >= 0) || !std::isfinite(plan.increment))
    return "--step-increase: the step increment must be 0 or more";
  if (!(plan.resolution > 0) || !std::isfinite(plan.resolution))
    return "--resolution: the resolution must be above 0";
  if (!(plan.max >= plan.first) || !std::isfinite(plan.max))
    return "--max: the highest intensity must be at least the first";
  if (plan.runs < 1) return "--runs: at least one run per record";
  return std::nullopt;
}

std::optional<double> next_intensity(const TracePlan& plan, std::span<const TracePoint> done) {
  const std::size_t n = done.size();
  if (plan.mode == TraceMode::kStepping) {
    for (const TracePoint& p : done)
      if (p.collapse) return std::nullopt;  // the flatline
    if (n >= plan.levels.size()) return std::nullopt;
    return plan.levels[n];
  }
  if (n >= static_cast<std::size_t>(plan.runs)) return std::nullopt;
  if (n == 0) return plan.first;
  const double collapse = lowest_collapse(done);
  double highest = 0;
  for (const TracePoint& p : done)
    highest = std::max(highest, p.im);
  // Hunt: every run so far stood and the top has not been reached.
  if (collapse == kInf && highest < plan.max) {
    const double step = plan.first + static_cast<double>(n - 1) * plan.increment;
    return std::min(done[n - 1].im + step, plan.max);
  }
  const std::vector<double> ims = standing(done, collapse);
  // Bracket: bisect between the highest standing run and the lowest collapse.
  if (collapse < kInf && collapse - ims.back() > plan.resolution)
    return 0.5 * (ims.back() + collapse);
  // Fill: the largest gap between standing runs, the lowest first among gaps equal to a part in
  // 10^9 (midpoints are not exact, and a rounding must not decide which gap is filled first).
  double gap = 0;
  std::size_t at = 0;
  for (std::size_t k = 1; k < ims.size(); ++k) {
    if (ims[k] - ims[k - 1] > gap * (1 + 1e-9)) gap = ims[k] - ims[k - 1], at = k;
  }
  if (gap > plan.resolution) return 0.5 * (ims[at - 1] + ims[at]);
  return std::nullopt;
}

std::optional<double> collapse_capacity(std::span<const TracePoint> done) {
  const double collapse = lowest_collapse(done);
  if (collapse == kInf) return std::nullopt;
  return standing(done, collapse).back();
}

}  // namespace ntn::ida
