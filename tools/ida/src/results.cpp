#include "ntn/ida/results.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "cli.hpp"
#include "ntn/plot/plot.hpp"
#include "numbers.hpp"

namespace ntn::ida {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string number(double v) {
  return detail::exact(v);
}
std::string short_number(double v) {
  return detail::rounded(v, 3);
}

// The rows of record r, by intensity.
std::vector<const RunRow*> rows_of(const std::vector<RunRow>& rows, std::size_t r) {
  std::vector<const RunRow*> out;
  for (const RunRow& row : rows)
    if (row.record == r) out.push_back(&row);
  std::sort(out.begin(), out.end(), [](const RunRow* a, const RunRow* b) { return a->im < b->im; });
  return out;
}

// The hinge_level column, or nothing (a model without plastic hinges, or --edp left it out).
std::optional<std::size_t> level_column(const Study& study) {
  for (std::size_t k = 0; k < study.columns().size(); ++k)
    if (study.columns()[k].kind == EdpColumn::Kind::kHingeLevel) return k;
  return std::nullopt;
}

// The record's peak drift at intensity `im` along its IDA curve (linear between the runs that
// stood, from (0, 0)); +infinity past its collapse capacity; NaN above its highest run when it
// never collapsed (unknown there).
double drift_at(const std::vector<const RunRow*>& rows, double im) {
  double im0 = 0, d0 = 0;
  std::optional<double> collapse;
  for (const RunRow* row : rows)
    if (row->collapse && !collapse) collapse = row->im;
  for (const RunRow* row : rows) {
    if (row->error() || row->collapse) continue;
    if (collapse && row->im > *collapse) continue;
    if (im <= row->im) {
      const double w = (im - im0) / (row->im - im0);
      return d0 + w * (row->peak_drift - d0);
    }
    im0 = row->im, d0 = row->peak_drift;
  }
  return collapse ? kInf : std::numeric_limits<double>::quiet_NaN();
}

namespace pl = ntn::plot;

// results.csv: the header and one line per run.
std::string results_text(const Study& study, const std::vector<RunRow>& sorted) {
  std::string text = study.csv_header() + "\n";
  for (const RunRow& row : sorted)
    text += study.csv_row(row) + "\n";
  return text;
}

// capacities.csv: per record its intensity measures, the intensity at which it reached each limit
// state (empty: never), its highest intensity and whether it was traced to the end.
std::string capacities_text(const Study& study, const std::vector<RecordCapacities>& caps) {
  const auto& records = study.records();
  std::string text = "record,im_record[g],pga[g],io[g],ls[g],cp[g],collapse[g],highest[g],traced\n";
  for (std::size_t r = 0; r < records.size(); ++r) {
    const RecordCapacities& c = caps[r];
    text += records[r].name + "," + number(records[r].im) + "," + number(records[r].pga);
    for (const LimitState s : kLimitStates) {
      const Capacity& k = c.of(s);
      text += "," + (k.im ? number(*k.im) : std::string());
    }
    text += "," + number(c.collapse.highest) + "," + (c.traced ? "1" : "0") + "\n";
  }
  return text;
}

// fragility.csv: per limit state its fit, or the note that says why there is none (a carriage
// return in a note written as a space).
std::string fragility_text(const std::vector<Fragility>& fr) {
  std::string text = "limit_state,median[g],beta,observed,censored,note\n";
  for (const Fragility& f : fr) {
    text += std::string(limit_state_name(f.state)) + ",";
    if (f.fit.ok()) {
      text += number(f.fit.median) + "," + number(f.fit.beta);
    } else {
      text += ",";
    }
    text += "," + std::to_string(f.fit.observed) + "," + std::to_string(f.fit.censored) + "," +
            (f.fit.ok() ? std::string() : f.fit.error) + "\n";
  }
  for (char& c : text)
    if (c == '\r') c = ' ';
  return text;
}

// Each record's IDA curve in `p`: from (0, 0) through the runs that stood, then flat out to the
// drift limit (%) at its collapse. The records' rows, by intensity.
std::vector<std::vector<const RunRow*>> add_record_curves(pl::Panel& p,
                                                          const std::vector<RunRow>& sorted,
                                                          std::size_t records, double limit) {
  std::vector<std::vector<const RunRow*>> by_record;
  for (std::size_t r = 0; r < records; ++r) {
    by_record.push_back(rows_of(sorted, r));
    pl::Series s;
    s.x.push_back(0), s.y.push_back(0);
    for (const RunRow* row : by_record.back()) {
      if (row->error()) continue;
      if (row->collapse) {  // the flatline, out to the drift limit
        s.x.push_back(limit), s.y.push_back(s.y.back());
        break;
      }
      s.x.push_back(100 * row->peak_drift), s.y.push_back(row->im);
    }
    s.colour = "#a8a8a8", s.width = 1.0;
    if (r == 0) s.name = "records";
    if (s.x.size() > 1) p.series.push_back(std::move(s));
  }
  return by_record;
}

// The 16/50/84 % fractiles of drift given the intensity (collapse: infinite drift) in `p`, up to
// the lowest intensity some record did not reach without collapsing; `top`: the highest
// intensity run.
void add_fractile_curves(pl::Panel& p, const std::vector<std::vector<const RunRow*>>& by_record,
                         double top, double limit) {
  const double fractiles[3] = {0.16, 0.50, 0.84};
  const char* const colours[3] = {"#1f77b4", "#000000", "#d62728"};
  for (int j = 0; j < 3; ++j) {
    const double q = fractiles[j];
    pl::Series s;
    s.name = short_number(100 * q) + " % (drift given the intensity)";
    s.colour = colours[j], s.width = 2.5;
    for (int k = 0; k <= 60; ++k) {
      const double im = top * k / 60.0;
      std::vector<double> d;
      bool known = true;
      for (const auto& rr : by_record) {
        const double v = drift_at(rr, im);
        if (std::isnan(v)) known = false;
        d.push_back(v);
      }
      if (!known) break;
      const double f = fractile(d, q);
      if (!std::isfinite(f) || 100 * f > 1.1 * limit) break;
      s.x.push_back(100 * f), s.y.push_back(im);
    }
    if (s.x.size() > 1) p.series.push_back(std::move(s));
  }
}

// The IDA figure: the records' curves and their fractiles, peak storey drift against intensity.
pl::Figure ida_figure(const Study& study, const std::vector<RunRow>& sorted, double top,
                      const std::string& im_label) {
  const std::size_t records = study.records().size();
  pl::Figure fig;
  fig.title = "IDA curves: " + std::to_string(records) + " records";
  fig.height = 700;
  pl::Panel& p = fig.panels.emplace_back();
  p.x_label = "peak storey drift [%]";
  p.y_label = im_label;
  // Without a drift limit (--collapse-drift none) the flatlines go out to the largest drift of a
  // run that did not diverge (a diverged run's peaks are the state's blowing up).
  double limit = 100 * study.config().collapse_drift;
  if (!std::isfinite(limit)) {
    limit = 0;
    for (const RunRow& row : sorted)
      if (!row.error() && row.status != "diverged" && std::isfinite(row.peak_drift))
        limit = std::max(limit, 100 * row.peak_drift);
    if (!(limit > 0)) limit = 10;
  }
  p.x_range = {0.0, 1.1 * limit};
  p.y_range.min = 0.0;
  add_fractile_curves(p, add_record_curves(p, sorted, records, limit), top, limit);
  return fig;
}

// The records' capacities for limit state s as an empirical curve up to 1.2 `top` (censored
// records never step up).
pl::Series empirical_curve(LimitState s, const std::vector<RecordCapacities>& caps, double top) {
  std::vector<double> seen;
  for (const RecordCapacities& c : caps)
    if (c.traced && c.of(s).im) seen.push_back(*c.of(s).im);
  std::sort(seen.begin(), seen.end());
  std::size_t traced = 0;
  for (const RecordCapacities& c : caps)
    traced += c.traced ? 1 : 0;
  pl::Series e;
  e.name = std::string(limit_state_name(s)) + ": records";
  e.x.push_back(0), e.y.push_back(0);
  for (std::size_t k = 0; k < seen.size(); ++k) {
    e.x.push_back(seen[k]), e.y.push_back(static_cast<double>(k) / static_cast<double>(traced));
    e.x.push_back(seen[k]), e.y.push_back(static_cast<double>(k + 1) / static_cast<double>(traced));
  }
  e.x.push_back(1.2 * top), e.y.push_back(e.y.back());
  return e;
}

// The fragility figure: each fitted limit state's lognormal curve up to 1.2 `top` and the
// records' capacities beside it.
pl::Figure fragility_figure(const std::vector<Fragility>& fr,
                            const std::vector<RecordCapacities>& caps, double top,
                            const std::string& im_label) {
  pl::Figure fig;
  fig.title = "Fragility curves (lognormal, maximum likelihood)";
  fig.height = 600;
  pl::Panel& p = fig.panels.emplace_back();
  p.x_label = im_label;
  p.y_label = "probability of exceedance";
  p.y_range = {0.0, 1.0};
  for (const Fragility& f : fr) {
    if (!f.fit.ok()) continue;
    pl::Series s;
    s.name = std::string(limit_state_name(f.state)) + ": median " + short_number(f.fit.median) +
             " g, beta " + short_number(f.fit.beta);
    for (int k = 0; k <= 200; ++k) {
      const double im = 1.2 * top * k / 200.0;
      s.x.push_back(im), s.y.push_back(lognormal_cdf(im, f.fit.median, f.fit.beta));
    }
    p.series.push_back(std::move(s));
    p.series.push_back(empirical_curve(f.state, caps, top));
  }
  return fig;
}

// The plots DIR/ida (with drifts) and DIR/fragility (with a fit): their files into `w`,
// gnuplot's warnings and a plot with nothing to draw into `notes`, a plot error into
// w.plots_lost.
void draw_plots(const Study& study, const std::vector<RunRow>& sorted,
                const std::vector<RecordCapacities>& caps, const std::vector<Fragility>& fr,
                const std::string& dir, Written& w, std::vector<std::string>& notes) {
  namespace fs = std::filesystem;
  double top = 0;
  for (const RunRow& row : sorted)
    if (!row.error()) top = std::max(top, row.im);
  const std::string im_label = study.measure_name() + " [g]";
  try {
    if (study.has_drifts()) {
      const pl::Figure fig = ida_figure(study, sorted, top, im_label);
      const pl::Rendered out = pl::render(fig, (fs::path(dir) / "ida").string());
      for (const std::string& n : out.warnings)
        notes.push_back("ida plot: " + n);
      w.files.push_back(out.png), w.files.push_back(out.svg);
    }
    const pl::Figure fig = fragility_figure(fr, caps, top, im_label);
    if (!fig.panels.front().series.empty()) {
      const pl::Rendered out = pl::render(fig, (fs::path(dir) / "fragility").string());
      for (const std::string& n : out.warnings)
        notes.push_back("fragility plot: " + n);
      w.files.push_back(out.png), w.files.push_back(out.svg);
    } else {
      notes.push_back("no fragility curve to plot: no limit state was fitted");
    }
  } catch (const pl::Error& e) {
    w.plots_lost.push_back(std::string("plots not made: ") + e.what());
  }
}

}  // namespace

