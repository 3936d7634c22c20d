// ntn::plot (tools/plot): what gnuplot writes is read back with independent readers — the PNG's
// IHDR for the pixel size, expat for the SVG (well-formed, and the text a person reads: titles,
// axis labels, legend entries, marker labels). Sizes are integers and texts strings: every
// comparison is exact. Needs gnuplot-nox (tools/common.sh installs it).
#include "ntn/plot/plot.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "plot_support.hpp"

namespace plot_test {

namespace pl = ntn::plot;
namespace fs = std::filesystem;
using ntn::plot::test::parse_svg;
using ntn::plot::test::png_size;
using ntn::plot::test::read_file;
using ntn::plot::test::TempDir;

constexpr double kPi = 3.14159265358979323846;

pl::Series sine(const std::string& name, double f, std::size_t n, double dt, double a = 1) {
  pl::Series s{name, {}, {}};
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    s.x.push_back(t);
    s.y.push_back(a * std::sin(2 * kPi * f * t));
  }
  return s;
}

// Two stacked panels, names with gnuplot markup characters ('_', '^', a quote).
pl::Figure two_panels() {
  pl::Figure fig;
  fig.title = "frame3d, El Centro";
  fig.width = 800;
  fig.height = 600;
  pl::Panel& a = fig.panels.emplace_back();
  a.title = "roof";
  a.x_label = "time [s]";
  a.y_label = "roof_ux [m]";
  a.series.push_back(sine("roof_ux", 1.6, 500, 0.01));
  a.series.push_back(sine("floor1_ux", 1.6, 500, 0.01, 0.4));
  pl::Panel& b = fig.panels.emplace_back();
  b.x_label = "time [s]";
  b.y_label = "pin_A1_1_V [N]";
  b.series.push_back(sine("pin's V^2", 3.2, 500, 0.01, 1e4));
  b.markers.push_back({2.0, "t_peak 2 s"});
  return fig;
}

