#include "ntn/plot/plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

extern char** environ;

namespace ntn::plot {

namespace {

namespace fs = std::filesystem;

// Okabe & Ito's colour-blind safe palette, black last.
constexpr const char* kColours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                    "#e69f00", "#56b4e9", "#000000"};
constexpr std::size_t kColourCount = sizeof kColours / sizeof kColours[0];

[[noreturn]] void input_error(const std::string& message) {
  throw Error(Error::Kind::kInput, message);
}

std::string num(double v, const char* f = "%.17g") {
  char b[48];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// A gnuplot single-quoted string: nothing is special inside but the quote, written twice.
// Control characters (a newline would end the command) become blanks.
std::string quote(std::string_view s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "''";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      q += ' ';
    } else {
      q += c;
    }
  }
  return q + "'";
}

std::string where(std::size_t p, const Panel& panel) {
  std::string w = "panel " + std::to_string(p + 1);
  if (!panel.title.empty()) w += " '" + panel.title + "'";
  return w;
}

void check_range(const Range& r, Scale scale, const std::string& what) {
  for (const auto& end : {r.min, r.max}) {
    if (end && !std::isfinite(*end)) input_error(what + ": the range is not finite");
    if (end && scale == Scale::kLog && !(*end > 0))
      input_error(what + ": a log axis needs a range above 0, not " + num(*end, "%g"));
  }
  if (r.min && r.max && !(*r.min < *r.max))
    input_error(what + ": the range [" + num(*r.min, "%g") + ", " + num(*r.max, "%g") +
                "] is empty");
}

constexpr double kMaxPlotValue = 1e300;

void check(const Figure& f) {
  if (f.panels.empty()) input_error("the figure has no panel");
  if (f.width < 100 || f.width > 10000)
    input_error("width " + std::to_string(f.width) + " px is outside 100 ... 10000");
  if (f.height != 0 && (f.height < 100 || f.height > 20000))
    input_error("height " + std::to_string(f.height) + " px is outside 100 ... 20000");
  // The default height grows with the panels (240 px each): more than the limit is more
  // panels than a figure can hold.
  if (f.height == 0 && f.panels.size() > 20000 / 240)
    input_error(std::to_string(f.panels.size()) + " panels need " +
                std::to_string(240 * f.panels.size()) +
                " px at 240 px each, more than the 20000 px a figure may have: plot fewer "
                "channels (--channels), or give --size with a smaller height per panel");
  constexpr std::size_t kMinPanelHeight = 40;  // px: an axis, its tics and a trace
  if (f.height != 0 && f.panels.size() * kMinPanelHeight > static_cast<std::size_t>(f.height))
    input_error(std::to_string(f.panels.size()) + " panels in " + std::to_string(f.height) +
                " px: a panel needs at least " + std::to_string(kMinPanelHeight) +
                " px (plot fewer channels, or give a taller --size)");
  for (std::size_t p = 0; p < f.panels.size(); ++p) {
    const Panel& panel = f.panels[p];
    const std::string w = where(p, panel);
    if (panel.series.empty()) input_error(w + " has no series");
    check_range(panel.x_range, panel.x_scale, w + " x");
    check_range(panel.y_range, panel.y_scale, w + " y");
    for (const Series& s : panel.series) {
      const std::string ws = w + ", series '" + s.name + "'";
      if (s.x.size() != s.y.size())
        input_error(ws + ": " + std::to_string(s.x.size()) + " x values but " +
                    std::to_string(s.y.size()) + " y values");
      if (s.x.empty()) input_error(ws + " is empty");
      const bool hex = s.colour.size() == 7 && s.colour[0] == '#' &&
                       s.colour.find_first_not_of("0123456789abcdefABCDEF", 1) == std::string::npos;
      if (!s.colour.empty() && !hex) input_error(ws + ": colour '" + s.colour + "' is not #rrggbb");
      if (!(s.width >= 0.1 && s.width <= 10))
        input_error(ws + ": line width " + num(s.width, "%g") + " is outside 0.1 ... 10");
      std::size_t drawable = 0;
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        for (const auto& [v, axis] : {std::pair{s.x[i], "x"}, std::pair{s.y[i], "y"}}) {
          if (!std::isfinite(v))
            input_error(ws + ": " + axis + "[" + std::to_string(i) + "] is " +
                        (std::isnan(v) ? "NaN" : "infinite"));
          // gnuplot's axis ranges and tics overflow near DBL_MAX ("all points undefined").
          if (std::fabs(v) > kMaxPlotValue)
            input_error(ws + ": " + axis + "[" + std::to_string(i) + "] = " + num(v, "%g") +
                        " is beyond +-" + num(kMaxPlotValue, "%g") + ", which no axis can show");
        }
        if ((panel.x_scale == Scale::kLinear || s.x[i] > 0) &&
            (panel.y_scale == Scale::kLinear || s.y[i] > 0))
          ++drawable;
      }
      if (drawable == 0)
        input_error(ws + ": no value above 0 to draw on a log axis (" + std::to_string(s.x.size()) +
                    " points)");
    }
    for (const Marker& m : panel.markers) {
      if (!std::isfinite(m.x)) input_error(w + ", marker '" + m.label + "': x is not finite");
    }
  }
}

