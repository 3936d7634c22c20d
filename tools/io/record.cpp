#include "record.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
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

// %g of a number, for messages.
std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
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

// The sample-interval rule of every record (kMinSampleInterval .. kMaxSampleInterval), with the
// key that gave the value; nothing when `dt` is in range.
std::optional<std::string> sample_interval_problem(double dt, const std::string& key) {
  if (std::isfinite(dt) && dt >= kMinSampleInterval && dt <= kMaxSampleInterval)
    return std::nullopt;
  return key + " = " + num(dt) + " s is outside the accepted sample interval [" +
         num(kMinSampleInterval) + ", " + num(kMaxSampleInterval) +
         "] s (1 MHz to 1 Hz: a corrupt header or a unit slip, e.g. DT in ms)";
}

// The unit named by the three free-text lines of an AT2 header. Words are compared, not
// substrings ("IN GAL" is not "IN G"): a word parse_unit knows as an acceleration names the unit,
// except a lone "g", which must follow "of", "in", "are", "units" or ":" or stand in
// parentheses ("UNITS OF G", "The units are (g)", "ACCELERATION IN G"), so that a "G" in a station
// name does not. Sets `units` (empty when no line names one); returns the error (line, message)
// for two different units or a line that speaks of units and names none.
std::optional<std::pair<int, std::string>> at2_header_units(const std::vector<std::string>& lines,
                                                            std::string& units) {
  std::optional<Unit> found;
  for (int h = 0; h < 3; ++h) {
    const std::string l = lower(lines[static_cast<std::size_t>(h)]);
    std::vector<std::string> words;
    std::vector<bool> in_parens;  // the word alone in parentheses: "(g)"
    std::string w;
    bool after_open = false;  // the word began right after '('
    auto flush = [&](bool closed) {
      if (!w.empty()) words.push_back(w), in_parens.push_back(after_open && closed);
      w.clear();
      after_open = false;
    };
    for (char c : l) {
      if (c == '(') {
        flush(false);
        after_open = true;
      } else if (c == ')') {
        flush(true);
      } else if (std::isspace(static_cast<unsigned char>(c)) || c == ',' || c == ';' || c == '=') {
        flush(false);
      } else if (c == ':') {
        flush(false);
        words.push_back(":"), in_parens.push_back(false);
      } else {
        w.push_back(c);
      }
    }
    flush(false);
    bool names_one = false;
    for (std::size_t i = 0; i < words.size(); ++i) {
      std::string word = words[i];
      if (word == "g's" || word == "gs") word = "g";
      if (word == "g" || word == "mg") {
        const std::string prev = i > 0 ? words[i - 1] : "";
        const bool stated = in_parens[i] || prev == "of" || prev == "in" || prev == "are" ||
                            prev == "units" || prev == "unit" || prev == ":";
        if (!stated) continue;
      }
      const std::optional<Unit> u = parse_unit(word);
      if (!u || u->quantity != Quantity::kAcceleration) continue;
      names_one = true;
      if (found && found->si != u->si) {
        return std::make_pair(h + 1, "the header names two different units, '" + found->name +
                                         "' and '" + u->name + "'");
      }
      if (!found) found = u;
    }
    const bool speaks_of_units = std::find_if(words.begin(), words.end(), [](const std::string& x) {
                                   return x == "unit" || x == "units";
                                 }) != words.end();
    if (!names_one && speaks_of_units) {
      return std::make_pair(h + 1, "the header speaks of units but names none that ntn knows (" +
                                       known_units() + ")");
    }
  }
  units = found ? found->name : std::string();
  return std::nullopt;
}

}  // namespace

std::optional<Unit> parse_unit(std::string_view text) {
  std::string s;
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) s.push_back(c);
  s = lower(s);
  auto replace_all = [&s](std::string_view from, std::string_view to) {
    for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
      s.replace(p, from.size(), to);
  };
  replace_all("\xc2\xb2", "2");  // UTF-8 superscript two
  replace_all("**", "");
  replace_all("^", "");
  replace_all("sec", "s");
  replace_all("/s/s", "/s2");
  replace_all("*", "");
  replace_all(".", "");
  struct Known {
    const char* spelling;
    const char* name;
    Quantity quantity;
    double si;
  };
  static const Known kKnown[] = {
      {"g", "g", Quantity::kAcceleration, 9.80665},
      {"mg", "mg", Quantity::kAcceleration, 9.80665e-3},
      {"gal", "gal", Quantity::kAcceleration, 0.01},
      {"gals", "gal", Quantity::kAcceleration, 0.01},
      {"cm/s2", "cm/s2", Quantity::kAcceleration, 0.01},
      {"m/s2", "m/s2", Quantity::kAcceleration, 1},
      {"mm/s2", "mm/s2", Quantity::kAcceleration, 1e-3},
      {"in/s2", "in/s2", Quantity::kAcceleration, 0.0254},
      {"ft/s2", "ft/s2", Quantity::kAcceleration, 0.3048},
      {"n", "N", Quantity::kForce, 1},
      {"kn", "kN", Quantity::kForce, 1e3},
      {"nm", "N m", Quantity::kMoment, 1},
      {"knm", "kN m", Quantity::kMoment, 1e3},
  };
  for (const Known& k : kKnown) {
    if (s == k.spelling) return Unit{k.name, k.quantity, k.si};
  }
  return std::nullopt;
}

