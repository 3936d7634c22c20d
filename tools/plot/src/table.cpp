#include "ntn/plot/table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "ntn/plot/plot.hpp"
#include "record.hpp"  // tools/io

namespace ntn::plot {

namespace {

[[noreturn]] void fail(const std::string& file, std::size_t line, std::size_t column,
                       const std::string& message) {
  throw Error(Error::Kind::kInput, file + ":" + std::to_string(line) + ":" +
                                       std::to_string(column) + ": error: " + message);
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

// "name[unit]" -> {name, unit}.
std::pair<std::string, std::string> split_unit(const std::string& header) {
  const auto b = header.find('[');
  if (b == std::string::npos) return {header, {}};
  const auto e = header.find(']', b);
  return {trim(header.substr(0, b)),
          header.substr(b + 1, e == std::string::npos ? std::string::npos : e - b - 1)};
}

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

}  // namespace

std::size_t Table::index(std::string_view name) const {
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c] == name || names[c] + "[" + units[c] + "]" == name) return c;
  }
  std::string list;
  for (const std::string& n : names)
    list += (list.empty() ? "" : ", ") + n;
  throw Error(Error::Kind::kInput,
              source + ": no channel '" + std::string(name) + "' (channels: " + list + ")");
}

Table read_csv_table(const std::string& path, const std::string& x_unit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, 0, "cannot open the file");
  std::string line;
  std::size_t line_no = 0;
  bool found = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) {
      found = true;
      break;
    }
  }
  if (!found) fail(path, 1, 1, "the file is empty; expected a header row 'x[unit],name[unit],...'");
  std::vector<std::string> header;
  for (std::size_t i = 0;;) {
    const std::size_t e = std::min(line.find(',', i), line.size());
    header.push_back(trim(std::string_view(line).substr(i, e - i)));
    if (e >= line.size()) break;
    i = e + 1;
  }
  const std::size_t header_line = line_no;

  Table t;
  t.source = path;
  std::tie(t.x_name, t.x_unit) = split_unit(header[0]);
  if (!x_unit.empty() && !t.x_unit.empty() && t.x_unit != x_unit)
    fail(
        path, header_line, 1,
        "the first column must be in " + x_unit + ", not '" + t.x_unit + "' ('" + header[0] + "')");
  std::vector<std::size_t> kept;  // header column of each channel
  for (std::size_t c = 1; c < header.size(); ++c) {
    if (lower(header[c]) == "flags") continue;
    auto [name, unit] = split_unit(header[c]);
    if (name.empty())
      fail(path, header_line, 1, "column " + std::to_string(c + 1) + " has no name");
    t.names.push_back(name);
    t.units.push_back(unit);
    kept.push_back(c);
  }
  if (kept.empty())
    fail(path, header_line, 1, "the header needs a first column and at least one channel");
  t.columns.resize(kept.size());

  std::vector<double> values(header.size());
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::size_t count = 0;
    for (std::size_t i = 0;;) {
      const std::size_t end = std::min(line.find(',', i), line.size());
      if (count < values.size()) {
        std::size_t b = i;
        while (b < end && (line[b] == ' ' || line[b] == '\t'))
          ++b;
        std::size_t e = end;
        while (e > b && (line[e - 1] == ' ' || line[e - 1] == '\t'))
          --e;
        if (b < e && line[b] == '+') ++b;  // from_chars takes no leading '+'
        const auto r = std::from_chars(line.data() + b, line.data() + e, values[count]);
        if (b == e || r.ec != std::errc() || r.ptr != line.data() + e)
          fail(path, line_no, b + 1,
               "'" + line.substr(b, e - b) + "' in column '" + header[count] + "' is not a number");
      }
      ++count;
      if (end >= line.size()) break;
      i = end + 1;
    }
    if (count != header.size())
      fail(path, line_no, 1,
           "expected " + std::to_string(header.size()) + " values, found " + std::to_string(count));
    const double x = values[0];
    if (!std::isfinite(x)) fail(path, line_no, 1, "'" + header[0] + "' is not finite");
    if (!t.x.empty() && !(x > t.x.back()))
      fail(path, line_no, 1,
           "'" + t.x_name + "' does not increase (" + num(x) + " after " + num(t.x.back()) + ")");
    for (std::size_t c = 0; c < kept.size(); ++c) {
      const double v = values[kept[c]];
      if (!std::isfinite(v))
        fail(path, line_no, 1,
             "channel '" + t.names[c] + "' is " + (std::isnan(v) ? "NaN" : "infinite") + " at " +
                 t.x_name + " = " + num(x) + (t.x_unit.empty() ? "" : " " + t.x_unit) +
                 " (did the run diverge or a sensor drop out?)");
      t.columns[c].push_back(v);
    }
    t.x.push_back(x);
  }
  if (t.x.size() < 2)
    fail(path, line_no + 1, 1,
         "a plot needs at least 2 rows of data, found " + std::to_string(t.x.size()));
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
  const std::string l = lower(path);
  if (l.size() > 4 && l.substr(l.size() - 4) == ".at2") {
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