// Indices to draw: all, or the minimum and the maximum of each of `buckets` equal index ranges
// in index order (the envelope a pixel column shows), and the first and last index.
std::vector<std::size_t> keep(const Series& s, std::size_t limit, std::size_t buckets) {
  const std::size_t n = s.y.size();
  std::vector<std::size_t> idx;
  if (limit == 0 || n <= limit || buckets == 0) {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      idx[i] = i;
    return idx;
  }
  idx.reserve(2 * buckets);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t i0 = b * n / buckets;
    const std::size_t i1 = (b + 1) * n / buckets;
    if (i0 == i1) continue;
    std::size_t lo = i0, hi = i0;
    for (std::size_t i = i0; i < i1; ++i) {
      if (s.y[i] < s.y[lo]) lo = i;
      if (s.y[i] > s.y[hi]) hi = i;
    }
    // The first and the last point are kept too, so every panel spans the same x.
    const std::size_t first = std::min(lo, hi), last = std::max(lo, hi);
    for (std::size_t i : {b == 0 ? i0 : first, first, last, b + 1 == buckets ? i1 - 1 : last}) {
      if (idx.empty() || i > idx.back()) idx.push_back(i);
    }
  }
  return idx;
}

// The data file: one gnuplot index (a block ended by two blank lines) per series, panel by
// panel; a point a log axis cannot show becomes a single blank line, so the line breaks there.
void write_data(const Figure& f, const std::string& path, const RenderOptions& o) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(Error::Kind::kIo, path + ": cannot write the data file");
  out << "# ntn::plot data: one block per series (gnuplot index), x then y\n";
  char buf[64];
  for (const Panel& panel : f.panels) {
    for (const Series& s : panel.series) {
      std::string name = s.name;  // a comment line: no line break inside
      std::replace_if(
          name.begin(), name.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
      out << "# " << name << '\n';
      // A gap is written only between two drawn points: a blank line more at either end would
      // make two and end the gnuplot index.
      bool drawn = false;
      bool gap = false;
      for (std::size_t i : keep(s, o.decimate_above, static_cast<std::size_t>(f.width))) {
        if ((panel.x_scale == Scale::kLog && !(s.x[i] > 0)) ||
            (panel.y_scale == Scale::kLog && !(s.y[i] > 0))) {
          gap = drawn;
          continue;
        }
        if (gap) out << '\n';
        gap = false;
        drawn = true;
        std::snprintf(buf, sizeof buf, "%.10g %.10g\n", s.x[i], s.y[i]);
        out << buf;
      }
      out << "\n\n";
    }
  }
  if (!out.flush()) throw Error(Error::Kind::kIo, path + ": cannot write the data file");
}

// The x extent gnuplot draws a panel over (autoscale xfix: the drawable points, or the range
// given); a marker outside it is left out, since gnuplot would draw it over the margin.
std::pair<double, double> x_extent(const Panel& panel) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Series& s : panel.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (panel.x_scale == Scale::kLog && !(s.x[i] > 0)) continue;
      if (panel.y_scale == Scale::kLog && !(s.y[i] > 0)) continue;
      lo = std::min(lo, s.x[i]);
      hi = std::max(hi, s.x[i]);
    }
  }
  if (panel.x_range.min) lo = *panel.x_range.min;
  if (panel.x_range.max) hi = *panel.x_range.max;
  return {lo, hi};
}

bool drawn(const Marker& m, std::pair<double, double> extent) {
  return m.x >= extent.first && m.x <= extent.second;
}

std::string range(const Range& r) {
  return "[" + (r.min ? num(*r.min) : std::string("*")) + ":" +
         (r.max ? num(*r.max) : std::string("*")) + "]";
}

