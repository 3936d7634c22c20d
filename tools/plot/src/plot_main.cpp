// ntn-plot: PNG and SVG plots of a run's histories and of spectra, through gnuplot.
//   ntn-plot history RUN.csv [--channels a,b+c] [--model M.toml --kind hinge_force] --out BASE
//   ntn-plot psd SPECTRUM.csv [--columns a,b] [--marks 1.60,mode 2=1.739] --out BASE
// Exit 0 ok; 2 bad input or usage (unreadable file, unknown channel, NaN, an output directory
// that does not exist, ...); 3 gnuplot missing or failed. README.md has the details.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli.hpp"  // tools/io: validators that print numbers with %g and refuse NaN and inf
#include "ntn/laws/table.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/plot/plot.hpp"
#include "ntn/plot/table.hpp"

namespace {

namespace pl = ntn::plot;

[[noreturn]] void bad(const std::string& message) {
  throw pl::Error(pl::Error::Kind::kInput, message);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  for (std::size_t i = 0;;) {
    const std::size_t e = std::min(s.find(sep, i), s.size());
    std::string item = s.substr(i, e - i);
    const auto b = item.find_first_not_of(' ');
    item =
        b == std::string::npos ? std::string() : item.substr(b, item.find_last_not_of(' ') - b + 1);
    out.push_back(item);
    if (e >= s.size()) break;
    i = e + 1;
  }
  return out;
}

double number(const std::string& s, const std::string& what) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
    bad(what + ": '" + s + "' is not a number");
  return v;
}

std::string fmt(const char* f, double v) {
  char b[48];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string with_unit(const std::string& text, const std::string& unit) {
  return unit.empty() ? text : text + " [" + unit + "]";
}

// Options both subcommands share.
struct Common {
  std::string file;
  std::string out;
  std::string title;
  std::string size;  // WxH
  std::string gnuplot = "gnuplot";
  bool keep_script = false;
  bool no_png = false;
  bool no_svg = false;
};

void add_common(ntn::cli::App* c, Common& o) {
  c->add_option("file", o.file, "input file")->required();
  c->add_option("-o,--out", o.out, "output base: writes BASE.png and BASE.svg")->required();
  c->add_option("--title", o.title, "figure title (default: the file name)");
  c->add_option("--size", o.size, "WIDTHxHEIGHT in px (default 1200 x 240 per panel, >= 480)");
  c->add_option("--gnuplot", o.gnuplot, "gnuplot program (a name in PATH or a path)");
  c->add_flag("--keep-script", o.keep_script, "keep BASE.gp and BASE.dat (gnuplot BASE.gp)");
  c->add_flag("--no-png", o.no_png, "write only the SVG");
  c->add_flag("--no-svg", o.no_svg, "write only the PNG");
}

pl::Rendered draw(pl::Figure& fig, const Common& o) {
  if (fig.title.empty()) fig.title = std::filesystem::path(o.file).filename().string();
  if (!o.size.empty()) {
    const auto x = o.size.find('x');
    if (x == std::string::npos) bad("--size wants WIDTHxHEIGHT, got '" + o.size + "'");
    const double w = number(o.size.substr(0, x), "--size width");
    const double h = number(o.size.substr(x + 1), "--size height");
    if (w != std::floor(w) || h != std::floor(h) || w < 100 || h < 100 || w > 10000 || h > 20000)
      bad("--size: " + o.size + " is not a size in px (100 ... 10000 x 100 ... 20000)");
    fig.width = static_cast<int>(w);
    fig.height = static_cast<int>(h);
  }
  pl::RenderOptions ro;
  ro.gnuplot = o.gnuplot;
  ro.keep_script = o.keep_script;
  ro.png = !o.no_png;
  ro.svg = !o.no_svg;
  return pl::render(fig, o.out, ro);
}

// The model's output names of one kind (as the TOML spells it).
std::vector<std::string> outputs_of_kind(const std::string& model_file, const std::string& kind) {
  using K = ntn::OutputKind;
  static const std::pair<const char*, K> kKinds[] = {
      {"displacement", K::kDisplacement},
      {"velocity", K::kVelocity},
      {"acceleration", K::kAcceleration},
      {"element_force", K::kElementForce},
      {"drift", K::kDrift},
      {"reaction", K::kReaction},
      {"absolute_acceleration", K::kAbsoluteAcceleration},
      {"hinge_force", K::kHingeForce},
      {"hinge_displacement", K::kHingeDisplacement},
      {"hinge_plastic_deformation", K::kHingePlastic},
      {"hinge_dissipated_energy", K::kHingeDissipated},
      {"hinge_performance_level", K::kHingeLevel},
      {"hinge_velocity", K::kHingeVelocity},
      {"hinge_slip_state", K::kHingeSlipState}};
  const auto it = std::find_if(std::begin(kKinds), std::end(kKinds),
                               [&](const auto& k) { return kind == k.first; });
  if (it == std::end(kKinds)) {
    std::string list;
    for (const auto& k : kKinds)
      list += (list.empty() ? "" : ", ") + std::string(k.first);
    bad("--kind: no output kind '" + kind + "' (kinds: " + list + ")");
  }
  const ntn::modelc::LoadResult r = ntn::modelc::load_model(model_file);
  if (!r.ok()) bad(ntn::modelc::format_all(r.errors) + "--model: the model does not load");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < r.model->outputs.size(); ++i) {
    if (r.model->outputs[i].kind == it->second) names.push_back(r.model->output_names[i]);
  }
  if (names.empty()) bad(model_file + " has no output of kind '" + kind + "'");
  return names;
}

