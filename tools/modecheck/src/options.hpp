// The modal check's options as its messages name them (options.cpp): an option refused, worded
// as the caller spells it, and the segment a line spacing needs.
#pragma once

#include <string>

#include "ntn/modecheck/modecheck.hpp"

namespace ntn::modecheck::detail {

// Refuses one option, worded as the caller spells it: ntn-check-modes ("option --tolerance is
// 150 %: ...", the fractions it takes in %) or the library and the Python module ("tolerance is
// 1.5: ...", fractions as fractions). `percent`: a fraction the command line takes in %.
struct OptionName {
  const char* cli;
  const char* library;
  bool percent;
};

[[noreturn]] void bad_option(const Options& o, OptionName name, double value, const char* unit,
                             const char* rule);

// Samples in one segment for a line spacing df (as Welch's ceil(fs / df), guarded against
// rounding up a ratio that is an integer in exact arithmetic). A double: for a tiny df it exceeds
// every record (and std::size_t), so it is compared before any conversion.
double segment_samples(double fs, double df);

// A number as the check's messages and files write it (printf's format, %.6g by default).
std::string num(double v, const char* format = "%.6g");

// A number of samples as messages write it: whole, or %.6g from 1e15 on.
std::string count(double samples);

}  // namespace ntn::modecheck::detail