const char* limit_state_name(LimitState s) {
  switch (s) {
    case LimitState::kIO:
      return "IO";
    case LimitState::kLS:
      return "LS";
    case LimitState::kCP:
      return "CP";
    case LimitState::kCollapse:
      return "collapse";
  }
  return "?";
}

const Capacity& RecordCapacities::of(LimitState s) const {
  switch (s) {
    case LimitState::kIO:
      return io;
    case LimitState::kLS:
      return ls;
    case LimitState::kCP:
      return cp;
    case LimitState::kCollapse:
      break;
  }
  return collapse;
}

std::vector<RecordCapacities> capacities(const Study& study, const std::vector<RunRow>& rows) {
  std::vector<RecordCapacities> out(study.records().size());
  const std::optional<std::size_t> levels = level_column(study);
  for (std::size_t r = 0; r < out.size(); ++r) {
    RecordCapacities& c = out[r];
    c.levels = levels.has_value();
    double highest = 0;
    for (const RunRow* row : rows_of(rows, r)) {
      if (row->error()) {
        c.traced = false;
        continue;
      }
      highest = std::max(highest, row->im);
      if (levels) {
        const int level = row->collapse ? 4 : static_cast<int>(row->edps[*levels]);
        Capacity* reached[3] = {&c.io, &c.ls, &c.cp};
        for (int k = 0; k < 3; ++k)
          if (level >= k + 2 && !reached[k]->im) reached[k]->im = row->im;
      }
      if (row->collapse && !c.collapse.im) c.collapse.im = row->im;
    }
    c.io.highest = c.ls.highest = c.cp.highest = c.collapse.highest = highest;
  }
  return out;
}

