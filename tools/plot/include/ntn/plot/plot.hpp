// Plots a person can look at (DESIGN §9): a figure of one or more stacked panels,
// each with named series, log or linear axes and labelled vertical markers, rendered by gnuplot
// (Debian gnuplot-nox) to BASE.png (pngcairo) and BASE.svg. The library writes a data file and a
// gnuplot script, runs gnuplot without a shell (posix_spawn) and checks that both files appeared.
//
//   namespace pl = ntn::plot;
//   pl::Figure fig;
//   fig.title = "PSD of roof_ux";
//   pl::Panel& p = fig.panels.emplace_back();
//   p.x_label = "frequency [Hz]";
//   p.y_label = "PSD [m^2/Hz]";
//   p.y_scale = pl::Scale::kLog;
//   p.series.push_back({"roof_ux", f, psd});
//   p.markers.push_back({1.60, "mode 1 1.600 Hz"});
//   pl::render(fig, "out/psd");  // out/psd.png, out/psd.svg; throws pl::Error
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ntn::plot {

// The one exception type of the plot library; `kind` says whose problem it is.
class Error : public std::runtime_error {
 public:
  enum class Kind {
    kInput,           // bad figure or data: NaN, empty series, sizes that differ, bad range
    kGnuplotMissing,  // the gnuplot program was not found (the message names the package)
    kGnuplotFailed,   // gnuplot ran but failed or did not write a file (its stderr included)
    kIo,              // a file could not be written
  };
  Error(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

enum class Scale { kLinear, kLog };

// One line in a panel: y over x, drawn in the panel's next colour and named in its legend.
struct Series {
  Series() = default;
  Series(std::string n, std::vector<double> xs, std::vector<double> ys)
      : name(std::move(n)), x(std::move(xs)), y(std::move(ys)) {}
  std::string name;       // legend entry (printed literally: "_" and "^" are not markup); empty:
                          // none
  std::vector<double> x;  // same length as y, finite
  std::vector<double> y;  // finite; on a log axis values <= 0 are left out (a gap)
  std::string colour;     // "#rrggbb"; empty: the panel's colour for the series' place
  double width = 1.3;     // line width, in gnuplot's units (0.1 ... 10)
};

// A vertical dashed line across a panel at x, with its label written along it at the top, right
// of the line. Left out (and named in Rendered::notes) when x lies outside the panel's x extent:
// the x range, or else the points drawn (on a log axis only those above 0).
struct Marker {
  double x = 0;
  std::string label;  // e.g. "mode 1  1.600 Hz"; may be empty
};

// An axis range; unset ends are chosen by gnuplot from the data.
struct Range {
  std::optional<double> min;
  std::optional<double> max;
};

struct Panel {
  std::string title;    // above the panel; may be empty
  std::string x_label;  // with units, "time [s]"; left out on all but the bottom panel when the
                        // panels share x (Figure::shared_x)
  std::string y_label;  // with units, "roof_ux [m]"
  Scale x_scale = Scale::kLinear;
  Scale y_scale = Scale::kLinear;
  Range x_range;
  Range y_range;
  std::vector<Series> series;   // at least one
  std::vector<Marker> markers;  // any number
};

// Panels are stacked top to bottom, one above the other, with aligned left and right edges.
struct Figure {
  std::string title;          // over the whole figure; may be empty
  std::vector<Panel> panels;  // at least one
  int width = 1200;           // px, PNG and SVG
  int height = 0;             // px; 0: default_height(panels.size())
  bool shared_x = true;       // x label only under the bottom panel
};

// 0 -> 480 px for one panel, then 240 px per panel (at least 480), about 1 200 px for five.
int default_height(std::size_t panels);

// A log-y panel whose data reach more than `decades` below their peak (a spectrum down to its
// numerical floor, 1e-45, squeezes the peaks into the top of the plot): its y axis starts
// `decades` below the largest value within its x range. Leaves a panel with a y minimum set,
// a linear y axis or a narrower span as it is.
void clip_log_floor(Panel& panel, double decades = 6);

struct RenderOptions {
  // The gnuplot program: a name looked up in PATH (as execvp would) or a path with a '/'.
  std::string gnuplot = "gnuplot";
  bool png = true;  // BASE.png, gnuplot's pngcairo terminal (antialiased)
  bool svg = true;  // BASE.svg, gnuplot's svg terminal
  // Keep BASE.gp (the script) and BASE.dat (the data) next to the plots, so that
  // `gnuplot BASE.gp` makes them again (paths in the script are absolute); otherwise both are
  // removed after gnuplot has run.
  bool keep_script = false;
  // A series longer than `decimate_above` points is reduced to the minimum and maximum of each of
  // `width` equal index buckets (in their order), so the envelope a pixel column shows, peaks
  // included, is kept while the files stay small. 0: never.
  std::size_t decimate_above = 20000;
};

struct Rendered {
  std::string png;                    // path of BASE.png, empty if not asked for
  std::string svg;                    // path of BASE.svg, empty if not asked for
  std::string script;                 // BASE.gp (removed unless keep_script)
  std::string data;                   // BASE.dat (removed unless keep_script)
  std::vector<std::string> warnings;  // gnuplot's stderr lines, when it succeeded anyway
  std::vector<std::string> notes;     // markers left out (outside their panel's x extent)
};

// Checks the figure, writes BASE.dat and a script, runs gnuplot once for both terminals into
// BASE.part.png and BASE.part.svg, checks that each is whole (a PNG's IEND chunk, an SVG's
// </svg>: a full disk can cut a file while gnuplot exits 0) and renames them to BASE.png and
// BASE.svg. Whatever fails, no plot file is left at BASE (nor an earlier one). BASE may have a
// directory part, which must exist. Throws Error (kIo for a file cut short).
Rendered render(const Figure& figure, const std::string& base, const RenderOptions& options = {});

// The gnuplot script render() would write (for tests and for a look at what is drawn).
std::string script(const Figure& figure, const std::string& base, const std::string& data_file,
                   const RenderOptions& options = {});

// Full path of `program` as render() would run it: itself when it contains '/', otherwise the
// first executable PATH entry; empty when there is none (an unset or empty PATH finds nothing).
std::string find_program(const std::string& program);

}  // namespace ntn::plot