struct HistoryArgs {
  std::string channels;  // "a,b+c": panels separated by ',', channels in a panel by '+'
  std::string model;
  std::string kind;
  std::string from, to;  // s
};

pl::Figure history(const Common& o, const HistoryArgs& a) {
  const pl::Table t = pl::read_table(o.file, "s");
  // Panels: --channels, or the model's outputs of --kind (one panel each), or every channel.
  std::vector<std::vector<std::size_t>> panels;
  if (!a.channels.empty()) {
    for (const std::string& panel : split(a.channels, ',')) {
      std::vector<std::size_t> cols;
      for (const std::string& name : split(panel, '+')) {
        if (name.empty()) bad("--channels: an empty name in '" + a.channels + "'");
        cols.push_back(t.index(name));
      }
      panels.push_back(cols);
    }
  }
  if (!a.kind.empty()) {
    for (const std::string& name : outputs_of_kind(a.model, a.kind))
      panels.push_back({t.index(name)});
  }
  if (panels.empty()) {
    for (std::size_t c = 0; c < t.names.size(); ++c)
      panels.push_back({c});
  }

  // The time window [from, to], by rows.
  const double t_from = a.from.empty() ? t.x.front() : number(a.from, "--from");
  const double t_to = a.to.empty() ? t.x.back() : number(a.to, "--to");
  const auto r0 =
      static_cast<std::size_t>(std::lower_bound(t.x.begin(), t.x.end(), t_from) - t.x.begin());
  const auto r1 =
      static_cast<std::size_t>(std::upper_bound(t.x.begin(), t.x.end(), t_to) - t.x.begin());
  if (r1 < r0 + 2)
    bad("--from/--to: fewer than 2 rows of " + o.file + " lie in [" + fmt("%g", t_from) + ", " +
        fmt("%g", t_to) + "] s (the file spans " + fmt("%g", t.x.front()) + " ... " +
        fmt("%g", t.x.back()) + " s)");
  const std::vector<double> time(t.x.begin() + static_cast<std::ptrdiff_t>(r0),
                                 t.x.begin() + static_cast<std::ptrdiff_t>(r1));

  pl::Figure fig;
  fig.title = o.title;
  for (const auto& cols : panels) {
    pl::Panel& p = fig.panels.emplace_back();
    p.x_label = with_unit(t.x_name.empty() ? "time" : t.x_name, t.x_unit.empty() ? "s" : t.x_unit);
    std::string names;
    for (std::size_t c : cols) {
      if (t.units[c] != t.units[cols.front()])
        bad("--channels: one panel mixes units: " +
            with_unit(t.names[cols.front()], t.units[cols.front()]) + " and " +
            with_unit(t.names[c], t.units[c]) + " (give them panels of their own)");
      names += (names.empty() ? "" : ", ") + t.names[c];
      p.series.push_back(
          {t.names[c], time,
           std::vector<double>(t.columns[c].begin() + static_cast<std::ptrdiff_t>(r0),
                               t.columns[c].begin() + static_cast<std::ptrdiff_t>(r1))});
    }
    p.y_label = with_unit(names, t.units[cols.front()]);
  }
  return fig;
}

