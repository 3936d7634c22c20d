#include "ntn/spectral/channels.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "ntn/spectral/error.hpp"
#include "record.hpp"  // tools/io
#include "table.hpp"   // tools/io

namespace ntn::spectral {

namespace {

std::string num(double v, const char* f = "%.9g") {
  char b[40];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

[[noreturn]] void fail(const io::ReadError& e) {
  throw Error(e.format());
}

}  // namespace

std::size_t Channels::index(std::string_view name) const {
  if (const auto c = io::find_channel(names, units, name)) return *c;
  throw Error(source + ": no channel '" + std::string(name) +
              "' (channels: " + io::channel_list(names) + ")");
}

Channels read_csv_channels(const std::string& path) {
  // Header: time, then channels; a "flags" column (ntn-hil, ntn-feeder) is not a channel.
  io::TableReader in;
  if (auto e = in.open(path, "time[s],channel,...")) fail(*e);
  const std::vector<std::string>& header = in.header();
  const std::size_t header_line = in.header_line();
  if (header[0].find('[') != std::string::npos) {
    const std::string unit = io::split_unit(header[0]).second;
    if (unit != "s")
      fail(in.error(header_line, 1, "the time column must be in s, not '" + unit + "'"));
  }

  Channels ch;
  ch.source = path;
  std::vector<std::size_t> columns;  // header column of each channel
  if (auto e = in.channels(ch.names, ch.units, columns, "a time column")) fail(*e);
  ch.data.resize(columns.size());

  std::vector<double> times;
  std::vector<std::size_t> rows;  // file line of each row
  std::vector<io::TableField> fields;
  while (in.next_row(fields)) {
    const std::size_t line_no = in.line_number();
    if (auto e = in.row_length_error(fields)) fail(*e);
    for (const io::TableField& f : fields)
      if (!f.ok) fail(in.error(line_no, f.column, "not a number"));
    const double t = fields[0].value;
    if (!std::isfinite(t)) fail(in.error(line_no, fields[0].column, "the time is not finite"));
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const io::TableField& f = fields[columns[c]];
      if (!std::isfinite(f.value)) {
        fail(in.error(line_no, f.column,
                      "channel '" + ch.names[c] + "' is " +
                          (std::isnan(f.value) ? "NaN" : "infinite") + " at t = " + num(t) +
                          " s; a spectrum needs finite data (did the run diverge or a sensor "
                          "drop out?)"));
      }
      ch.data[c].push_back(f.value);
    }
    times.push_back(t);
    rows.push_back(line_no);
  }
  if (times.size() < 2)
    fail(in.error(in.line_number() + 1, 1,
                  "a record needs at least 2 rows of data, found " + std::to_string(times.size())));

  // Strictly increasing and uniform to a fraction of the step, the rule of every record reader
  // (tools/io check_time_grid): relative to the step, not to |t|, so that a time column counted
  // from an epoch is held to the same precision as one starting at 0.
  double dt = 0;
  if (const auto e = io::check_time_grid(times, dt)) fail(in.error(rows[e->index], 1, e->message));
  ch.fs = 1 / dt;
  ch.t0 = times.front();
  return ch;
}

Channels read_at2_channel(const std::string& path) {
  const io::ReadResult r = io::read_at2(path);
  if (r.error) throw Error(r.error->format());
  const io::Record& rec = *r.record;
  Channels ch;
  ch.source = path;
  ch.fs = 1 / rec.dt;
  ch.t0 = 0;
  ch.names.push_back(std::filesystem::path(path).stem().string());
  ch.units.push_back(rec.units);
  ch.data.push_back(rec.values);
  return ch;
}

Channels read_channels(const std::string& path) {
  if (io::is_at2_path(path)) return read_at2_channel(path);
  return read_csv_channels(path);
}

}  // namespace ntn::spectral