TEST(Plot, WritesPngOfTheAskedSizeAndWellFormedSvgWithEveryLabel) {
  TempDir dir;
  const pl::Rendered r = pl::render(two_panels(), dir / "fig");
  EXPECT_EQ(r.png, dir / "fig.png");
  EXPECT_EQ(r.svg, dir / "fig.svg");
  const auto size = png_size(r.png);
  ASSERT_TRUE(size) << "no PNG signature and IHDR in " << r.png;
  EXPECT_EQ(size->width, 800u);
  EXPECT_EQ(size->height, 600u);

  const auto svg = parse_svg(r.svg);
  ASSERT_EQ(svg.error, "") << r.svg << " is not well-formed XML";
  EXPECT_EQ(svg.root, "svg");
  EXPECT_EQ(svg.width, "800");
  EXPECT_EQ(svg.height, "600");
  for (const char* text : {"frame3d, El Centro", "roof", "time [s]", "roof_ux [m]", "roof_ux",
                           "floor1_ux", "pin_A1_1_V [N]", "pin's V^2", "t_peak 2 s"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
  // The script and the data file are gone: only the two plots are left.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path()))
    ++files;
  EXPECT_EQ(files, 2u);
  EXPECT_FALSE(fs::exists(r.script));
  EXPECT_FALSE(fs::exists(r.data));
}

TEST(Plot, DefaultHeightGrowsWithThePanels) {
  TempDir dir;
  pl::Figure fig;
  for (int i = 0; i < 3; ++i) {
    pl::Panel& p = fig.panels.emplace_back();
    p.series.push_back(sine("s" + std::to_string(i), 1, 100, 0.01));
  }
  pl::RenderOptions o;
  o.svg = false;
  const pl::Rendered r = pl::render(fig, dir / "three", o);
  EXPECT_EQ(r.svg, "");
  EXPECT_FALSE(fs::exists(dir / "three.svg"));
  const auto size = png_size(r.png);
  ASSERT_TRUE(size);
  EXPECT_EQ(size->width, 1200u);
  EXPECT_EQ(size->height, static_cast<std::uint32_t>(pl::default_height(3)));
  EXPECT_EQ(pl::default_height(3), 720);
  EXPECT_EQ(pl::default_height(1), 480);
}

// A PSD: log y with a zero line at DC (left out, not an error) and marked model frequencies.
TEST(Plot, LogPsdWithMarkers) {
  TempDir dir;
  pl::Figure fig;
  fig.width = 640;
  fig.height = 480;
  pl::Panel& p = fig.panels.emplace_back();
  p.x_label = "frequency [Hz]";
  p.y_label = "PSD [m^2/Hz]";
  p.y_scale = pl::Scale::kLog;
  pl::Series s{"roof_ux", {}, {}};
  for (int k = 0; k <= 200; ++k) {
    const double f = 0.05 * k;
    s.x.push_back(f);
    const double r = f / 1.6;  // a damped mode at 1.6 Hz, zeta 2 %
    s.y.push_back(k == 0 ? 0.0 : 1e-6 / ((1 - r * r) * (1 - r * r) + (0.04 * r) * (0.04 * r)));
  }
  p.series.push_back(s);
  p.markers.push_back({1.6, "mode 1  1.600 Hz"});
  p.markers.push_back({5.1, "mode 2  5.100 Hz"});
  p.markers.push_back({50.0, "beyond the data"});  // outside the x extent: not drawn
  const pl::Rendered r = pl::render(fig, dir / "psd");
  const auto svg = parse_svg(r.svg);
  ASSERT_EQ(svg.error, "");
  EXPECT_TRUE(svg.has_text("mode 1  1.600 Hz"));
  EXPECT_TRUE(svg.has_text("mode 2  5.100 Hz"));
  EXPECT_FALSE(svg.has_text("beyond the data"));
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("marker 'beyond the data' at 50 lies outside the x extent 0.05 ... 10"),
            std::string::npos)
      << r.notes[0];
  EXPECT_TRUE(svg.has_text("PSD [m^2/Hz]"));
  const auto size = png_size(r.png);
  ASSERT_TRUE(size);
  EXPECT_EQ(size->width, 640u);
  EXPECT_EQ(size->height, 480u);
}

// Decimation keeps what a pixel column shows: a one-sample spike among 200 000 samples survives.
TEST(Plot, DecimationKeepsTheEnvelope) {
  TempDir dir;
  pl::Figure fig;
  fig.width = 400;
  pl::Panel& p = fig.panels.emplace_back();
  pl::Series s = sine("long", 0.37, 200000, 0.001);
  s.y[123457] = 5;
  p.series.push_back(s);
  pl::RenderOptions o;
  o.keep_script = true;
  o.png = false;
  const pl::Rendered r = pl::render(fig, dir / "long", o);
  ASSERT_TRUE(fs::exists(r.data));
  ASSERT_TRUE(fs::exists(r.script));
  const std::string data = read_file(r.data);
  std::size_t rows = 0;
  double y_max = -1;
  std::vector<double> xs;
  std::istringstream in(data);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    ++rows;
    xs.push_back(std::stod(line));
    y_max = std::max(y_max, std::stod(line.substr(line.find(' ') + 1)));
  }
  // At most a minimum and a maximum per bucket (width 400 px), and the first and last point.
  EXPECT_LE(rows, 2u * 400u + 2u);
  ASSERT_FALSE(xs.empty());
  // The data file prints 10 significant digits: x within 1e-9 relative.
  EXPECT_NEAR(xs.front(), s.x.front(), 1e-9);
  EXPECT_NEAR(xs.back(), s.x.back(), 1e-9 * s.x.back());
  EXPECT_TRUE(std::is_sorted(xs.begin(), xs.end()));
  EXPECT_GE(rows, 400u);  // a sine has a distinct minimum and maximum in most buckets
  EXPECT_EQ(y_max, 5.0);
  // The kept script names its files by absolute path, so it can be run again from anywhere.
  const std::string gp = read_file(r.script);
  EXPECT_NE(gp.find("'" + fs::absolute(dir / "long.dat").string() + "'"), std::string::npos);
  EXPECT_NE(gp.find("'" + fs::absolute(dir / "long.svg").string() + "'"), std::string::npos);
}

pl::Error::Kind kind_of(const pl::Figure& fig, const std::string& base, const pl::RenderOptions& o,
                        std::string* message = nullptr) {
  try {
    pl::render(fig, base, o);
  } catch (const pl::Error& e) {
    if (message != nullptr) *message = e.what();
    return e.kind();
  }
  ADD_FAILURE() << "render() did not throw";
  return pl::Error::Kind::kIo;
}

