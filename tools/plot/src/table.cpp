#include "ntn/plot/table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "ntn/plot/plot.hpp"
#include "record.hpp"  // tools/io
#include "table.hpp"   // tools/io

namespace ntn::plot {

namespace {

[[noreturn]] void fail(const io::ReadError& e) {
  throw Error(Error::Kind::kInput, e.format());
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

}  // namespace

std::size_t Table::index(std::string_view name) const {
  if (const auto c = io::find_channel(names, units, name)) return *c;
  throw Error(Error::Kind::kInput, source + ": no channel '" + std::string(name) +
                                       "' (channels: " + io::channel_list(names) + ")");
}

Table read_csv_table(const std::string& path, const std::string& x_unit) {
  io::TableReader in;
  if (auto e = in.open(path, "x[unit],name[unit],...")) fail(*e);
  const std::vector<std::string>& header = in.header();
  const std::size_t header_line = in.header_line();

  Table t;
  t.source = path;
  std::tie(t.x_name, t.x_unit) = io::split_unit(header[0]);
  if (!x_unit.empty() && !t.x_unit.empty() && t.x_unit != x_unit)
    fail(in.error(header_line, 1,
                  "the first column must be in " + x_unit + ", not '" + t.x_unit + "' ('" +
                      header[0] + "')"));
  std::vector<std::size_t> kept;  // header column of each channel
  if (auto e = in.channels(t.names, t.units, kept, "a first column")) fail(*e);
  t.columns.resize(kept.size());

  std::vector<io::TableField> fields;
  while (in.next_row(fields)) {
    const std::size_t line_no = in.line_number();
    for (std::size_t k = 0; k < std::min(fields.size(), header.size()); ++k) {
      if (!fields[k].ok)
        fail(
            in.error(line_no, fields[k].column,
                     "'" + in.text(fields[k]) + "' in column '" + header[k] + "' is not a number"));
    }
    if (auto e = in.row_length_error(fields)) fail(*e);
    const double x = fields[0].value;
    if (!std::isfinite(x)) fail(in.error(line_no, 1, "'" + header[0] + "' is not finite"));
    if (!t.x.empty() && !(x > t.x.back()))
      fail(in.error(
          line_no, 1,
          "'" + t.x_name + "' does not increase (" + num(x) + " after " + num(t.x.back()) + ")"));
    for (std::size_t c = 0; c < kept.size(); ++c) {
      const double v = fields[kept[c]].value;
      if (!std::isfinite(v))
        fail(in.error(line_no, 1,
                      "channel '" + t.names[c] + "' is " + (std::isnan(v) ? "NaN" : "infinite") +
                          " at " + t.x_name + " = " + num(x) +
                          (t.x_unit.empty() ? "" : " " + t.x_unit) +
                          " (did the run diverge or a sensor drop out?)"));
      t.columns[c].push_back(v);
    }
    t.x.push_back(x);
  }
  if (t.x.size() < 2)
    fail(in.error(in.line_number() + 1, 1,
                  "a plot needs at least 2 rows of data, found " + std::to_string(t.x.size())));
  return t;
}

Table read_at2_table(const std::string& path) {
  const io::ReadResult r = io::read_at2(path);
  if (r.error) throw Error(Error::Kind::kInput, r.error->format());
  const io::Record& rec = *r.record;
  Table t;
  t.source = path;
  t.x_name = "time";
  t.x_unit = "s";
  t.x.resize(rec.values.size());
  for (std::size_t n = 0; n < rec.values.size(); ++n)
    t.x[n] = static_cast<double>(n) * rec.dt;
  for (std::size_t n = 0; n < rec.values.size(); ++n) {
    if (!std::isfinite(rec.values[n]))
      throw Error(Error::Kind::kInput,
                  path + ": error: sample " + std::to_string(n + 1) + " is not finite");
  }
  if (rec.values.size() < 2)
    throw Error(Error::Kind::kInput, path + ": error: a plot needs at least 2 samples");
  t.names.push_back(std::filesystem::path(path).stem().string());
  t.units.push_back(rec.units);
  t.columns.push_back(rec.values);
  return t;
}

Table read_table(const std::string& path, const std::string& x_unit) {
  if (io::is_at2_path(path)) {
    if (!x_unit.empty() && x_unit != "s")
      throw Error(Error::Kind::kInput, path +
                                           ": error: an AT2 record is a history in s, not a "
                                           "table over " +
                                           x_unit);
    return read_at2_table(path);
  }
  return read_csv_table(path, x_unit);
}

}  // namespace ntn::plot
