// The modal check's figure: the spectrum it used, with the model's frequencies marked (ntn::plot).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "ntn/modecheck/modecheck.hpp"
#include "ntn/plot/plot.hpp"
#include "options.hpp"

namespace ntn::modecheck {

using detail::num;

namespace {

std::string psd_unit(const std::string& u) {
  return u.empty() ? std::string("1/Hz") : u + "^2/Hz";
}

// The lines from 0 (first line after DC, which a log axis cannot show when it is 0) to f_top.
ntn::plot::Series series(const std::string& name, const spectral::Spectrum& s, double f_top) {
  ntn::plot::Series out;
  out.name = name;
  for (std::size_t k = 1; k < s.values.size(); ++k) {
    const double f = s.grid.frequency(k);
    if (f > f_top) break;
    out.x.push_back(f);
    out.y.push_back(s.values[k]);
  }
  return out;
}

}  // namespace

std::vector<std::string> write_plot(const std::string& base, const Report& r) {
  namespace pl = ntn::plot;
  const Identification& id = r.identification;
  const double f_top = std::min(id.grid.fs / 2, 1.5 * id.f_max);

  std::string common = r.selection.channels.empty() ? "" : r.selection.channels.front().unit;
  for (const ChannelInfo& c : r.selection.channels)
    if (c.unit != common) common.clear();

  std::vector<pl::Marker> marks;
  for (const ModeCheck& c : r.modes)
    marks.push_back({c.model_hz, "mode " + std::to_string(c.number) + "  " +
                                     num(c.model_hz, "%.4f") + " Hz" + (c.pass ? "" : " (FAIL)")});

  pl::Figure fig;
  fig.title = "ntn-check-modes: " + r.model_name + ", " + r.response_file + " — " +
              (r.pass ? "PASS" : "FAIL");
  pl::Panel& top = fig.panels.emplace_back();
  top.title = id.method == "FDD"
                  ? "singular values of the " + std::to_string(id.channels.size()) + " x " +
                        std::to_string(id.channels.size()) +
                        " cross-spectral matrix, df = " + num(id.grid.df(), "%.4g") +
                        " Hz; dashed: model frequencies"
                  : "PSD of " + id.channels.front() + ", df = " + num(id.grid.df(), "%.4g") +
                        " Hz; dashed: model frequencies";
  top.x_label = "frequency [Hz]";
  top.y_label = (id.method == "FDD" ? "singular value [" : "PSD [") + psd_unit(common) + "]";
  top.y_scale = pl::Scale::kLog;
  top.x_range.min = 0.0;
  top.x_range.max = f_top;
  top.markers = marks;
  if (id.method == "FDD") {
    for (std::size_t i = 0; i < std::min<std::size_t>(2, id.singular.size()); ++i)
      top.series.push_back(series("s" + std::to_string(i + 1), id.singular[i], f_top));
  } else {
    top.series.push_back(series(id.channels.front(), id.spectrum, f_top));
  }
  if (id.method == "FDD") {
    const auto x_range = top.x_range;  // `top` dangles once the vector grows
    pl::Panel& low = fig.panels.emplace_back();
    low.title = "PSD of each channel";
    low.x_label = "frequency [Hz]";
    low.y_label = "PSD [" + psd_unit(common) + "]";
    low.y_scale = pl::Scale::kLog;
    low.x_range = x_range;
    low.markers = marks;
    for (std::size_t c = 0; c < id.auto_psd.size(); ++c)
      low.series.push_back(series(id.channels[c], id.auto_psd[c], f_top));
    fig.height = 800;  // room for the channels' legend
  }
  for (pl::Panel& panel : fig.panels)
    pl::clip_log_floor(panel);
  try {
    const pl::Rendered out = pl::render(fig, base);
    return {out.png, out.svg};
  } catch (const pl::Error& e) {
    throw PlotError(e.what());
  }
}

}  // namespace ntn::modecheck
