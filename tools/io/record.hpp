// Reading sampled records (ground motions, measured channels): PEER AT2 and CSV.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ntn::io {

// One uniformly sampled channel.
struct Record {
  std::string source;          // file path
  std::string description;     // header text (AT2) or column name (CSV)
  std::string units;           // "g", "m/s2", ... as the file states; empty if it does not
  double dt = 0;               // s
  std::vector<double> values;  // in `units`

  double duration() const { return dt * static_cast<double>(values.size()); }
  // Linear interpolation at time t; 0 before the start and after the end (ground at rest).
  double at(double t) const;
  double peak_abs() const;
};

struct ReadError {
  std::string file;
  int line = 0;
  int column = 0;
  std::string message;
  std::string format() const;  // "file:line:column: error: message"
};

struct ReadResult {
  std::optional<Record> record;
  std::optional<ReadError> error;
};

// PEER AT2: three free-text header lines, a fourth with NPTS and DT in either style
// ("NPTS=  2000, DT= .02000 SEC" or "2000  0.0200  NPTS, DT"), then NPTS values in free or
// Fortran fixed format. CR/LF line endings of any mix are accepted. Units come from the header
// ("UNITS OF G", "units are (g)").
ReadResult read_at2(const std::string& path);
// The same from text in memory; `source` stands for the file name in the record and errors.
ReadResult read_at2_text(std::string_view text, const std::string& source);

// CSV with a header row; `column` names the channel (or is empty for the second column).
// The first column is time in s and must be uniformly spaced (to 1e-6 relative).
ReadResult read_csv(const std::string& path, const std::string& column);
ReadResult read_csv_text(std::string_view text, const std::string& column,
                         const std::string& source);

// By extension: .AT2/.at2 -> read_at2, anything else -> read_csv.
ReadResult read_record(const std::string& path, const std::string& column = {});
// True when `path` ends in ".at2" in any case: read_record and the channel readers of
// ntn::spectral and ntn::plot choose the AT2 reader by it.
bool is_at2_path(const std::string& path);

}  // namespace ntn::io