struct HysteresisArgs {
  std::string deformation, force;  // the CSV's channels for x and y
  std::string model, hinge, direction;
  std::string from, to;  // s
};

// A plastic hinge direction's force-deformation loops: the force channel over the
// deformation channel; with --model, --hinge and --direction, the law's monotonic envelope
// (bilinear: k up to the yield, then b k; backbone: its points A-B-C-D-E, no strength past E)
// and the acceptance limits IO, LS, CP marked at the deformations where the envelope reaches
// those plastic deformations.
pl::Figure hysteresis(const Common& o, const HysteresisArgs& a) {
  const pl::Table t = pl::read_table(o.file, "s");
  const std::size_t cx = t.index(a.deformation), cy = t.index(a.force);
  const double t_from = a.from.empty() ? t.x.front() : number(a.from, "--from");
  const double t_to = a.to.empty() ? t.x.back() : number(a.to, "--to");
  const auto r0 =
      static_cast<std::size_t>(std::lower_bound(t.x.begin(), t.x.end(), t_from) - t.x.begin());
  const auto r1 =
      static_cast<std::size_t>(std::upper_bound(t.x.begin(), t.x.end(), t_to) - t.x.begin());
  if (r1 < r0 + 2) bad("--from/--to: fewer than 2 rows of " + o.file + " in the window");
  auto slice = [&](std::size_t c) {
    return std::vector<double>(t.columns[c].begin() + static_cast<std::ptrdiff_t>(r0),
                               t.columns[c].begin() + static_cast<std::ptrdiff_t>(r1));
  };
  pl::Figure fig;
  fig.title = o.title;
  fig.height = 800;
  fig.width = 1000;
  pl::Panel& p = fig.panels.emplace_back();
  p.x_label = with_unit(t.names[cx], t.units[cx]);
  p.y_label = with_unit(t.names[cy], t.units[cy]);
  p.series.push_back({t.names[cy] + " over " + t.names[cx], slice(cx), slice(cy)});
  if (a.model.empty()) return fig;
  if (a.hinge.empty() || a.direction.empty()) bad("--model needs --hinge and --direction");
  const ntn::modelc::LoadResult r = ntn::modelc::load_model(a.model);
  if (!r.ok()) bad(ntn::modelc::format_all(r.errors) + "--model: the model does not load");
  const ntn::modelc::ModelDescription& m = *r.model;
  int h = -1;
  for (std::size_t i = 0; i < m.hinge_info.size(); ++i) {
    if (m.hinge_info[i].name == a.hinge) h = static_cast<int>(i);
  }
  if (h < 0) bad("--hinge: " + a.model + " has no hinge '" + a.hinge + "'");
  static const char* const kDir[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const auto* it = std::find(std::begin(kDir), std::end(kDir), a.direction);
  if (it == std::end(kDir)) bad("--direction: one of ux, uy, uz, rx, ry, rz");
  const auto k = static_cast<std::size_t>(it - std::begin(kDir));
  const ntn::HingeSpec& hs = m.hinges[static_cast<std::size_t>(h)];
  if (hs.behaviour[k] != ntn::HingeBehaviour::kPlastic)
    bad("--direction: " + a.direction + " of hinge " + a.hinge + " is not plastic");
  const ntn::HysteresisSpec& law = m.hystereses[static_cast<std::size_t>(hs.hysteresis[k])];
  const double kel = hs.stiffness[k];
  static const char* const kLevel[3] = {"IO", "LS", "CP"};
  // The frame is the loops' (and the yield's, so the envelope's knee shows): a limit beyond it
  // is marked at the edge with its value, not drawn by an axis many times wider than the data.
  const auto [lo, hi] = std::minmax_element(p.series[0].x.begin(), p.series[0].x.end());
  const double span = std::max(std::abs(*lo), std::abs(*hi));
  const auto frame = [&p, span](double yield_d) {
    const double edge = 1.15 * std::max(span, 1.5 * yield_d);
    p.x_range = {-edge, edge};
    // The limits beyond each edge, as one mark there ("beyond: IO 0.0113, LS 0.0152, CP 0.019";
    // the label is drawn right of its line, so the right one stands a little inside).
    std::vector<pl::Marker> kept;
    std::string beyond[2];
    for (const pl::Marker& mk : p.markers) {
      if (std::abs(mk.x) <= edge) {
        kept.push_back(mk);
      } else {
        std::string& b = beyond[mk.x > 0 ? 1 : 0];
        b += (b.empty() ? "beyond: " : ", ") + mk.label + " " + fmt("%.3g", mk.x);
      }
    }
    for (int side = 0; side < 2; ++side)
      if (!beyond[side].empty()) kept.push_back({(side ? 0.93 : -0.98) * edge, beyond[side]});
    p.markers = std::move(kept);
  };
  if (ntn::law_has_envelope(law.rule)) {
    // The backbone A-B-C-D-E of each sense, then no strength past E; the limits where the
    // envelope's plastic deformation d - f / k reaches them (it grows along every segment).
    pl::Series env{std::string("backbone (") + ntn::law_name(law.rule) + ")", {}, {}};
    const std::array<ntn::CurvePoint, 4> envelope[2] = {ntn::law_envelope(law, kel, -1),
                                                        ntn::law_envelope(law, kel, 1)};
    for (int side : {-1, 1}) {
      const auto& pts = envelope[side > 0 ? 1 : 0];
      std::vector<double> xs{0.0}, ys{0.0};
      for (const ntn::CurvePoint& q : pts)
        xs.push_back(side * q.d), ys.push_back(side * q.force);
      xs.push_back(side * pts[3].d), ys.push_back(0.0);
      if (side < 0) {
        env.x.insert(env.x.end(), xs.rbegin(), xs.rend());
        env.y.insert(env.y.end(), ys.rbegin(), ys.rend());
      } else {
        env.x.insert(env.x.end(), xs.begin() + 1, xs.end());
        env.y.insert(env.y.end(), ys.begin() + 1, ys.end());
      }
      for (std::size_t l = 0; law.limits[0] > 0 && l < 3; ++l) {
        const double dp = law.limits[l];
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
          const ntn::CurvePoint &q0 = pts[i], &q1 = pts[i + 1];
          const double p0 = q0.d - q0.force / kel, p1 = q1.d - q1.force / kel;
          if (dp < p0 || dp > p1 || !(p1 > p0)) continue;
          const double at = (dp - p0) / (p1 - p0);
          p.markers.push_back({side * (q0.d + at * (q1.d - q0.d)), kLevel[l]});
          break;
        }
      }
    }
    p.series.push_back(env);
    frame(std::min(envelope[1][0].d, envelope[0][0].d));
    return fig;
  }
  const double H = law.hardening * kel / (1.0 - law.hardening);
  // The envelope d(d_p) = d_p + (F_y + H d_p) / k on each side, drawn over the frame.
  pl::Series env{"envelope (bilinear, b = " + fmt("%g", law.hardening) + ")", {}, {}};
  for (int side : {-1, 1}) {
    const double fy = side > 0 ? law.yield_pos : law.yield_neg;
    const double dy = fy / kel;
    std::vector<double> xs{0.0, side * dy}, ys{0.0, side * fy};
    // To the frame's edge (frame() below); the limits beyond it are marked there.
    const double far = 1.15 * std::max(span, 1.5 * std::min(law.yield_pos, law.yield_neg) / kel);
    if (far > dy) {
      xs.push_back(side * far);
      ys.push_back(side * (fy + law.hardening * kel * (far - dy)));
    }
    if (side < 0) {
      env.x.insert(env.x.end(), xs.rbegin(), xs.rend());
      env.y.insert(env.y.end(), ys.rbegin(), ys.rend());
    } else {
      env.x.insert(env.x.end(), xs.begin() + 1, xs.end());
      env.y.insert(env.y.end(), ys.begin() + 1, ys.end());
    }
    if (law.limits[0] > 0) {
      for (std::size_t l = 0; l < 3; ++l) {
        const double dp = law.limits[l];
        const double d = dp + (fy + H * dp) / kel;
        p.markers.push_back({side * d, kLevel[l]});
      }
    }
  }
  p.series.push_back(env);
  frame(std::min(law.yield_pos, law.yield_neg) / kel);
  return fig;
}