std::string known_units() {
  return "g, mg, gal, cm/s2, m/s2, mm/s2, in/s2, ft/s2, N, kN, N m, kN m";
}

Unit input_unit(bool ground_acceleration, int dof, double scale) {
  if (ground_acceleration) {
    if (scale == 9.80665) return {"g", Quantity::kAcceleration, scale};
    if (scale == 1) return {"m/s2", Quantity::kAcceleration, scale};
    return {"(" + num(scale) + " m/s2)", Quantity::kAcceleration, scale};
  }
  const bool moment = dof >= 3;
  const std::string si = moment ? "N m" : "N";
  const Quantity q = moment ? Quantity::kMoment : Quantity::kForce;
  if (scale == 1) return {si, q, scale};
  if (scale == 1e3) return {"k" + si, q, scale};
  return {"(" + num(scale) + " " + si + ")", q, scale};
}

std::optional<ReadError> read_text_file(const std::string& path, std::string& text) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return ReadError{path, 0, 0, "cannot open: it is a directory"};
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int e = errno;
    return ReadError{path, 0, 0,
                     std::string("cannot open: ") + (e != 0 ? std::strerror(e) : "unreadable")};
  }
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return ReadError{path, 0, 0, "cannot read the file"};
  text = ss.str();
  return std::nullopt;
}

