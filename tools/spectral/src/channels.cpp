#include "ntn/spectral/channels.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "ntn/spectral/error.hpp"
#include "record.hpp"  // tools/io

namespace ntn::spectral {

namespace {

std::string num(double v, const char* f = "%.9g") {
  char b[40];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

[[noreturn]] void fail(const std::string& file, std::size_t line, std::size_t column,
                       const std::string& message) {
  throw Error(file + ":" + std::to_string(line) + ":" + std::to_string(column) +
              ": error: " + message);
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\"");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\"");
  return std::string(s.substr(b, e - b + 1));
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// One comma-separated field: the number and the 1-based column it starts at.
struct Field {
  double value = 0;
  std::size_t column = 0;
  bool ok = false;
};

// Splits a row into fields; a field is a number with optional surrounding blanks ("nan" and
// "inf" parse, so they can be reported by channel).
std::size_t parse_row(std::string_view row, std::vector<Field>& out) {
  out.clear();
  std::size_t i = 0;
  while (true) {
    const std::size_t start = i;
    const std::size_t end = std::min(row.find(',', i), row.size());
    std::size_t b = start;
    while (b < end && (row[b] == ' ' || row[b] == '\t'))
      ++b;
    std::size_t e = end;
    while (e > b && (row[e - 1] == ' ' || row[e - 1] == '\t'))
      --e;
    if (b < e && row[b] == '+') ++b;  // from_chars takes no leading '+'
    Field f;
    f.column = b + 1;
    const auto r = std::from_chars(row.data() + b, row.data() + e, f.value);
    f.ok = b < e && r.ec == std::errc() && r.ptr == row.data() + e;
    out.push_back(f);
    if (end >= row.size()) break;
    i = end + 1;
  }
  return out.size();
}

}  // namespace

std::size_t Channels::index(std::string_view name) const {
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] == name || names[c] + "[" + units[c] + "]" == name) return c;
  }
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  throw Error(source + ": no channel '" + std::string(name) + "' (channels: " + list + ")");
}

Channels read_csv_channels(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, 0, "cannot open the file");
  std::string line;
  std::size_t line_no = 0;
  // Header: time, then channels; a "flags" column (ntn-hil, ntn-feeder) is not a channel.
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) break;
  }
  if (line_no == 0 || line.find_first_not_of(" \t") == std::string::npos)
    fail(path, 1, 1, "the file is empty; expected a header row 'time[s],channel,...'");
  for (std::size_t i = 0;;) {
    const std::size_t e = std::min(line.find(',', i), line.size());
    header.push_back(trim(std::string_view(line).substr(i, e - i)));
    if (e >= line.size()) break;
    i = e + 1;
  }
  const std::size_t header_line = line_no;
  if (const auto b = header[0].find('['); b != std::string::npos) {
    const std::string unit = header[0].substr(b + 1, header[0].find(']', b) - b - 1);
    if (unit != "s") fail(path, header_line, 1, "the time column must be in s, not '" + unit + "'");
  }

  Channels ch;
  ch.source = path;
  std::vector<std::size_t> columns;  // header column of each channel
  for (std::size_t c = 1; c < header.size(); ++c) {
    if (lower(header[c]) == "flags") continue;
    std::string name = header[c];
    std::string unit;
    if (const auto b = name.find('['); b != std::string::npos) {
      const auto e = name.find(']', b);
      unit = name.substr(b + 1, e == std::string::npos ? std::string::npos : e - b - 1);
      name = trim(name.substr(0, b));
    }
    if (name.empty())
      fail(path, header_line, 1, "column " + std::to_string(c + 1) + " has no name");
    ch.names.push_back(name);
    ch.units.push_back(unit);
    columns.push_back(c);
  }
  if (header.size() < 2 || columns.empty())
    fail(path, header_line, 1, "the header needs a time column and at least one channel");
  ch.data.resize(columns.size());

  std::vector<double> times;
  std::vector<std::size_t> rows;  // file line of each row
  std::vector<Field> fields;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (parse_row(line, fields) != header.size())
      fail(path, line_no, 1,
           "expected " + std::to_string(header.size()) + " values, found " +
               std::to_string(fields.size()));
    for (const Field& f : fields)
      if (!f.ok) fail(path, line_no, f.column, "not a number");
    const double t = fields[0].value;
    if (!std::isfinite(t)) fail(path, line_no, fields[0].column, "the time is not finite");
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const Field& f = fields[columns[c]];
      if (!std::isfinite(f.value)) {
        fail(path, line_no, f.column,
             "channel '" + ch.names[c] + "' is " + (std::isnan(f.value) ? "NaN" : "infinite") +
                 " at t = " + num(t) +
                 " s; a spectrum needs finite data (did the run diverge or a sensor drop out?)");
      }
      ch.data[c].push_back(f.value);
    }
    times.push_back(t);
    rows.push_back(line_no);
  }
  if (times.size() < 2)
    fail(path, line_no + 1, 1,
         "a record needs at least 2 rows of data, found " + std::to_string(times.size()));

  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1]))
      fail(
          path, rows[k], 1,
          "time does not increase (t = " + num(times[k]) + " s after " + num(times[k - 1]) + " s)");
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
      fail(path, rows[k], 1,
           "time is not uniformly spaced: t = " + num(times[k], "%.12g") + " s where " +
               num(expected, "%.12g") + " s was expected (step " + num(dt, "%.9g") +
               " s fitted to all rows); a dropped or repeated row, or a record with gaps, has "
               "no single sample rate");
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
  const std::string l = lower(path);
  if (l.size() > 4 && l.substr(l.size() - 4) == ".at2") return read_at2_channel(path);
  return read_csv_channels(path);
}

}  // namespace ntn::spectral