struct PsdArgs {
  std::string columns;
  std::string marks;  // "1.60,mode 2=1.739"
  std::string y_label;
  std::string fmin, fmax;
  bool linear = false;
  bool log_x = false;
};

pl::Figure psd(const Common& o, const PsdArgs& a) {
  const pl::Table t = pl::read_table(o.file, "Hz");
  std::vector<std::size_t> cols;
  if (a.columns.empty()) {
    for (std::size_t c = 0; c < t.names.size(); ++c)
      cols.push_back(c);
  } else {
    for (const std::string& name : split(a.columns, ','))
      cols.push_back(t.index(name));
  }
  pl::Figure fig;
  fig.title = o.title;
  pl::Panel& p = fig.panels.emplace_back();
  p.x_label =
      with_unit(t.x_name.empty() ? "frequency" : t.x_name, t.x_unit.empty() ? "Hz" : t.x_unit);
  std::string unit = t.units[cols.front()];
  for (std::size_t c : cols) {
    if (t.units[c] != unit) unit.clear();  // mixed: the legend names them
    p.series.push_back({with_unit(t.names[c], t.units[c]), t.x, t.columns[c]});
  }
  p.y_label = a.y_label.empty()
                  ? with_unit(cols.size() == 1 ? t.names[cols.front()] + " PSD" : "PSD", unit)
                  : a.y_label;
  p.y_scale = a.linear ? pl::Scale::kLinear : pl::Scale::kLog;
  p.x_scale = a.log_x ? pl::Scale::kLog : pl::Scale::kLinear;
  // The frequency window must hold data: a window beyond the file's frequencies (--fmin 1e308)
  // left gnuplot to fail on an empty range.
  const std::string span =
      " (the file spans " + fmt("%g", t.x.front()) + " ... " + fmt("%g", t.x.back()) + " Hz)";
  if (!a.fmin.empty()) {
    p.x_range.min = number(a.fmin, "--fmin");
    if (!(*p.x_range.min < t.x.back()))
      bad("--fmin " + fmt("%g", *p.x_range.min) + " Hz: no data above it" + span);
  }
  if (!a.fmax.empty()) {
    p.x_range.max = number(a.fmax, "--fmax");
    if (!(*p.x_range.max > t.x.front()))
      bad("--fmax " + fmt("%g", *p.x_range.max) + " Hz: no data below it" + span);
  }
  if (p.x_range.min && p.x_range.max && !(*p.x_range.min < *p.x_range.max))
    bad("--fmin " + fmt("%g", *p.x_range.min) + " Hz must be below --fmax " +
        fmt("%g", *p.x_range.max) + " Hz");
  if (!a.marks.empty()) {
    for (const std::string& m : split(a.marks, ',')) {
      const auto eq = m.rfind('=');
      const std::string label = eq == std::string::npos ? std::string() : m.substr(0, eq);
      const double f = number(eq == std::string::npos ? m : m.substr(eq + 1), "--marks");
      const std::string hz = fmt("%.4g Hz", f);
      p.markers.push_back({f, label.empty() ? hz : label + "  " + hz});
    }
  }
  pl::clip_log_floor(p);  // once the frequency window is known
  return fig;
}

}  // namespace