std::string ReadError::format() const {
  if (line <= 0) return file + ": error: " + message;
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

bool scale_factor_valid(double factor) {
  return std::isfinite(factor) && factor != 0;
}

void Record::scale(double f) {
  if (f == 1) return;
  for (double& v : values)
    v *= f;
  scaled_by *= f;
}

double Record::peak_abs() const {
  double p = 0;
  for (double v : values)
    p = std::max(p, std::abs(v));
  return p;
}

std::optional<std::string> Record::to_unit(const Unit& target) {
  static const char* const kQuantity[] = {"an acceleration", "a force", "a moment"};
  const char* const wanted = kQuantity[static_cast<int>(target.quantity)];
  if (units.empty()) {  // no unit stated: the values are taken as given
    units = target.name;
    unit = target;
    converted_from.clear();
    unit_assumed = true;
    return std::nullopt;
  }
  if (!unit) {
    return "unit '" + units + "' is not one ntn knows (" + known_units() + "); the input wants " +
           wanted + " in " + target.name;
  }
  if (unit->quantity != target.quantity) {
    return "unit '" + units + "' is " + kQuantity[static_cast<int>(unit->quantity)] +
           "; the input wants " + wanted + " in " + target.name;
  }
  if (unit->si != target.si) {
    const double factor = unit->si / target.si;
    for (double& v : values)
      v *= factor;
    converted_from = units;
  } else {
    converted_from.clear();
  }
  units = target.name;
  unit = target;
  unit_assumed = false;
  return std::nullopt;
}

ReadResult read_at2(const std::string& path) {
  std::string text;
  if (auto e = read_text_file(path, text)) return {std::nullopt, std::move(e)};
  return read_at2_text(text, path);
}

ReadResult read_at2_text(std::string_view content, const std::string& path) {
  const std::vector<std::string> lines = split_lines(content);
  // The NPTS, DT line must be the fourth: one on an earlier line means a missing header line.
  for (std::size_t h = 0; h < std::min<std::size_t>(3, lines.size()); ++h) {
    const std::string l = lower(lines[h]);
    if (l.find("npts") != std::string::npos && l.find("dt") != std::string::npos) {
      return fail(path, static_cast<int>(h + 1), 1,
                  "NPTS and DT are on line " + std::to_string(h + 1) +
                      ", but an AT2 file has 3 free-text header lines before them: " +
                      std::to_string(3 - h) + " header line" + (h == 2 ? " is" : "s are") +
                      " missing");
    }
  }
  if (lines.size() < 4)
    return fail(path, 1, 1,
                "the file has " + std::to_string(lines.size()) +
                    " line(s); an AT2 file needs 3 free-text header lines and a fourth with NPTS "
                    "and DT before its values");

  Record r;
  r.source = path;
  r.description = lines[0] + " | " + lines[1];
  if (const auto e = at2_header_units(lines, r.units)) return fail(path, e->first, 1, e->second);
  if (!r.units.empty()) r.unit = parse_unit(r.units);

  // Fourth line: "NPTS=  2000, DT= .02000 SEC" (NGA style) or "2000  0.0200 NPTS, DT" (older).
  const std::string& h4 = lines[3];
  const bool keywords = lower(h4).find("npts") != std::string::npos;
  double npts = 0;
  if (const auto n = header_value(h4, "NPTS"), d = header_value(h4, "DT"); n && d) {
    npts = *n;
    r.dt = *d;
  } else {
    std::vector<double> v;
    std::string head = h4;
    const auto text = head.find_first_of("ABCDFGHIJKLMNOPQRSTUVWXYZabcdfghijklmnopqrstuvwxyz");
    if (text != std::string::npos) head = head.substr(0, text);
    const int bad = parse_numbers(head, v);
    if (!keywords && bad == 0 && v.size() > 2) {
      // Values where the NPTS, DT line should be: a header line is missing.
      return fail(path, 4, 1,
                  "line 4 holds " + std::to_string(v.size()) +
                      " numbers, not NPTS and DT: is a header line missing? (an AT2 file has 3 "
                      "free-text header lines, then e.g. 'NPTS= 1559, DT= .02 SEC')");
    }
    if (bad != 0 || v.size() < 2)
      return fail(path, 4, 1,
                  "expected NPTS and DT on the fourth line, e.g. 'NPTS= 1559, DT= .02 SEC'");
    npts = v[0];
    r.dt = v[1];
  }
  if (!(npts >= 1) || npts != std::floor(npts) || npts > kMaxPoints)
    return fail(path, 4, 1,
                "NPTS = " + num(npts) + " must be a whole number in [1, " + num(kMaxPoints) + "]");
  if (const auto e = sample_interval_problem(r.dt, "DT")) return fail(path, 4, 1, *e);

  const auto n = static_cast<std::size_t>(npts);
  // NPTS comes from the file: reserve no more than the text could hold (a value takes at least
  // one character), so a header claiming 10^8 points does not allocate 800 MB up front.
  r.values.reserve(std::min(n, content.size()));
  for (std::size_t k = 4; k < lines.size(); ++k) {
    if (const int col = parse_numbers(lines[k], r.values); col != 0) {
      return fail(path, static_cast<int>(k + 1), col, "not a finite number");
    }
    if (r.values.size() > n) {
      return fail(path, static_cast<int>(k + 1), 1,
                  "more values than NPTS = " + std::to_string(n) + " (value " +
                      std::to_string(n + 1) + " onwards)");
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
  if (auto e = read_text_file(path, text)) return {std::nullopt, std::move(e)};
  return read_csv_text(text, column, path);
}

std::optional<TimeGridError> check_time_grid(const std::vector<double>& times, double& dt) {
  char message[320];
  if (times.size() < 2) {
    return TimeGridError{times.size(),
                         "a record needs at least 2 rows, found " + std::to_string(times.size())};
  }
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) {
      std::snprintf(message, sizeof message,
                    "time does not increase (t = %.12g s after %.12g s): rows out of order or "
                    "repeated",
                    times[k], times[k - 1]);
      return TimeGridError{k, message};
    }
  }
  // A row out of place first, by the steps between rows: each within 4 % of the median step (if
  // every time is within 1 % of a step of a grid, every step is within 2 % of the grid's and so
  // of the median's: this only finds the row of a dropped, repeated or jittered time sooner
  // than the fit below, which would spread its error over every row).
  std::vector<double> steps(times.size() - 1);
  for (std::size_t k = 1; k < times.size(); ++k)
    steps[k - 1] = times[k] - times[k - 1];
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double median = sorted[sorted.size() / 2];
  const char* const why =
      "a dropped or repeated row, or jittered times, have no single sample rate";
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(std::abs(steps[k - 1] - median) <= 4 * kTimeGridTolerance * median)) {
      std::snprintf(message, sizeof message,
                    "time is not uniformly spaced: t = %.12g s comes %.9g s after the row before, "
                    "where the step is %.9g s (the median): %s",
                    times[k], steps[k - 1], median, why);
      return TimeGridError{k, message};
    }
  }
  // The step: the least-squares line through all (k, t_k) (it averages the rounding of printed
  // times out: a 9-digit time column of 300 s at 1 024 Hz gives the rate to 1e-10; the first two
  // rows alone drifted off the grid at the 1 025th row). Offsets from t_0 (t_k - t_0, exact for
  // nearby values) keep an epoch-based time column as precise as one that starts at 0, and the
  // sums small (about the centre k - kc).
  const double t0 = times.front();
  const double count = static_cast<double>(times.size());
  const double kc = 0.5 * (count - 1);
  double mean = 0;
  for (double t : times)
    mean += t - t0;
  mean /= count;
  double skt = 0;
  for (std::size_t k = 0; k < times.size(); ++k)
    skt += (static_cast<double>(k) - kc) * ((times[k] - t0) - mean);
  const double d = skt / (count * (count * count - 1) / 12);
  if (!(d > 0) || !std::isfinite(d)) {
    return TimeGridError{times.size() - 1, "the time column spans " + num(times.back() - t0) +
                                               " s: no step can be taken from it"};
  }
  // Every time within kTimeGridTolerance of a step of the line; the farthest one is reported.
  std::size_t worst = 0;
  double worst_off = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double off = (times[k] - t0) - (mean + (static_cast<double>(k) - kc) * d);
    if (!(std::abs(off) <= std::abs(worst_off))) worst = k, worst_off = off;
  }
  if (!(std::abs(worst_off) <= kTimeGridTolerance * d)) {
    const double expected = mean + (static_cast<double>(worst) - kc) * d;
    std::snprintf(message, sizeof message,
                  "time is not uniformly spaced: t = %.12g s where %.12g s was expected (%.3g "
                  "steps off; allowed %g of a step of %.9g s fitted to all rows): %s",
                  times[worst], t0 + expected, worst_off / d, kTimeGridTolerance, d, why);
    return TimeGridError{worst, message};
  }
  dt = d;
  return std::nullopt;
}