std::vector<Fragility> fragilities(const std::vector<RecordCapacities>& caps) {
  std::vector<Fragility> out;
  for (const LimitState s : kLimitStates) {
    if (s != LimitState::kCollapse && !caps.empty() && !caps[0].levels) {
      LognormalFit none;
      none.error =
          "no performance levels: the model has no plastic hinge directions (or --edp "
          "left out hinge_level)";
      out.push_back({s, none});
      continue;
    }
    std::vector<double> observed, censored;
    for (const RecordCapacities& c : caps) {
      if (!c.traced) continue;
      const Capacity& k = c.of(s);
      if (k.im && *k.im > 0) {
        observed.push_back(*k.im);
      } else if (!k.im && k.highest > 0) {
        censored.push_back(k.highest);
      }
    }
    LognormalFit fit = fit_lognormal(observed, censored);
    if (!fit.ok() && observed.empty())
      fit.error = "no record reached it (" + std::to_string(censored.size()) +
                  " ran without reaching it up to their highest intensity)";
    out.push_back({s, fit});
  }
  return out;
}

void sort_rows(std::vector<RunRow>& rows) {
  std::sort(rows.begin(), rows.end(), [](const RunRow& a, const RunRow& b) {
    return a.record != b.record ? a.record < b.record : a.im < b.im;
  });
}