int main(int argc, char** argv) {
  ntn::cli::App app{"PNG and SVG plots of histories and spectra (gnuplot)"};
  app.require_subcommand(1);
  Common ho, po, yo;
  HistoryArgs ha;
  PsdArgs pa;
  HysteresisArgs ya;
  ntn::cli::App* h = app.add_subcommand(
      "history", "one panel per channel (or group) of a run's CSV (time[s],name[unit],...) or AT2");
  add_common(h, ho);
  h->add_option("-c,--channels", ha.channels,
                "panels separated by ',', channels in one panel by '+' (default: all)");
  h->add_option("--model", ha.model, "model file (.toml) for --kind");
  h->add_option("--kind", ha.kind, "add a panel per model output of this kind (hinge_force, ...)")
      ->needs("--model");
  h->add_option("--from", ha.from, "start time in s")->check(ntn::cli::Finite());
  h->add_option("--to", ha.to, "end time in s")->check(ntn::cli::Finite());
  ntn::cli::App* s = app.add_subcommand(
      "psd", "spectra from a CSV (frequency[Hz],name[unit],...), with marked frequencies");
  add_common(s, po);
  s->add_option("--columns", pa.columns, "columns to draw, separated by ',' (default: all)");
  s->add_option("-m,--marks", pa.marks, "frequencies to mark, 'F' or 'LABEL=F', separated by ','");
  s->add_option("--ylabel", pa.y_label, "y axis label (default: PSD [unit])");
  s->add_option("--fmin", pa.fmin, "lowest frequency drawn, Hz")->check(ntn::cli::Finite());
  s->add_option("--fmax", pa.fmax, "highest frequency drawn, Hz")->check(ntn::cli::Finite());
  s->add_flag("--linear", pa.linear, "linear y axis (default: log)");
  s->add_flag("--logx", pa.log_x, "log frequency axis");
  ntn::cli::App* y = app.add_subcommand(
      "hysteresis", "a hinge direction's force over its deformation (two channels of a run's CSV)");
  add_common(y, yo);
  y->add_option("-x,--deformation", ya.deformation, "deformation channel (x)")->required();
  y->add_option("-y,--force", ya.force, "force channel (y)")->required();
  y->add_option("--model", ya.model, "model file (.toml): draw the plastic law's envelope");
  y->add_option("--hinge", ya.hinge, "the hinge (its name in the model)")->needs("--model");
  y->add_option("--direction", ya.direction, "its direction (ux ... rz)")->needs("--model");
  y->add_option("--from", ya.from, "start time in s")->check(ntn::cli::Finite());
  y->add_option("--to", ya.to, "end time in s")->check(ntn::cli::Finite());
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;

  try {
    const bool is_history = h->parsed();
    const bool is_loops = y->parsed();
    const Common& o = is_history ? ho : is_loops ? yo : po;
    pl::Figure fig = is_history ? history(ho, ha) : is_loops ? hysteresis(yo, ya) : psd(po, pa);
    const pl::Rendered r = draw(fig, o);
    for (const std::string& w : r.warnings)
      std::fprintf(stderr, "gnuplot: %s\n", w.c_str());
    for (const std::string& n : r.notes)
      std::fprintf(stderr, "ntn-plot: note: %s\n", n.c_str());
    for (const std::string& f : {r.png, r.svg, o.keep_script ? r.script : std::string()})
      if (!f.empty()) std::printf("%s\n", f.c_str());
    return 0;
  } catch (const pl::Error& e) {
    // File errors already read "FILE:LINE:COLUMN: error: ...".
    const bool located = std::string(e.what()).find(": error: ") != std::string::npos;
    std::fprintf(stderr, "ntn-plot: %s%s\n", located ? "" : "error: ", e.what());
    const bool gnuplot =
        e.kind() == pl::Error::Kind::kGnuplotMissing || e.kind() == pl::Error::Kind::kGnuplotFailed;
    return gnuplot ? 3 : 2;
  }
}
