// Reading CSV tables: a header row "x[unit],name[unit],..." (the first column the abscissa:
// time, frequency), then rows of comma-separated numbers. The layer that
// ntn::spectral::read_csv_channels and ntn::plot::read_csv_table share; each puts its own checks
// and messages on top (uniform sampling; an increasing abscissa; how NaN is reported), so this
// reader splits and parses but does not judge the numbers.
#pragma once

#include <cstddef>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "record.hpp"  // ReadError

namespace ntn::io {

// "name[unit]" -> {name, unit}: the name trimmed of blanks and quotes, the unit as written
// (to the "]" or the end of the cell). Without "[": {header, ""}.
std::pair<std::string, std::string> split_unit(const std::string& header);

// The index of a channel by name, exact or as "name[unit]"; nullopt when there is none.
std::optional<std::size_t> find_channel(const std::vector<std::string>& names,
                                        const std::vector<std::string>& units,
                                        std::string_view name);
// "a, b, c", for the message that lists the channels when find_channel found none.
std::string channel_list(const std::vector<std::string>& names);

// One comma-separated field of a row.
struct TableField {
  double value = 0;
  std::size_t column = 0;  // 1-based, at the first character after blanks and a leading '+'
  std::size_t length = 0;  // characters from `column` to the last one that is not blank
  bool ok = false;         // the whole field is one number ("nan" and "inf" parse)
};

// Reads a table row by row, so that the caller checks each row in its own order. Every error is
// a ReadError of the file, formatted "FILE:LINE:COLUMN: error: message" ("FILE: error: message"
// for a file that cannot be opened).
class TableReader {
 public:
  // Opens `path` and reads the header: the first line that is not blank, split at commas, each
  // cell trimmed of blanks and quotes. Errors: "cannot open: <reason>" (a directory, a missing
  // file, no permission; line 0: no position); a file with no line that is not blank, "the file
  // is empty; expected a header row '<expected_header>'" (1:1).
  std::optional<ReadError> open(const std::string& path, std::string_view expected_header);

  const std::string& path() const { return path_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t header_line() const { return header_line_; }

  // The channels of the header: every column after the first except one named "flags" (any
  // case; ntn-hil-<model> and ntn-feeder write it), split by split_unit into `names` and
  // `units`, with `columns` the header column (0-based) of each. Errors at the header line,
  // column 1: "column N has no name", "the header needs <first_column> and at least one
  // channel" (e.g. "a time column").
  std::optional<ReadError> channels(std::vector<std::string>& names,
                                    std::vector<std::string>& units,
                                    std::vector<std::size_t>& columns,
                                    std::string_view first_column) const;

  // The next row that is not blank, split at commas into `fields` (as many as the row has, which
  // the caller compares with the header: row_length_error). False at the end of the file.
  bool next_row(std::vector<TableField>& fields);
  // The line last read (CR of a CRLF ending removed) and its 1-based number; at the end of the
  // file, the number of the last line.
  const std::string& line() const { return line_; }
  std::size_t line_number() const { return line_number_; }
  // The text of a field of the line last read.
  std::string text(const TableField& f) const { return line_.substr(f.column - 1, f.length); }

  // "expected N values, found M" at column 1 of the line last read, when a row of `fields`
  // does not have one value per header column.
  std::optional<ReadError> row_length_error(const std::vector<TableField>& fields) const;

  // An error in this file.
  ReadError error(std::size_t line, std::size_t column, std::string message) const;

 private:
  bool next_line();  // false at the end of the file

  std::ifstream in_;
  std::string path_;
  std::vector<std::string> header_;
  std::size_t header_line_ = 0;
  std::string line_;
  std::size_t line_number_ = 0;
};

}  // namespace ntn::io
