// The files ntn-plot draws: a CSV table whose first column is the abscissa (time in s for a
// history, frequency in Hz for a spectrum) and whose other columns are named "name[unit]", as
// ntn-run-<model>, ntn-hil-<model> and ntn-feeder write them; and PEER AT2 records (tools/io).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace ntn::plot {

struct Table {
  std::string source;                        // file path
  std::string x_name;                        // header of the first column without "[unit]"
  std::string x_unit;                        // its unit, empty when the header gives none
  std::vector<double> x;                     // first column
  std::vector<std::string> names;            // the other columns, header without "[unit]"
  std::vector<std::string> units;            // "m", "N", ...; empty when the header gives none
  std::vector<std::vector<double>> columns;  // columns[c][row]

  // Index of a column by name (exact, or "name[unit]" as in the header); throws Error (kInput)
  // "FILE: no channel 'x' (channels: a, b, ...)".
  std::size_t index(std::string_view name) const;
};

// CSV: a header row, then rows of comma-separated numbers, as many as the header has names. A
// column named "flags" (ntn-hil-<model>, ntn-feeder) is left out. `x_unit`, when not empty, is
// the unit the first column must have if its header names one ("s", "Hz"). Throws Error (kInput)
// as "FILE:LINE:COLUMN: error: ..." on an unreadable or empty file, a row of the wrong length,
// something that is not a number, a NaN or infinite value (column and abscissa named), fewer than
// 2 rows, or an abscissa that does not increase. Unlike ntn::spectral::read_channels it does not
// ask for uniform sampling: a record with gaps still plots.
Table read_csv_table(const std::string& path, const std::string& x_unit = {});

// A PEER AT2 record through ntn::io::read_at2: x is time in s, one column named after the file's
// stem, in the units of its header. Throws Error (kInput) with the reader's message.
Table read_at2_table(const std::string& path);

// By extension: .AT2/.at2 -> read_at2_table, anything else -> read_csv_table.
Table read_table(const std::string& path, const std::string& x_unit = {});

}  // namespace ntn::plot
