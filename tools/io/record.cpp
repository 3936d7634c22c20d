#include "record.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>

namespace ntn::io {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool read_file(const std::string& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::stringstream ss;
  ss << in.rdbuf();
  text = ss.str();
  return true;
}

// Splits text into lines, accepting \n, \r\n, \r\r\n (seen in PEER files) and lone \r.
std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  std::string line;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      lines.push_back(line);
      line.clear();
    } else if (c == '\r') {
      std::size_t k = i;
      while (k + 1 < text.size() && text[k + 1] == '\r')
        ++k;
      if (k + 1 < text.size() && text[k + 1] == '\n') ++k;
      i = k;
      lines.push_back(line);
      line.clear();
    } else {
      line.push_back(c);
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// Parses numbers from one line, also where Fortran fixed-width fields run together
// ("-0.12345-0.23456") and with a D exponent. Returns the column (1-based) of a bad character,
// or 0 when the whole line parsed.
int parse_numbers(std::string line, std::vector<double>& out) {
  std::replace(line.begin(), line.end(), 'D', 'E');
  std::replace(line.begin(), line.end(), 'd', 'e');
  std::size_t i = 0;
  while (i < line.size()) {
    if (std::isspace(static_cast<unsigned char>(line[i])) || line[i] == ',') {
      ++i;
      continue;
    }
    std::size_t start = i;
    if (line[start] == '+') ++start;  // from_chars takes no leading '+'
    double v = 0;
    const auto r = std::from_chars(line.data() + start, line.data() + line.size(), v);
    if (r.ec != std::errc() || !std::isfinite(v)) return static_cast<int>(i) + 1;
    out.push_back(v);
    i = static_cast<std::size_t>(r.ptr - line.data());
    if (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])) && line[i] != ',' &&
        line[i] != '-' && line[i] != '+') {
      return static_cast<int>(i) + 1;
    }
  }
  return 0;
}

ReadResult fail(const std::string& file, int line, int column, std::string message) {
  return {std::nullopt, ReadError{file, line, column, std::move(message)}};
}

// Reads "NAME= value" from a header line, e.g. NPTS=  2000 or DT= .02000.
std::optional<double> header_value(const std::string& line, const std::string& name) {
  const std::string l = lower(line);
  const auto pos = l.find(lower(name));
  if (pos == std::string::npos) return std::nullopt;
  std::size_t i = pos + name.size();
  while (i < l.size() && (l[i] == ' ' || l[i] == '=' || l[i] == ':'))
    ++i;
  std::vector<double> v;
  std::string rest = line.substr(i);
  const auto end = rest.find_first_of(", \t");
  if (end != std::string::npos) rest = rest.substr(0, end);
  if (parse_numbers(rest, v) != 0 || v.size() != 1) return std::nullopt;
  return v[0];
}

}  // namespace

std::string ReadError::format() const {
  return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": error: " + message;
}

double Record::at(double t) const {
  // The record is followed by zeros: the ground comes to rest after the last sample.
  if (values.empty() || !(dt > 0) || !(t >= 0)) return 0;
  const double x = t / dt;
  if (x >= static_cast<double>(values.size())) return 0;
  const auto k = static_cast<std::size_t>(x);
  const double v0 = values[k];
  const double v1 = k + 1 < values.size() ? values[k + 1] : 0.0;
  return v0 + (x - static_cast<double>(k)) * (v1 - v0);
}

double Record::peak_abs() const {
  double p = 0;
  for (double v : values)
    p = std::max(p, std::abs(v));
  return p;
}

ReadResult read_at2(const std::string& path) {
  std::string text;
  if (!read_file(path, text)) return fail(path, 0, 0, "cannot open the file");
  return read_at2_text(text, path);
}

ReadResult read_at2_text(std::string_view content, const std::string& path) {
  const std::vector<std::string> lines = split_lines(content);
  if (lines.size() < 4) return fail(path, 1, 1, "an AT2 file needs 4 header lines");

  Record r;
  r.source = path;
  r.description = lines[0] + " | " + lines[1];
  for (int h = 0; h < 3; ++h) {
    const std::string l = lower(lines[static_cast<std::size_t>(h)]);
    if (l.find("units of g") != std::string::npos || l.find("(g)") != std::string::npos ||
        l.find("in g") != std::string::npos) {
      r.units = "g";
    }
  }

  // Fourth line: "NPTS=  2000, DT= .02000 SEC" (NGA style) or "2000  0.0200 NPTS, DT" (older).
  const std::string& h4 = lines[3];
  double npts = 0;
  if (const auto n = header_value(h4, "NPTS"), d = header_value(h4, "DT"); n && d) {
    npts = *n;
    r.dt = *d;
  } else {
    std::vector<double> v;
    std::string head = h4;
    const auto text = head.find_first_of("ABCDFGHIJKLMNOPQRSTUVWXYZabcdfghijklmnopqrstuvwxyz");
    if (text != std::string::npos) head = head.substr(0, text);
    if (parse_numbers(head, v) != 0 || v.size() < 2)
      return fail(path, 4, 1,
                  "expected NPTS and DT on the fourth line, e.g. 'NPTS= 1559, DT= .02 SEC'");
    npts = v[0];
    r.dt = v[1];
  }
  if (!(npts >= 1) || npts != std::floor(npts) || npts > 1e8)
    return fail(path, 4, 1, "NPTS must be a positive whole number");
  if (!(r.dt > 0) || !std::isfinite(r.dt)) return fail(path, 4, 1, "DT must be positive");

  const auto n = static_cast<std::size_t>(npts);
  // NPTS comes from the file: reserve no more than the text could hold (a value takes at least
  // one character), so a header claiming 10^8 points does not allocate 800 MB up front.
  r.values.reserve(std::min(n, content.size()));
  for (std::size_t k = 4; k < lines.size(); ++k) {
    const std::size_t before = r.values.size();
    if (const int col = parse_numbers(lines[k], r.values); col != 0) {
      return fail(path, static_cast<int>(k + 1), col, "not a finite number");
    }
    if (r.values.size() > n) {
      return fail(path, static_cast<int>(k + 1), 1,
                  "more values than NPTS = " + std::to_string(n) + " (value " +
                      std::to_string(before + 1) + " onwards)");
    }
  }
  if (r.values.size() != n) {
    return fail(path, static_cast<int>(lines.size()), 1,
                "NPTS = " + std::to_string(n) + " but the file holds " +
                    std::to_string(r.values.size()) + " values");
  }
  return {std::move(r), std::nullopt};
}

