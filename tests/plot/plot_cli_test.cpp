// ntn-plot end to end: histories and spectra from CSV files the test writes (and, when the runner
// is built, from a real ntn-run-frame3d run with the model's hinge force channels), exit codes
// and messages for bad input and a missing gnuplot. Exact comparisons: exit codes, pixel sizes,
// label strings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ntn/plot/plot.hpp"
#include "plot_support.hpp"

namespace plot_cli_test {

namespace fs = std::filesystem;
using ntn::plot::test::parse_svg;
using ntn::plot::test::png_size;
using ntn::plot::test::run;
using ntn::plot::test::TempDir;
using ntn::plot::test::write_file;

const std::string kCli = NTN_PLOT_CLI;

// 0 ... 0.99 s at 100 Hz, the runner's header style, a flags column like ntn-hil's.
std::string history_csv(const std::string& bad_row = {}) {
  std::string csv = "time[s],roof_ux[m],pin_A1_1_V[N],pin_A1_1_N[N],flags\n";
  for (int i = 0; i < 100; ++i) {
    const double t = 0.01 * i;
    csv += std::to_string(t) + "," + std::to_string(0.01 * t) + "," + std::to_string(100 * t) +
           "," + std::to_string(-50 * t) + ",0\n";
    if (i == 40 && !bad_row.empty()) csv += bad_row + "\n";
  }
  return csv;
}

TEST(PlotCli, HistoryOnePanelPerGroup) {
  TempDir dir;
  write_file(dir / "run.csv", history_csv());
  const auto r = run(kCli + " history " + (dir / "run.csv") +
                         " --channels roof_ux,pin_A1_1_V+pin_A1_1_N --out " + (dir / "h"),
                     dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, (dir / "h.png") + "\n" + (dir / "h.svg") + "\n");
  const auto size = png_size(dir / "h.png");
  ASSERT_TRUE(size);
  EXPECT_EQ(size->width, 1200u);
  EXPECT_EQ(size->height, static_cast<std::uint32_t>(ntn::plot::default_height(2)));
  const auto svg = parse_svg(dir / "h.svg");
  ASSERT_EQ(svg.error, "");
  for (const char* text : {"run.csv", "time [s]", "roof_ux [m]", "pin_A1_1_V, pin_A1_1_N [N]",
                           "pin_A1_1_V", "pin_A1_1_N"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
  EXPECT_FALSE(svg.has_text("flags"));
}

TEST(PlotCli, HistoryDefaultsToEveryChannelAndTakesASize) {
  TempDir dir;
  write_file(dir / "run.csv", history_csv());
  const auto r = run(kCli + " history " + (dir / "run.csv") + " --size 900x700 --title 'a run'" +
                         " --from 0.2 --to 0.5 --no-svg --out " + (dir / "all"),
                     dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "all.svg"));
  const auto size = png_size(dir / "all.png");
  ASSERT_TRUE(size);
  EXPECT_EQ(size->width, 900u);
  EXPECT_EQ(size->height, 700u);
  const auto svg_run =
      run(kCli + " history " + (dir / "run.csv") + " --no-png --out " + (dir / "all"), dir);
  ASSERT_EQ(svg_run.status, 0) << svg_run.err;
  const auto svg = parse_svg(dir / "all.svg");
  ASSERT_EQ(svg.error, "");
  for (const char* text : {"roof_ux [m]", "pin_A1_1_V [N]", "pin_A1_1_N [N]"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
}

// Exit 2 with a message that names the problem, and no plot written.
void expect_bad_input(const TempDir& dir, const std::string& args, const std::string& message) {
  const auto r = run(kCli + " " + args + " --out " + (dir / "bad"), dir);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos) << args << "\nstderr: " << r.err;
  EXPECT_FALSE(fs::exists(dir / "bad.png")) << args;
}

TEST(PlotCli, BadInputExitsTwoWithAMessage) {
  TempDir dir;
  write_file(dir / "run.csv", history_csv());
  write_file(dir / "nan.csv", history_csv("0.405,1e-3,nan,0,0"));
  write_file(dir / "short.csv", history_csv("0.41,1e-3,1,0"));
  write_file(dir / "back.csv", history_csv("0.1,1e-3,1,0,0"));
  write_file(dir / "text.csv", history_csv("0.405,1e-3,abc,0,0"));
  write_file(dir / "empty.csv", "");
  expect_bad_input(dir, "history " + (dir / "run.csv") + " --channels roof_ux,nope",
                   "no channel 'nope' (channels: roof_ux, pin_A1_1_V, pin_A1_1_N)");
  expect_bad_input(dir, "history " + (dir / "missing.csv"),
                   "missing.csv: error: cannot open: No such file");
  expect_bad_input(dir, "history " + (dir / "empty.csv"), "the file is empty");
  expect_bad_input(dir, "history " + (dir / "nan.csv"),
                   "nan.csv:43:1: error: channel 'pin_A1_1_V' is NaN at time = 0.405 s");
  expect_bad_input(dir, "history " + (dir / "short.csv"), "short.csv:43:1: error: expected 5");
  expect_bad_input(dir, "history " + (dir / "back.csv"), "'time' does not increase");
  expect_bad_input(dir, "history " + (dir / "text.csv"),
                   "'abc' in column 'pin_A1_1_V[N]' is not a number");
  expect_bad_input(dir, "history " + (dir / "run.csv") + " --channels roof_ux+pin_A1_1_V",
                   "one panel mixes units: roof_ux [m] and pin_A1_1_V [N]");
  expect_bad_input(dir, "history " + (dir / "run.csv") + " --from 5", "fewer than 2 rows");
  expect_bad_input(dir, "history " + (dir / "run.csv") + " --size 12", "--size wants");
  expect_bad_input(dir, "psd " + (dir / "run.csv"), "the first column must be in Hz, not 's'");
  expect_bad_input(dir, "history " + (dir / "run.csv") + " --model /nonexistent.toml --kind drift",
                   "the model does not load");
  expect_bad_input(dir, "history " + (dir / "run.csv") + " --bogus", "bogus");
  // An output directory that does not exist.
  const auto r = run(kCli + " history " + (dir / "run.csv") + " --out " + (dir / "no/such/x"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
}

TEST(PlotCli, PsdWithMarks) {
  TempDir dir;
  std::string csv = "frequency[Hz],roof_ux[m^2/Hz],floor1_ux[m^2/Hz]\n";
  for (int k = 0; k <= 100; ++k) {
    const double f = 0.1 * k;
    const double r = f / 1.6;
    const double h = 1 / ((1 - r * r) * (1 - r * r) + (0.04 * r) * (0.04 * r));
    char row[96];
    std::snprintf(row, sizeof row, "%.9g,%.9g,%.9g\n", f, 1e-6 * h, 3e-7 * h);
    csv += row;
  }
  write_file(dir / "spectrum.csv", csv);
  const auto r = run(kCli + " psd " + (dir / "spectrum.csv") +
                         " --marks '1.6,mode 2=5.25,20' --out " + (dir / "psd"),
                     dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("marker '20 Hz' at 20 lies outside the x extent 0 ... 10: not drawn"),
            std::string::npos)
      << r.err;
  const auto svg = parse_svg(dir / "psd.svg");
  ASSERT_EQ(svg.error, "");
  for (const char* text : {"frequency [Hz]", "PSD [m^2/Hz]", "roof_ux [m^2/Hz]",
                           "floor1_ux [m^2/Hz]", "1.6 Hz", "mode 2  5.25 Hz"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
  EXPECT_FALSE(svg.has_text("20 Hz"));
  ASSERT_TRUE(png_size(dir / "psd.png"));

  expect_bad_input(dir, "psd " + (dir / "spectrum.csv") + " --marks 1.6,x", "'x' is not a number");
  expect_bad_input(dir, "psd " + (dir / "spectrum.csv") + " --columns nope", "no channel 'nope'");
}

TEST(PlotCli, MissingGnuplotExitsThreeAndNamesThePackage) {
  TempDir dir;
  write_file(dir / "run.csv", history_csv());
  for (const std::string& how :
       {"/usr/bin/env PATH= " + kCli + " history", kCli + " history --gnuplot /nonexistent/gp"}) {
    const auto r = run(how + " " + (dir / "run.csv") + " --out " + (dir / "x"), dir);
    EXPECT_EQ(r.status, 3) << how << "\n" << r.err;
    EXPECT_NE(r.err.find("gnuplot not found"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("apt-get install gnuplot-nox"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.png"));
  }
}

#if defined(NTN_RUNNER)
// The README's example: a frame3d run on El Centro (2 s of it), then its roof displacement,
// drifts and the model's hinge force channels (kind hinge_force in config/frame3d.toml).
TEST(PlotCli, Frame3dHingeForces) {
  TempDir dir;
  const auto sim = run(std::string(NTN_RUNNER) + " -q --input ag_x=" + NTN_CONFIG_DIR +
                           "/ground-motions/elCentro.AT2 --duration 2 --out " + (dir / "x.csv"),
                       dir);
  ASSERT_EQ(sim.status, 0) << sim.err;
  const auto r =
      run(kCli + " history " + (dir / "x.csv") + " --channels roof_ux,drift1_x+drift2_x --model " +
              NTN_CONFIG_DIR + "/frame3d.toml --kind hinge_force --out " + (dir / "frame3d"),
          dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto size = png_size(dir / "frame3d.png");
  ASSERT_TRUE(size);
  EXPECT_EQ(size->height, static_cast<std::uint32_t>(ntn::plot::default_height(4)));
  const auto svg = parse_svg(dir / "frame3d.svg");
  ASSERT_EQ(svg.error, "");
  for (const char* text :
       {"roof_ux [m]", "drift1_x", "drift2_x", "pin_A1_1_V [N]", "pin_A1_1_N [N]"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
  // The ground motion itself, from the AT2 file.
  const auto at2 = run(kCli + " history " + NTN_CONFIG_DIR + "/ground-motions/elCentro.AT2" +
                           " --no-svg --out " + (dir / "ag"),
                       dir);
  EXPECT_EQ(at2.status, 0) << at2.err;
  EXPECT_TRUE(png_size(dir / "ag.png"));
}
#endif

}  // namespace plot_cli_test

namespace plot_cli_test {

// A 3 m column whose base is a hinge to the ground with `ry` as its bending direction.
std::string column_model(const std::string& ry) {
  return R"([model]
name = "m"
[[materials]]
id = "S"
E = 210e9
nu = 0.3
rho = 7850
[[sections]]
id = "H"
A = 1e-2
Iy = 1e-4
Iz = 5e-5
J = 1e-6
[[nodes]]
id = 1
xyz = [0, 0, 0]
[[nodes]]
id = 2
xyz = [0, 0, 3]
[[members]]
id = "C"
nodes = [1, 2]
material = "S"
section = "H"
[[hinges]]
id = "base"
nodes = [1, "ground"]
ry = )" + ry +
         "\n";
}

// ntn-plot hysteresis of dir/run.csv (base_ry, base_My) with dir/m.toml's hinge base, ry, into
// dir/loops.svg and .png.
ntn::plot::test::Run plot_loops(const TempDir& dir) {
  return run(kCli + " hysteresis " + (dir / "run.csv") + " -x base_ry -y base_My --model " +
                 (dir / "m.toml") + " --hinge base --direction ry --out " + (dir / "loops"),
             dir);
}

// A plastic hinge direction's loops: the force over the deformation, the law's
// bilinear envelope and its IO, LS, CP limits marked, from a model with such a hinge (a column
// whose base is a plastic hinge to the ground, ry).
TEST(PlotCli, HysteresisLoopsWithEnvelopeAndLimits) {
  TempDir dir;
  write_file(dir / "m.toml",
             column_model("{ plastic = 1e8, yield = 1e5, hardening = 0.05, io = 0.002, ls = "
                          "0.005, cp = 0.008 }"));
  // Two cycles of a bilinear loop, +-6 mrad, yield rotation 1 mrad.
  std::string csv = "time[s],base_ry[rad],base_My[N m]\n";
  double dp = 0;
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.01 * i;
    const double d = 0.006 * std::sin(2 * 3.141592653589793 * t / 2.0);
    const double H = 0.05 * 1e8 / 0.95;
    const double xi = 1e8 * (d - dp) - H * dp;
    if (xi > 1e5) dp += (xi - 1e5) / (1e8 + H);
    if (xi < -1e5) dp += (xi + 1e5) / (1e8 + H);
    char row[96];
    std::snprintf(row, sizeof row, "%.6f,%.9g,%.9g\n", t, d, 1e8 * (d - dp));
    csv += row;
  }
  write_file(dir / "run.csv", csv);
  const auto r = plot_loops(dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto svg = parse_svg(dir / "loops.svg");
  ASSERT_EQ(svg.error, "");
  for (const char* text : {"base_ry [rad]", "base_My [N m]", "base_My over base_ry",
                           "envelope (bilinear, b = 0.05)", "IO", "LS", "CP"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
  ASSERT_TRUE(png_size(dir / "loops.png"));
  // The frame is the loops' (+-6 mrad, x 1.15): CP (8 mrad plastic, 9.42 mrad in all) lies
  // beyond it and is marked at the edge with its value, not drawn by an axis widened for it; no
  // marker is left out.
  EXPECT_EQ(r.err.find("not drawn"), std::string::npos) << r.err;
  EXPECT_TRUE(svg.has_text("beyond: CP 0.00942")) << "CP is not marked at the edge";
  const auto exact = [&svg](const std::string& s) {  // a tick label, blanks aside
    for (std::string t : svg.texts) {
      t.erase(0, t.find_first_not_of(' '));
      if (t == s) return true;
    }
    return false;
  };
  EXPECT_TRUE(exact("0.006")) << "no tick at the loops' extent";
  EXPECT_FALSE(exact("0.01")) << "the axis reaches past the loops to the CP limit";

  expect_bad_input(dir,
                   "hysteresis " + (dir / "run.csv") + " -x base_ry -y base_My --model " +
                       (dir / "m.toml") + " --hinge base --direction rx",
                   "--direction: rx of hinge base is not plastic");
  expect_bad_input(dir,
                   "hysteresis " + (dir / "run.csv") + " -x base_ry -y base_My --model " +
                       (dir / "m.toml") + " --hinge nope --direction ry",
                   "has no hinge 'nope'");
}

// A backbone direction: the envelope A-B-C-D-E of each sense (and no strength past E) with the
// IO/LS/CP limits where its plastic deformation d - f / k reaches them.
TEST(PlotCli, HysteresisWithABackbone) {
  TempDir dir;
  write_file(dir / "m.toml",
             column_model("{ backbone = [[0.001, 1e5], [0.01, 1.2e5], [0.012, 2e4], [0.02, 2e4]], "
                          "rule = \"peak_oriented\", io = 0.002, ls = 0.005, cp = 0.008 }"));
  std::string csv = "time[s],base_ry[rad],base_My[N m]\n";
  for (int i = 0; i <= 40; ++i) {
    const double d = 0.0005 * (i % 20 < 10 ? i % 20 : 20 - i % 20);  // small elastic cycles
    char row[96];
    std::snprintf(row, sizeof row, "%.6f,%.9g,%.9g\n", 0.01 * i, d, 1e8 * d);
    csv += row;
  }
  write_file(dir / "run.csv", csv);
  const auto r = plot_loops(dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto svg = parse_svg(dir / "loops.svg");
  ASSERT_EQ(svg.error, "");
  for (const char* text : {"backbone (peak_oriented)", "IO", "LS", "CP"})
    EXPECT_TRUE(svg.has_text(text)) << "the SVG lacks '" << text << "'";
  EXPECT_EQ(r.err.find("not drawn"), std::string::npos) << r.err;
}

}  // namespace plot_cli_test
