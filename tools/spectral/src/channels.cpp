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

  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1]))
      fail(in.error(rows[k], 1,
                    "time does not increase (t = " + num(times[k]) + " s after " +
                        num(times[k - 1]) + " s)"));
  }
  // The step: least squares over all rows (averages the rounding of printed times out), about
  // the centre (k - kc) so the sums stay small. Uniform spacing: every time within
  // 1e-6 dt + 1e-8 |t| of that line (the second term is the rounding of a 9-significant-digit
  // time column).
  const double count = static_cast<double>(times.size());
  const double kc = 0.5 * (count - 1);
  double t_mean = 0;
  for (double t : times)
    t_mean += t;
  t_mean /= count;
  double skt = 0;
  for (std::size_t k = 0; k < times.size(); ++k)
    skt += (static_cast<double>(k) - kc) * (times[k] - t_mean);
  const double dt = skt / (count * (count * count - 1) / 12);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double expected = t_mean + (static_cast<double>(k) - kc) * dt;
    if (std::abs(times[k] - expected) > 1e-6 * dt + 1e-8 * std::abs(times[k])) {
      fail(in.error(rows[k], 1,
                    "time is not uniformly spaced: t = " + num(times[k], "%.12g") + " s where " +
                        num(expected, "%.12g") + " s was expected (step " + num(dt, "%.9g") +
                        " s fitted to all rows); a dropped or repeated row, or a record with "
                        "gaps, has no single sample rate"));
    }
  }
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