TEST(Plot, BadFiguresAreInputErrorsThatSayWhat) {
  TempDir dir;
  std::string m;
  {
    pl::Figure fig = two_panels();
    fig.panels[1].series[0].y[17] = std::nan("");
    EXPECT_EQ(kind_of(fig, dir / "x", {}, &m), pl::Error::Kind::kInput);
    EXPECT_NE(m.find("panel 2, series 'pin's V^2': y[17] is NaN"), std::string::npos) << m;
  }
  {
    pl::Figure fig = two_panels();
    fig.panels[0].series[1].x.pop_back();
    EXPECT_EQ(kind_of(fig, dir / "x", {}, &m), pl::Error::Kind::kInput);
    EXPECT_NE(m.find("499 x values but 500 y values"), std::string::npos) << m;
  }
  {
    pl::Figure fig = two_panels();
    fig.panels[0].y_scale = pl::Scale::kLog;
    for (double& y : fig.panels[0].series[0].y)
      y = -std::abs(y);
    EXPECT_EQ(kind_of(fig, dir / "x", {}, &m), pl::Error::Kind::kInput);
    EXPECT_NE(m.find("no value above 0 to draw on a log axis"), std::string::npos) << m;
  }
  {
    pl::Figure fig = two_panels();
    fig.panels[0].x_range = {3.0, 1.0};
    EXPECT_EQ(kind_of(fig, dir / "x", {}, &m), pl::Error::Kind::kInput);
    EXPECT_NE(m.find("is empty"), std::string::npos) << m;
  }
  EXPECT_EQ(kind_of(pl::Figure{}, dir / "x", {}, &m), pl::Error::Kind::kInput);
  EXPECT_NE(m.find("no panel"), std::string::npos) << m;
  EXPECT_EQ(kind_of(two_panels(), dir / "no-such-dir/x", {}, &m), pl::Error::Kind::kIo);
  EXPECT_NE(m.find("does not exist"), std::string::npos) << m;
  EXPECT_TRUE(fs::is_empty(dir.path()));  // nothing written for a figure that was refused
}

