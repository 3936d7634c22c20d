// Sampled channels from a file: the CSV of ntn-run, ntn-hil-<model> and ntn-feeder (a time column
// in s, then named channels "name[unit]", and a "flags" column that is left out), any CSV of the
// same shape, and PEER AT2 records (one channel, through tools/io).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace ntn::spectral {

struct Channels {
  std::string source;                     // file path
  double fs = 0;                          // sample rate, Hz
  double t0 = 0;                          // time of the first sample, s
  std::vector<std::string> names;         // channel names (CSV header without "[unit]")
  std::vector<std::string> units;         // "m", "g", ...; empty when the file does not say
  std::vector<std::vector<double>> data;  // data[c][n]

  std::size_t samples() const { return data.empty() ? 0 : data.front().size(); }
  double duration() const { return static_cast<double>(samples()) / fs; }  // s
  // The index of a channel by name (exact, or the name before "["); throws Error listing the
  // names when there is none.
  std::size_t index(std::string_view name) const;
  const std::vector<double>& channel(std::string_view name) const { return data[index(name)]; }
};

// CSV: a header row, then rows of numbers separated by commas. The first column is time in s
// (its header may say "[s]", no other unit), strictly increasing and uniform by the rule of every
// record reader (ntn::io::check_time_grid): dt is the slope of the least-squares line through
// all (n, t_n - t0), t0 the first time; every t_n must lie within 1 % of a step of that line.
// Throws Error, as "file:line:column: error: message", on: an unreadable file, fewer than 2
// rows, a row of the wrong length, something not a number, a NaN or infinite value (the channel
// and time named), time that does not increase or is not uniform (a dropped or repeated row).
Channels read_csv_channels(const std::string& path);

// PEER AT2 (tools/io read_at2): one channel named after the file's stem, t0 = 0.
Channels read_at2_channel(const std::string& path);

// By extension: .AT2/.at2 -> read_at2_channel, anything else -> read_csv_channels.
Channels read_channels(const std::string& path);

}  // namespace ntn::spectral