ReadResult read_csv(const std::string& path, const std::string& column) {
  std::string text;
  if (!read_file(path, text)) return fail(path, 0, 0, "cannot open the file");
  return read_csv_text(text, column, path);
}

ReadResult read_csv_text(std::string_view content, const std::string& column,
                         const std::string& path) {
  const std::vector<std::string> lines = split_lines(content);
  if (lines.size() < 3) return fail(path, 1, 1, "a CSV record needs a header row and 2 rows");

  std::vector<std::string> names;
  {
    std::stringstream ss(lines[0]);
    std::string name;
    while (std::getline(ss, name, ',')) {
      name.erase(0, name.find_first_not_of(" \t\""));
      name.erase(name.find_last_not_of(" \t\"") + 1);
      names.push_back(name);
    }
  }
  if (names.size() < 2) return fail(path, 1, 1, "the header needs a time column and a channel");
  std::size_t col = 1;
  if (!column.empty()) {
    const auto it = std::find_if(names.begin(), names.end(), [&](const std::string& s) {
      return s == column || s.rfind(column + "[", 0) == 0;
    });
    if (it == names.end()) return fail(path, 1, 1, "no column named '" + column + "'");
    col = static_cast<std::size_t>(it - names.begin());
  }

  Record r;
  r.source = path;
  r.description = names[col];
  if (const auto b = names[col].find('['); b != std::string::npos) {
    r.units = names[col].substr(b + 1, names[col].find(']', b) - b - 1);
  }
  std::vector<double> times;
  std::vector<int> rows;  // file line of each row, for errors
  for (std::size_t k = 1; k < lines.size(); ++k) {
    if (lines[k].find_first_not_of(" \t") == std::string::npos) continue;
    std::vector<double> v;
    if (const int c = parse_numbers(lines[k], v); c != 0)
      return fail(path, static_cast<int>(k + 1), c, "not a finite number");
    if (v.size() != names.size())
      return fail(path, static_cast<int>(k + 1), 1,
                  "expected " + std::to_string(names.size()) + " values, found " +
                      std::to_string(v.size()));
    times.push_back(v[0]);
    rows.push_back(static_cast<int>(k + 1));
    r.values.push_back(v[col]);
  }
  if (times.size() < 2) return fail(path, 2, 1, "a CSV record needs at least 2 rows");
  // The spacing is (t_last - t_0) / (n - 1); every row must sit on that grid to 1e-6 of the
  // spacing, plus the rounding of a time printed with 9 significant digits (as ntn-run and
  // ntn-hil write it: 5e-9 of |t|, taken as 1e-8). Spacing from the first two rows alone would
  // carry their rounding along the whole record (at 1 024 Hz the 1 025th row failed).
  if (!(times[1] > times[0])) return fail(path, rows[1], 1, "time must increase");
  r.dt = (times.back() - times[0]) / static_cast<double>(times.size() - 1);
  for (std::size_t k = 1; k < times.size(); ++k) {
    const double expected = times[0] + static_cast<double>(k) * r.dt;
    const double tolerance = 1e-6 * r.dt + 1e-8 * std::max(std::abs(times[k]), std::abs(times[0]));
    if (!(std::abs(times[k] - expected) <= tolerance)) {
      char message[200];
      std::snprintf(message, sizeof message,
                    "time is not uniformly spaced (t = %.12g s, expected %.12g s on the grid "
                    "t0 + k dt, dt = %.12g s)",
                    times[k], expected, r.dt);
      return fail(path, rows[k], 1, message);
    }
  }
  return {std::move(r), std::nullopt};
}

bool is_at2_path(const std::string& path) {
  const std::string l = lower(path);
  return l.size() > 4 && l.substr(l.size() - 4) == ".at2";
}

ReadResult read_record(const std::string& path, const std::string& column) {
  if (is_at2_path(path)) return read_at2(path);
  return read_csv(path, column);
}

}  // namespace ntn::io