Written write_results(const Study& study, const std::vector<RunRow>& rows, const std::string& dir,
                      bool plots, std::vector<std::string>& notes) {
  namespace fs = std::filesystem;
  Written w;
  const auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
  std::error_code ec;
  for (const char* name : {"results.csv", "capacities.csv", "fragility.csv", "ida.png", "ida.svg",
                           "fragility.png", "fragility.svg"})
    fs::remove(path(name), ec);
  const auto write = [&](const char* name, const std::string& text) {
    if (auto e = cli::write_output_file(path(name), text, "--out")) {
      w.lost.push_back(*e);
    } else {
      w.files.push_back(path(name));
    }
  };
  std::vector<RunRow> sorted = rows;
  sort_rows(sorted);
  write("results.csv", results_text(study, sorted));
  const std::vector<RecordCapacities> caps = capacities(study, sorted);
  write("capacities.csv", capacities_text(study, caps));
  const std::vector<Fragility> fr = fragilities(caps);
  write("fragility.csv", fragility_text(fr));

  if (!plots) return w;
  if (!w.lost.empty()) {
    w.plots_lost.push_back(
        "plots not made: the result files they are drawn from are not all written");
    return w;
  }
  draw_plots(study, sorted, caps, fr, dir, w, notes);
  return w;
}

std::string summary_text(const Study& study, const std::vector<RunRow>& rows) {
  std::size_t collapsed = 0, diverged = 0, past_bound = 0, errors = 0;
  for (const RunRow& row : rows) {
    collapsed += row.collapse ? 1 : 0;
    diverged += row.status == "diverged" ? 1 : 0;
    past_bound += row.status == "geometry_bound" ? 1 : 0;
    errors += row.error() ? 1 : 0;
  }
  std::string s = "runs " + std::to_string(rows.size()) + " (" + std::to_string(collapsed) +
                  " collapsed, of them " + std::to_string(diverged) + " diverged and " +
                  std::to_string(past_bound) + " past the geometry bound; " +
                  std::to_string(errors) + " could not run)\n";
  const std::vector<Fragility> fr = fragilities(capacities(study, rows));
  for (const Fragility& f : fr) {
    char line[200];
    if (f.fit.ok()) {
      std::snprintf(line, sizeof line,
                    "  %-9s median %.3g g  beta %.3f   (%d records reached it, %d did not)\n",
                    limit_state_name(f.state), f.fit.median, f.fit.beta, f.fit.observed,
                    f.fit.censored);
    } else {
      std::snprintf(line, sizeof line, "  %-9s no fit: %s\n", limit_state_name(f.state),
                    f.fit.error.c_str());
    }
    s += line;
  }
  return s;
}

}  // namespace ntn::ida