TEST(Plot, MissingGnuplotSaysWhichPackageToInstall) {
  TempDir dir;
  std::string m;
  pl::RenderOptions o;
  o.gnuplot = (dir / "no-gnuplot-here");
  EXPECT_EQ(kind_of(two_panels(), dir / "x", o, &m), pl::Error::Kind::kGnuplotMissing);
  EXPECT_NE(m.find("gnuplot-nox"), std::string::npos) << m;
  EXPECT_NE(m.find("not an executable file"), std::string::npos) << m;

  // An empty PATH finds nothing (the current directory is not searched either).
  const std::string path = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  ::setenv("PATH", "", 1);
  EXPECT_EQ(pl::find_program("gnuplot"), "");
  EXPECT_EQ(kind_of(two_panels(), dir / "x", {}, &m), pl::Error::Kind::kGnuplotMissing);
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_NE(m.find("apt-get install gnuplot-nox"), std::string::npos) << m;
  EXPECT_NE(pl::find_program("gnuplot"), "");
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// A program that runs but fails (/bin/false exits 1) is reported with its status, and no script
// or data file is left behind.
TEST(Plot, FailingGnuplotIsReported) {
  TempDir dir;
  std::string m;
  pl::RenderOptions o;
  o.gnuplot = "/bin/false";
  EXPECT_EQ(kind_of(two_panels(), dir / "x", o, &m), pl::Error::Kind::kGnuplotFailed);
  EXPECT_NE(m.find("exited with status 1"), std::string::npos) << m;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// A gnuplot that writes part of the PNG and then fails (a full disk, a Cairo error) leaves no
// partial plot behind: the failure removes both outputs.
TEST(Plot, FailingGnuplotLeavesNoPartialPlot) {
  TempDir dir;
  const std::string fake = dir / "half-gnuplot";
  {
    std::ofstream f(fake);
    f << "#!/bin/sh\n# writes the first bytes of a PNG where the script says, then fails\n"
         "out=$(sed -n \"s/^set output '\\(.*\\.png\\)'$/\\1/p\" \"$2\" | head -n 1)\n"
         "printf '\\211PNG' > \"$out\"\necho 'Cairo is unhappy' >&2\nexit 3\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  std::string m;
  pl::RenderOptions o;
  o.gnuplot = fake;
  EXPECT_EQ(kind_of(two_panels(), dir / "x", o, &m), pl::Error::Kind::kGnuplotFailed);
  EXPECT_NE(m.find("Cairo is unhappy"), std::string::npos) << m;
  EXPECT_FALSE(fs::exists(dir / "x.png")) << "a partial PNG was left";
  EXPECT_FALSE(fs::exists(dir / "x.svg"));
  fs::remove(fake);
  EXPECT_TRUE(fs::is_empty(dir.path())) << "a part file, script or data file was left";
}

// A stand-in for gnuplot at dir/NAME: writes `png` and `svg` (printf formats) where the script's
// `set output` lines say, and exits 0.
std::string fake_gnuplot(const TempDir& dir, const std::string& name, const std::string& png,
                         const std::string& svg) {
  const std::string fake = dir / name;
  {
    std::ofstream f(fake);
    f << "#!/bin/sh\n"
         "png=$(sed -n \"s/^set output '\\(.*\\.png\\)'$/\\1/p\" \"$2\")\n"
         "svg=$(sed -n \"s/^set output '\\(.*\\.svg\\)'$/\\1/p\" \"$2\")\n"
         "printf '"
      << png << "' > \"$png\"\nprintf '" << svg << "' > \"$svg\"\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  return fake;
}

constexpr const char* kWholePng = "\\211PNG\\r\\n\\032\\n\\0\\0\\0\\0IEND\\256B`\\202";
constexpr const char* kWholeSvg = "<svg>\\n</svg>\\n";

// A full disk cuts the plot while gnuplot exits 0 (pngcairo and svg do not check their writes):
// the cut file is found (no IEND chunk, no </svg>) and nothing is left, not even an earlier plot.
TEST(Plot, APlotCutShortByTheDiskIsAnErrorAndLeavesNothing) {
  for (const char* cut : {"png", "svg"}) {
    TempDir dir;
    const bool png_cut = std::string(cut) == "png";
    const std::string fake =
        fake_gnuplot(dir, "cut-gnuplot", png_cut ? "\\211PNG\\r\\n\\032\\n0123456789" : kWholePng,
                     png_cut ? kWholeSvg : "<svg>\\n<g>");
    { std::ofstream(dir / "x.png") << "an earlier plot"; }
    std::string m;
    pl::RenderOptions o;
    o.gnuplot = fake;
    EXPECT_EQ(kind_of(two_panels(), dir / "x", o, &m), pl::Error::Kind::kIo) << cut;
    EXPECT_NE(m.find(std::string("x.") + cut + ": gnuplot wrote only the first"), std::string::npos)
        << m;
    fs::remove(fake);
    EXPECT_TRUE(fs::is_empty(dir.path())) << cut << ": a plot or part file was left";
  }
  // The same fake with both files whole: the plots are renamed into place.
  TempDir dir;
  pl::RenderOptions o;
  o.gnuplot = fake_gnuplot(dir, "whole-gnuplot", kWholePng, kWholeSvg);
  const pl::Rendered r = pl::render(two_panels(), dir / "w", o);
  EXPECT_EQ(fs::file_size(r.png), 20U);
  EXPECT_TRUE(fs::exists(r.svg));
  EXPECT_FALSE(fs::exists(dir / "w.part.png"));
}

// A spectrum down to its numerical floor (1e-45 under a 1e-3 peak) gets a log axis from 6 decades
// under the peak; one within 6 decades, a linear axis or a minimum given are left alone.
TEST(Plot, LogAxesStartAFewDecadesUnderThePeak) {
  pl::Panel p;
  p.y_scale = pl::Scale::kLog;
  p.series.push_back({"psd", {1, 2, 3, 4}, {1e-45, 1e-3, 1e-9, 1e-31}});
  pl::clip_log_floor(p);
  ASSERT_TRUE(p.y_range.min);
  EXPECT_DOUBLE_EQ(*p.y_range.min, 1e-3 * 1e-6);
  p.x_range.max = 1.5;  // only the first line: nothing to clip
  p.y_range.min.reset();
  pl::clip_log_floor(p);
  EXPECT_FALSE(p.y_range.min);
  pl::Panel narrow = p, linear = p, given = p;
  narrow.x_range.max.reset();
  narrow.series[0].y = {1e-5, 1e-3, 1e-8, 1e-6};
  pl::clip_log_floor(narrow);
  EXPECT_FALSE(narrow.y_range.min);
  linear.x_range.max.reset();
  linear.y_scale = pl::Scale::kLinear;
  pl::clip_log_floor(linear);
  EXPECT_FALSE(linear.y_range.min);
  given.x_range.max.reset();
  given.y_range.min = 1e-40;
  pl::clip_log_floor(given);
  EXPECT_EQ(*given.y_range.min, 1e-40);
}

// Figures no axis or page can hold are refused before gnuplot runs: values beyond +-1e300
// ("all points y value undefined!") and more panels than the 20000 px limit at 240 px each.
TEST(Plot, UndrawableFiguresAreRefusedUpFront) {
  TempDir dir;
  std::string m;
  pl::Figure huge = two_panels();
  huge.panels[0].series[0].y[0] = 1e308;
  EXPECT_EQ(kind_of(huge, dir / "h", {}, &m), pl::Error::Kind::kInput);
  EXPECT_NE(m.find("beyond +-1e+300"), std::string::npos) << m;
  pl::Figure tall = two_panels();
  while (tall.panels.size() < 2000)
    tall.panels.push_back(tall.panels[0]);
  EXPECT_EQ(kind_of(tall, dir / "t", {}, &m), pl::Error::Kind::kInput);
  EXPECT_NE(m.find("2000 panels in 600 px: a panel needs at least 40 px"), std::string::npos) << m;
  tall.height = 0;  // the default: 240 px a panel
  EXPECT_EQ(kind_of(tall, dir / "t", {}, &m), pl::Error::Kind::kInput);
  EXPECT_NE(m.find("2000 panels need 480000 px"), std::string::npos) << m;
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace plot_test
