// The response CSV that ntn-run and ntn-hil write (time[s],NAME[UNIT],...[,flags], one row per
// frame, values printed with %.17g and so read back as the same doubles), and the check that one
// response is another times a factor. Header-only; include it as "support/response_csv.hpp".
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace ntn_test {

struct ResponseCsv {
  std::string header;
  std::vector<std::string> times;           // the time column as written (%.9g)
  std::vector<std::vector<double>> values;  // per row, the output channels
  std::vector<std::string> flags;           // per row, the flags column if there is one
};

// Reads `path`; an unreadable or empty file gives no rows (which every comparison fails).
inline ResponseCsv read_response_csv(const std::string& path) {
  ResponseCsv r;
  std::ifstream in(path);
  if (!std::getline(in, r.header)) return r;
  const bool has_flags = r.header.size() >= 6 && r.header.ends_with(",flags");
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');)
      cells.push_back(cell);
    if (cells.empty()) continue;
    r.times.push_back(cells.front());
    if (has_flags) {
      r.flags.push_back(cells.back());
      cells.pop_back();
    }
    std::vector<double> row;
    for (std::size_t c = 1; c < cells.size(); ++c)
      row.push_back(std::strtod(cells[c].c_str(), nullptr));
    r.values.push_back(std::move(row));
  }
  return r;
}

// Whether `b` is `a` times `factor`: the same header, times and flags, and every value of b
// equal to factor x a's exactly (no tolerances) or within tolerance[c] x the peak |value| of a's
// channel c (a relative error per channel: a response crosses zero, where a pointwise relative
// error means nothing).
inline ::testing::AssertionResult scaled_response(const ResponseCsv& a, const ResponseCsv& b,
                                                  double factor,
                                                  const std::vector<double>& tolerance = {}) {
  if (a.values.empty()) return ::testing::AssertionFailure() << "no rows in the reference";
  if (a.header != b.header)
    return ::testing::AssertionFailure() << "headers differ: " << a.header << " / " << b.header;
  if (a.times != b.times || a.flags != b.flags || a.values.size() != b.values.size())
    return ::testing::AssertionFailure() << "rows, times or flags differ";
  const std::size_t channels = a.values.front().size();
  if (!tolerance.empty() && tolerance.size() != channels)
    return ::testing::AssertionFailure()
           << tolerance.size() << " tolerances for " << channels << " channels";
  std::vector<double> peak(channels, 0.0);
  for (const auto& row : a.values)
    for (std::size_t c = 0; c < channels && c < row.size(); ++c)
      peak[c] = std::max(peak[c], std::abs(row[c]));
  double worst = 0;
  for (std::size_t k = 0; k < a.values.size(); ++k) {
    if (a.values[k].size() != channels || b.values[k].size() != channels)
      return ::testing::AssertionFailure() << "row " << k << " has another channel count";
    for (std::size_t c = 0; c < channels; ++c) {
      const double want = factor * a.values[k][c];
      const double got = b.values[k][c];
      if (tolerance.empty()) {
        if (got != want)
          return ::testing::AssertionFailure()
                 << "row " << k << " channel " << c << ": " << got << " is not " << factor << " x "
                 << a.values[k][c] << " = " << want << " (difference " << got - want << ")";
      } else {
        const double e = peak[c] > 0 ? std::abs(got - want) / (std::abs(factor) * peak[c]) : 0.0;
        worst = std::max(worst, e);
        if (!(e <= tolerance[c]))
          return ::testing::AssertionFailure()
                 << "row " << k << " channel " << c << ": " << got << " against " << want << ", "
                 << e << " of the channel's peak (tolerance " << tolerance[c] << ")";
      }
    }
  }
  return ::testing::AssertionSuccess() << "largest difference " << worst << " of a peak";
}

}  // namespace ntn_test