// The plotting commands, the same for both terminals.
std::string body(const Figure& f, const std::string& data) {
  std::ostringstream s;
  const std::size_t n = f.panels.size();
  s << "set multiplot layout " << n << ",1";
  if (!f.title.empty()) s << " title " << quote(f.title) << " font ',13' noenhanced";
  s << "\n";
  std::size_t block = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const Panel& panel = f.panels[p];
    s << "# " << where(p, panel) << "\n";
    s << "unset arrow\nunset label\n";
    s << "set title " << quote(panel.title) << " noenhanced\n";
    if (!f.shared_x || p + 1 == n) {
      s << "set xlabel " << quote(panel.x_label) << " noenhanced\n";
    } else {
      s << "unset xlabel\n";
    }
    s << "set ylabel " << quote(panel.y_label) << " noenhanced\n";
    s << (panel.x_scale == Scale::kLog ? "set logscale x\n" : "unset logscale x\n");
    s << (panel.y_scale == Scale::kLog ? "set logscale y\n" : "unset logscale y\n");
    s << "set format y " << (panel.y_scale == Scale::kLog ? "'10^{%L}'" : "'%g'") << "\n";
    // 5 % of air above and below the data on a linear y axis, so a peak does not hide in the
    // frame (autoscaling then rounds out to the next tic).
    s << (panel.y_scale == Scale::kLinear ? "set offsets 0, 0, graph 0.05, graph 0.05\n"
                                          : "set offsets 0, 0, 0, 0\n");
    s << "set xrange " << range(panel.x_range) << "\n";
    s << "set yrange " << range(panel.y_range) << "\n";
    const auto extent = x_extent(panel);
    for (const Marker& m : panel.markers) {
      if (!drawn(m, extent)) continue;
      const std::string x = num(m.x);
      s << "set arrow from first " << x << ", graph 0 to first " << x
        << ", graph 1 nohead dashtype 2 linewidth 1.2 linecolor rgb '#505050' back\n";
      if (!m.label.empty())
        s << "set label " << quote(m.label) << " at first " << x
          << ", graph 0.98 rotate by 90 right offset character 1.3, 0 textcolor rgb '#303030' "
             "front noenhanced\n";
    }
    s << "plot ";
    for (std::size_t k = 0; k < panel.series.size(); ++k, ++block) {
      if (k > 0) s << ", \\\n     ";
      s << quote(data) << " index " << block << " using 1:2 with lines linewidth "
        << num(panel.series[k].width, "%g") << " linecolor rgb '"
        << (panel.series[k].colour.empty() ? kColours[k % kColourCount] : panel.series[k].colour)
        << "' title " << quote(panel.series[k].name) << " noenhanced";
    }
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

}  // namespace

void clip_log_floor(Panel& p, double decades) {
  if (p.y_scale != Scale::kLog || p.y_range.min) return;
  double top = 0, low = std::numeric_limits<double>::infinity();
  for (const Series& s : p.series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if ((p.x_range.min && s.x[i] < *p.x_range.min) || (p.x_range.max && s.x[i] > *p.x_range.max))
        continue;
      if (!(s.y[i] > 0)) continue;
      top = std::max(top, s.y[i]);
      low = std::min(low, s.y[i]);
    }
  }
  const double floor = top * std::pow(10.0, -decades);
  if (top > 0 && low < floor) p.y_range.min = floor;
}

int default_height(std::size_t panels) {
  return std::max(480, 240 * static_cast<int>(panels));
}

std::string script(const Figure& f, const std::string& base, const std::string& data_file,
                   const RenderOptions& o) {
  check(f);
  const int width = f.width;
  const int height = f.height > 0 ? f.height : default_height(f.panels.size());
  const std::string b = body(f, data_file);
  std::ostringstream s;
  s << "# Written by ntn::plot (tools/plot). `gnuplot " << base
    << ".gp` makes the plots again.\n"
       "set encoding utf8\n"
       "set grid xtics ytics linecolor rgb '#cccccc' linewidth 0.8 dashtype solid\n"
       // The legend above the panel, right-aligned, so it never hides the data.
       "set key tmargin right horizontal samplen 2\n"
       "set border linewidth 1\n"
       "set tics nomirror out\n"
       "set mxtics\nset mytics\n"
       "set autoscale xfix\n"
       "set lmargin 12\nset rmargin 4\n";
  if (o.png) {
    s << "\nset terminal pngcairo size " << width << "," << height
      << " enhanced font 'Sans,10' background rgb 'white'\n"
      << "set output " << quote(base + ".png") << "\n"
      << b << "set output\n";
  }
  if (o.svg) {
    s << "\nset terminal svg size " << width << "," << height
      << " enhanced font 'Sans,11' background rgb 'white'\n"
      << "set output " << quote(base + ".svg") << "\n"
      << b << "set output\n";
  }
  return s.str();
}

