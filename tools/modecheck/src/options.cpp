// The modal check's options: checked (validate), refused as the caller spells them
// (bad_option), and the line spacing resolved from them and the record (resolve_resolution).
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "ntn/modecheck/modecheck.hpp"
#include "options.hpp"

namespace ntn::modecheck {

namespace detail {

std::string num(double v, const char* format) {
  char b[48];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

double segment_samples(double fs, double df) {
  return std::ceil(fs / df * (1 - 1e-12));
}

std::string count(double samples) {
  return num(samples, samples < 1e15 ? "%.0f" : "%.6g");
}

[[noreturn]] void bad_option(const Options& o, OptionName name, double value, const char* unit,
                             const char* rule) {
  const bool cli = o.spelling == Spelling::kCli;
  const bool pc = cli && name.percent;
  std::string r = rule;
  if (name.percent) {
    // The rule's bounds: "100 %" on the command line, "1" as a fraction.
    const std::string hundred = "100 %";
    for (auto at = r.find(hundred); !pc && at != std::string::npos; at = r.find(hundred))
      r.replace(at, hundred.size(), "1");
  }
  throw InputError((cli ? std::string("option ") + name.cli : std::string(name.library)) + " is " +
                   num(pc ? 100 * value : value) + (pc ? " %" : unit) + ": " + r);
}

}  // namespace detail

using detail::bad_option;
using detail::count;
using detail::num;
using detail::segment_samples;

void validate(const Options& o) {
  const auto in = [](double v, double lo, double hi) {
    return std::isfinite(v) && v >= lo && v <= hi;
  };
  const bool cli = o.spelling == Spelling::kCli;
  if (o.modes < 1) {
    throw InputError(std::string(cli ? "option --modes" : "modes") + " is " +
                     std::to_string(o.modes) + ": it must be at least 1");
  }
  if (!in(o.tolerance, 0, 1) || o.tolerance == 0)
    bad_option(o, {"--tolerance", "tolerance", true}, o.tolerance, "",
               "it must be above 0 and at most 100 %");
  if (!in(o.search_band, 0, 1) || o.search_band == 0)
    bad_option(o, {"--band", "band", true}, o.search_band, "",
               "it must be above 0 and at most 100 %");
  if (!in(o.min_mac, 0, 1))
    bad_option(o, {"--min-mac", "min_mac", false}, o.min_mac, "", "it must be in [0, 1]");
  if (!std::isfinite(o.resolution_hz) || o.resolution_hz < 0) {
    bad_option(o, {"--resolution", "resolution", false}, o.resolution_hz, " Hz",
               cli ? "it must be a finite positive line spacing"
                   : "it must be a finite positive line spacing, or 0: automatic");
  }
  if (!in(o.overlap, 0, 0.95))
    bad_option(o, {"--overlap", "overlap", false}, o.overlap, "", "it must be in [0, 0.95]");
  if (o.direction < -1 || o.direction > 2) {
    throw InputError(std::string(cli ? "the direction" : "direction") + " is " +
                     std::to_string(o.direction) +
                     ": it must be x, y or z (0, 1, 2; -1: every mode)");
  }
  if (!in(o.min_mass_fraction, 0, 1)) {
    bad_option(o, {"--min-mass", "min_mass", true}, o.min_mass_fraction, "",
               "it must be in [0, 100 %]");
  }
  if (!in(o.min_prominence, 1, std::numeric_limits<double>::max())) {
    bad_option(o, {"--min-prominence", "min_prominence", false}, o.min_prominence, "",
               "it must be a finite ratio of at least 1");
  }
  if (!in(o.min_level, 0, 1))
    bad_option(o, {"--min-level", "min_level", false}, o.min_level, "", "it must be in [0, 1]");
  if (!in(o.false_alarm, 0, 1) || o.false_alarm == 0 || o.false_alarm == 1) {
    bad_option(o, {"--false-alarm", "false_alarm", true}, o.false_alarm, "",
               "it must be above 0 and below 100 %");
  }
  if (!in(o.min_visibility, 0, 1)) {
    bad_option(o, {"--min-visibility", "min_visibility", true}, o.min_visibility, "",
               "it must be in [0, 100 %]");
  }
}

double resolve_resolution(const spectral::Channels& data, double lowest_model_hz,
                          const Options& options, std::vector<std::string>* notes) {
  const double fs = data.fs;
  const std::size_t n = data.samples();
  if (options.resolution_hz > 0) {
    if (options.resolution_hz > fs / 8) {
      bad_option(options, {"--resolution", "resolution", false}, options.resolution_hz, " Hz",
                 ("a segment needs at least 8 samples: at most fs / 8 = " + num(fs / 8) +
                  " Hz for this record")
                     .c_str());
    }
    const double seg = segment_samples(fs, options.resolution_hz);
    if (static_cast<double>(n) < seg) {
      throw InputError("the record is too short for a resolution of " + num(options.resolution_hz) +
                       " Hz: it is " + num(static_cast<double>(n) / fs) + " s (" +
                       std::to_string(n) + " samples at " + num(fs) + " Hz), and one segment of " +
                       num(seg / fs) + " s (" + count(seg) +
                       " samples) is needed; give a record of at least " + num(seg / fs) +
                       " s or a coarser --resolution");
    }
    return options.resolution_hz;
  }
  const double wanted = options.tolerance * lowest_model_hz / 2;
  if (static_cast<double>(n) >= segment_samples(fs, wanted)) return wanted;
  const double df = fs / static_cast<double>(n);
  if (notes != nullptr) {
    notes->push_back("resolution " + num(df) + " Hz (the whole record, " +
                     num(static_cast<double>(n) / fs) + " s, as one segment) is coarser than " +
                     "tolerance x lowest frequency / 2 = " + num(wanted) + " Hz, which needs " +
                     num(1 / wanted) + " s");
  }
  return df;
}

}  // namespace ntn::modecheck