ReadResult read_csv_text(std::string_view content, const std::string& column,
                         const std::string& path) {
  const std::vector<std::string> lines = split_lines(content);
  std::size_t head = 0;  // the header: the first line that is not blank
  while (head < lines.size() && lines[head].find_first_not_of(" \t") == std::string::npos)
    ++head;
  if (head == lines.size())
    return fail(path, 1, 1, "the file is empty; a CSV record needs a header row 'time[s],name'");

  std::vector<std::string> names;
  {
    std::stringstream ss(lines[head]);
    std::string name;
    while (std::getline(ss, name, ',')) {
      name.erase(0, name.find_first_not_of(" \t\""));
      name.erase(name.find_last_not_of(" \t\"") + 1);
      names.push_back(name);
    }
  }
  const int header_line = static_cast<int>(head + 1);
  if (names.size() < 2)
    return fail(path, header_line, 1, "the header needs a time column and a channel");
  if (const auto b = names[0].find('['); b != std::string::npos) {
    const std::string unit = names[0].substr(b + 1, names[0].find(']', b) - b - 1);
    if (unit != "s")
      return fail(path, header_line, 1, "the time column must be in s, not '" + unit + "'");
  }
  std::size_t col = 1;
  if (!column.empty()) {
    const auto it = std::find_if(names.begin(), names.end(), [&](const std::string& s) {
      return s == column || s.rfind(column + "[", 0) == 0;
    });
    if (it == names.end()) return fail(path, header_line, 1, "no column named '" + column + "'");
    col = static_cast<std::size_t>(it - names.begin());
    if (col == 0) return fail(path, header_line, 1, "column '" + column + "' is the time column");
  }

  Record r;
  r.source = path;
  r.description = names[col];
  if (const auto b = names[col].find('['); b != std::string::npos) {
    r.units = names[col].substr(b + 1, names[col].find(']', b) - b - 1);
    r.unit = parse_unit(r.units);
  }
  std::vector<double> times;
  std::vector<int> rows;  // file line of each row, for errors
  for (std::size_t k = head + 1; k < lines.size(); ++k) {
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
  if (times.size() < 2)
    return fail(path, static_cast<int>(lines.size()) + 1, 1,
                "a CSV record needs at least 2 rows, found " + std::to_string(times.size()));
  if (auto e = check_time_grid(times, r.dt)) return fail(path, rows[e->index], 1, e->message);
  if (const auto e = sample_interval_problem(r.dt, "the time step"))
    return fail(path, rows[1], 1, *e);
  r.t0 = times.front();
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