std::string find_program(const std::string& program) {
  const auto executable = [](const std::string& p) {
    struct stat st {};
    return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
  };
  if (program.empty()) return {};
  if (program.find('/') != std::string::npos) return executable(program) ? program : std::string();
  const char* path = std::getenv("PATH");
  if (path == nullptr) return {};
  std::string_view rest(path);
  while (!rest.empty()) {
    const std::size_t colon = std::min(rest.find(':'), rest.size());
    const std::string dir(rest.substr(0, colon));
    rest.remove_prefix(std::min(colon + 1, rest.size()));
    if (dir.empty()) continue;  // an empty entry (the current directory) is not searched
    const std::string candidate = dir + "/" + program;
    if (executable(candidate)) return candidate;
  }
  return {};
}

namespace {

// Runs `program args...` without a shell: stdin and stdout /dev/null, stderr returned.
// Returns the exit status (128 + signal when killed).
int run(const std::string& program, const std::vector<std::string>& args, std::string& err) {
  int pipe_fd[2];
  if (::pipe(pipe_fd) != 0)
    throw Error(Error::Kind::kGnuplotFailed, std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], 2);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[0]);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[1]);
  std::vector<char*> argv;
  std::vector<std::string> storage{program};
  storage.insert(storage.end(), args.begin(), args.end());
  for (std::string& a : storage)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fd[1]);
  if (rc != 0) {
    ::close(pipe_fd[0]);
    throw Error(
        rc == ENOENT || rc == EACCES ? Error::Kind::kGnuplotMissing : Error::Kind::kGnuplotFailed,
        "cannot run '" + program + "': " + std::strerror(rc));
  }
  char buf[4096];
  while (true) {
    const ssize_t got = ::read(pipe_fd[0], buf, sizeof buf);
    if (got > 0) {
      err.append(buf, static_cast<std::size_t>(got));
    } else if (got == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(pipe_fd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return 127;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    if (l.find_first_not_of(" \t\r") != std::string::npos) out.push_back(l);
  }
  return out;
}

// Why the plot file at `path` is not a whole plot, or "" when it is: a PNG ends with its IEND
// chunk, an SVG with </svg>. A file cut by a full disk (gnuplot may still exit 0) fails.
std::string incomplete(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return "no file";
  if (size == 0) return "an empty file";
  std::ifstream in(path, std::ios::binary);
  const bool png = path.size() > 4 && path.compare(path.size() - 4, 4, ".png") == 0;
  const std::string cut = "only the first " + std::to_string(size) + " bytes";
  if (png) {
    static constexpr unsigned char kIend[12] = {0,   0,   0,    0,    'I',  'E',
                                                'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    if (size < 8 + sizeof kIend) return cut;
    char tail[sizeof kIend];
    in.seekg(-static_cast<std::streamoff>(sizeof kIend), std::ios::end);
    if (!in.read(tail, sizeof tail) || std::memcmp(tail, kIend, sizeof kIend) != 0) return cut;
    return "";
  }
  const std::streamoff n = std::min<std::streamoff>(static_cast<std::streamoff>(size), 64);
  std::string tail(static_cast<std::size_t>(n), '\0');
  in.seekg(-n, std::ios::end);
  if (!in.read(tail.data(), n)) return cut;
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back())))
    tail.pop_back();
  const std::string end = "</svg>";
  if (tail.size() < end.size() || tail.compare(tail.size() - end.size(), end.size(), end) != 0)
    return cut;
  return "";
}

}  // namespace

Rendered render(const Figure& f, const std::string& base, const RenderOptions& o) {
  check(f);
  if (!o.png && !o.svg) input_error("neither PNG nor SVG asked for");
  if (base.empty()) input_error("no output name");
  const fs::path parent = fs::path(base).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw Error(Error::Kind::kIo,
                base + ": the directory '" + parent.string() + "' does not exist");

  const std::string program = find_program(o.gnuplot);
  if (program.empty()) {
    const char* path = std::getenv("PATH");
    std::string where_looked = o.gnuplot.find('/') != std::string::npos
                                   ? "'" + o.gnuplot + "' is not an executable file"
                                   : "no executable '" + o.gnuplot + "' in PATH=" +
                                         (path != nullptr ? std::string(path) : "(unset)");
    throw Error(Error::Kind::kGnuplotMissing,
                "gnuplot not found (" + where_looked +
                    "). Install the Debian package gnuplot-nox (apt-get install gnuplot-nox; "
                    "tools/common.sh lists it), or name the program to run (ntn-plot --gnuplot "
                    "PROG, RenderOptions::gnuplot)");
  }

  Rendered r;
  const std::string absolute_base = fs::absolute(base).lexically_normal().string();
  r.script = base + ".gp";
  r.data = base + ".dat";
  if (o.png) r.png = base + ".png";
  if (o.svg) r.svg = base + ".svg";
  // gnuplot writes BASE.part.png and BASE.part.svg, which are checked whole and renamed: a plot
  // at BASE.png is complete or absent, whatever gnuplot or the disk do.
  const std::string part_base = base + ".part";
  const std::string part_script = part_base + ".gp";
  const std::vector<std::pair<std::string, std::string>> outputs = [&] {
    std::vector<std::pair<std::string, std::string>> v;
    if (o.png) v.emplace_back(part_base + ".png", r.png);
    if (o.svg) v.emplace_back(part_base + ".svg", r.svg);
    return v;
  }();
  std::error_code ec;
  const auto remove_plots = [&] {
    for (const auto& [part, final_path] : outputs) {
      fs::remove(part, ec);
      fs::remove(final_path, ec);
    }
  };
  const auto cleanup = [&] {
    fs::remove(part_script, ec);
    if (!o.keep_script) {
      fs::remove(r.script, ec);
      fs::remove(r.data, ec);
    }
  };
  remove_plots();  // a stale plot must not pass for a new one

  const auto write_script = [&](const std::string& path, const std::string& out_base) {
    std::ofstream out(path, std::ios::binary);
    out << script(f, out_base, absolute_base + ".dat", o);
    if (!out.flush()) {
      cleanup();
      throw Error(Error::Kind::kIo, path + ": cannot write the script");
    }
  };
  try {
    write_data(f, r.data, o);
  } catch (const Error&) {
    cleanup();
    throw;
  }
  write_script(part_script, fs::absolute(part_base).lexically_normal().string());
  std::string err;
  // --default-settings: no ~/.gnuplot or system init file changes what is drawn.
  const int status = run(program, {"--default-settings", part_script}, err);
  if (status != 0) {
    cleanup();
    remove_plots();
    std::string hint;
    if (err.find("unknown or ambiguous terminal") != std::string::npos)
      hint = " (this gnuplot lacks the pngcairo or svg terminal; Debian's gnuplot-nox has both)";
    throw Error(Error::Kind::kGnuplotFailed, "'" + program + "' exited with status " +
                                                 std::to_string(status) + hint + ":\n" + err);
  }
  for (const auto& [part, final_path] : outputs) {
    const std::string why = incomplete(part);
    if (!why.empty()) {
      cleanup();
      remove_plots();
      const bool missing = why == "no file";
      throw Error(missing ? Error::Kind::kGnuplotFailed : Error::Kind::kIo,
                  missing
                      ? "'" + program + "' exited 0 but did not write " + final_path + ":\n" + err
                      : final_path + ": gnuplot wrote " + why +
                            " (a full disk or a file size limit?); no plot is left");
    }
  }
  for (const auto& [part, final_path] : outputs) {
    fs::rename(part, final_path, ec);
    if (ec) {
      const std::string why = ec.message();
      cleanup();
      remove_plots();
      throw Error(Error::Kind::kIo, final_path + ": cannot write: " + why);
    }
  }
  if (o.keep_script) write_script(r.script, absolute_base);  // names the plots themselves
  cleanup();
  r.warnings = lines(err);
  for (std::size_t p = 0; p < f.panels.size(); ++p) {
    const auto extent = x_extent(f.panels[p]);
    for (const Marker& m : f.panels[p].markers) {
      if (!drawn(m, extent))
        r.notes.push_back(where(p, f.panels[p]) + ": marker '" + m.label + "' at " +
                          num(m.x, "%g") + " lies outside the x extent " + num(extent.first, "%g") +
                          " ... " + num(extent.second, "%g") + ": not drawn");
    }
  }
  return r;
}

}  // namespace ntn::plot
