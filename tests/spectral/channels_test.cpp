// Inputs and errors: the CSV of ntn-run / ntn-hil / ntn-feeder and AT2 records read into
// channels; a clear error for every bad input (NaN, non-uniform time, too short a record, bad
// options), each message checked for what it must say.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "ntn/spectral/amplitude.hpp"
#include "ntn/spectral/channels.hpp"
#include "ntn/spectral/error.hpp"
#include "ntn/spectral/fdd.hpp"
#include "ntn/spectral/frf.hpp"
#include "ntn/spectral/peaks.hpp"
#include "ntn/spectral/welch.hpp"
#include "signals.hpp"

namespace ntn::spectral {
namespace channels_test {

// Runs f and returns the Error's message; fails the test when f does not throw Error.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error thrown";
  return {};
}

#define EXPECT_HAS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

class Files : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() /
        ("ntn_spectral_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const auto p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  std::filesystem::path dir_;
};

std::string fmt(const char* f, double v) {
  char b[40];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// Rows as ntn-run writes them: time "%.9g" of k / fs, values "%.17g" (so they read back exactly).
std::string run_csv(double fs, std::size_t rows, bool flags) {
  std::string s = "time[s],roof_ux[m],base_shear_x[N]";
  s += flags ? ",flags\n" : "\n";
  for (std::size_t k = 0; k < rows; ++k) {
    const double t = static_cast<double>(k) / fs;
    s += fmt("%.9g", t) + "," + fmt("%.17g", std::sin(2 * std::numbers::pi * 3 * t)) + "," +
         fmt("%.17g", 1e5 * std::cos(t));
    s += flags ? ",0\n" : "\n";
  }
  return s;
}

// ntn-run's CSV: names and units from the header, values bit for bit, fs from the time column
// to 1e-9 (the 9-digit times of 2000 rows at 1 kHz are exact decimals here).
TEST_F(Files, ReadsTheRunnerCsv) {
  const Channels c = read_channels(write("run.csv", run_csv(1000, 2000, false)));
  ASSERT_EQ(c.names, (std::vector<std::string>{"roof_ux", "base_shear_x"}));
  EXPECT_EQ(c.units, (std::vector<std::string>{"m", "N"}));
  ASSERT_EQ(c.samples(), 2000u);
  EXPECT_NEAR(c.fs, 1000, 1e-9 * 1000);
  EXPECT_EQ(c.t0, 0.0);
  EXPECT_EQ(c.channel("roof_ux")[7], std::sin(2 * std::numbers::pi * 3 * 0.007));
  EXPECT_EQ(c.index("base_shear_x[N]"), 1u);
  EXPECT_HAS(error_of([&] { (void)c.index("roof_uy"); }),
             "no channel 'roof_uy' (channels: roof_ux, base_shear_x)");
}

// ntn-hil and ntn-feeder add a "flags" column: not a channel.
TEST_F(Files, LeavesOutTheFlagsColumn) {
  const Channels c = read_csv_channels(write("hil.csv", run_csv(500, 100, true)));
  EXPECT_EQ(c.names.size(), 2u);
  EXPECT_NEAR(c.fs, 500, 1e-9 * 500);
}

// 1024 Hz for 300 s: times printed with 9 significant digits are off by up to 5e-7 s, 5e-4 of a
// step; the reader accepts them (1e-8 |t| allowance), and the least-squares step over all rows
// averages their rounding out: the rate is right to 1e-10 relative (the last row alone would
// give 1.5e-9).
TEST_F(Files, AcceptsNineDigitTimesOfALongRun) {
  const double fs = 1024;
  std::string s = "time[s],a\n";
  for (std::size_t k = 0; k < 300 * 1024; k += 1)
    s += fmt("%.9g", static_cast<double>(k) / fs) + ",1\n";
  const Channels c = read_csv_channels(write("long.csv", s));
  EXPECT_NEAR(c.fs, fs, 1e-10 * fs);
}

// A row the feeder did not receive leaves a gap: the time is not uniform, and the message says
// where and why.
TEST_F(Files, RejectsNonUniformTime) {
  std::string s = "time[s],y0,flags\n";
  for (int k = 0; k < 50; ++k) {
    if (k == 20) continue;
    s += fmt("%.9g", k * 1e-3) + ",0.5,0\n";
  }
  const std::string m = error_of([&] { (void)read_channels(write("gap.csv", s)); });
  EXPECT_HAS(m, "gap.csv:");
  EXPECT_HAS(m, "time is not uniformly spaced");
  EXPECT_HAS(m, "dropped or repeated row");
  const std::string back =
      error_of([&] { (void)read_channels(write("back.csv", "time,a\n0,1\n0.1,2\n0.05,3\n")); });
  EXPECT_HAS(back, "back.csv:4:1: error: time does not increase");
}

// NaN in a channel (a diverged run, a sensor drop-out): the file, line, column, channel and time.
TEST_F(Files, RejectsNanWithChannelAndTime) {
  const std::string m = error_of([&] {
    (void)read_channels(write("nan.csv", "time[s],a[m],b[m]\n0,1,2\n0.5,3,nan\n1,5,6\n"));
  });
  EXPECT_HAS(m, "nan.csv:3:7: error: channel 'b' is NaN at t = 0.5 s");
  const std::string inf =
      error_of([&] { (void)read_channels(write("inf.csv", "time[s],a\n0,1\n1,-inf\n2,3\n")); });
  EXPECT_HAS(inf, "channel 'a' is infinite");
}

TEST_F(Files, RejectsMalformedCsv) {
  EXPECT_HAS(error_of([&] { (void)read_channels((dir_ / "missing.csv").string()); }),
             "missing.csv: error: cannot open: No such file or directory");
  EXPECT_HAS(error_of([&] { (void)read_channels(write("empty.csv", "")); }), "the file is empty");
  EXPECT_HAS(error_of([&] { (void)read_channels(write("one.csv", "time[s],a\n0,1\n")); }),
             "at least 2 rows");
  EXPECT_HAS(error_of([&] { (void)read_channels(write("cols.csv", "time,a,b\n0,1,2\n1,2\n")); }),
             "cols.csv:3:1: error: expected 3 values, found 2");
  EXPECT_HAS(error_of([&] { (void)read_channels(write("text.csv", "time,a\n0,1\n1,x2\n")); }),
             "text.csv:3:3: error: not a number");
  EXPECT_HAS(error_of([&] { (void)read_channels(write("time.csv", "time\n0\n1\n")); }),
             "a time column and at least one channel");
  EXPECT_HAS(error_of([&] { (void)read_channels(write("ms.csv", "time[ms],a\n0,1\n1,2\n")); }),
             "ms.csv:1:1: error: the time column must be in s, not 'ms'");
}

// AT2 through tools/io: El Centro, 1559 values at 0.02 s, units g, named after the file.
TEST(At2, ReadsElCentroAsOneChannel) {
  const Channels c = read_channels(std::string(NTN_RECORDS_DIR) + "/elCentro.AT2");
  ASSERT_EQ(c.names, std::vector<std::string>{"elCentro"});
  EXPECT_EQ(c.units[0], "g");
  EXPECT_EQ(c.samples(), 1559u);
  EXPECT_DOUBLE_EQ(c.fs, 50.0);
  EXPECT_HAS(error_of([] { (void)read_channels("/nonexistent/x.at2"); }), "cannot open");
}

// The analysis functions check their input too (data from the API, not a file).
TEST(Errors, NanInDataIsNamed) {
  auto x = test::white_noise(4096, 1.0, 51);
  x[17] = std::nan("");
  WelchOptions o;
  o.segment = 256;
  EXPECT_HAS(error_of([&] { (void)welch_psd(x, 100.0, o); }), "a NaN at sample 17 (t = 0.17 s");
  EXPECT_HAS(error_of([&] { (void)amplitude_spectrum(x, 100.0); }), "a NaN at sample 17");
  const auto y = test::white_noise(4096, 1.0, 52);
  EXPECT_HAS(error_of([&] { (void)frf_h1(y, x, 100.0, o); }), "the output channel has a NaN");
  std::vector<std::vector<double>> ch{y, x};
  EXPECT_HAS(error_of([&] { (void)cross_spectral_matrix(ch, 100.0, o); }), "channel 1 has a NaN");
  x[17] = std::numeric_limits<double>::infinity();
  EXPECT_HAS(error_of([&] { (void)welch_psd(x, 100.0, o); }), "an infinite value at sample 17");
}

// 10 s at 100 Hz cannot give 0.05 Hz lines (one segment must be 20 s): the message gives both.
TEST(Errors, TooShortForTheResolution) {
  const auto x = test::white_noise(1000, 1.0, 53);
  WelchOptions o;
  o.resolution_hz = 0.05;
  const std::string m = error_of([&] { (void)welch_psd(x, 100.0, o); });
  EXPECT_HAS(m, "too short for the requested resolution");
  EXPECT_HAS(m, "1000 samples (10 s at 100 Hz)");
  EXPECT_HAS(m, "2000 samples (20 s) is needed for 0.05 Hz resolution");
}

TEST(Errors, BadOptionsAndShapes) {
  const auto x = test::white_noise(1000, 1.0, 54);
  WelchOptions o;
  o.segment = 100;
  EXPECT_HAS(error_of([&] { (void)Welch(0.0, o); }), "sample rate must be positive");
  EXPECT_HAS(error_of([&] { (void)Welch(100.0, WelchOptions{}); }),
             "give a segment length or a resolution");
  WelchOptions fine;
  fine.resolution_hz = 1e-300;
  EXPECT_HAS(error_of([&] { (void)Welch(100.0, fine); }), "more than 10^9 samples per segment");
  WelchOptions bad = o;
  bad.overlap = 1.0;
  EXPECT_HAS(error_of([&] { (void)Welch(100.0, bad); }), "overlap must be in [0, 1)");
  bad = o;
  bad.segment = 1;
  EXPECT_HAS(error_of([&] { (void)Welch(100.0, bad); }), "at least 2 samples");
  bad = o;
  bad.nfft = 50;
  EXPECT_HAS(error_of([&] { (void)Welch(100.0, bad); }), "nfft (50) is shorter than the segment");
  const std::vector<double> shorter(x.begin(), x.begin() + 900);
  EXPECT_HAS(error_of([&] { (void)cross_spectral_density(x, shorter, 100.0, o); }),
             "differ in length (1000 and 900");
  EXPECT_HAS(error_of([&] { (void)frf_h1(x, shorter, 100.0, o); }), "differ in length");
  std::vector<std::vector<double>> ch{x, shorter};
  EXPECT_HAS(error_of([&] { (void)cross_spectral_matrix(ch, 100.0, o); }),
             "channel 1 has 900 samples, channel 0 has 1000");
  EXPECT_HAS(error_of([&] { (void)amplitude_spectrum(std::vector<double>{1.0}, 100.0); }),
             "at least 2 samples");
  const Spectrum p = welch_psd(x, 100.0, o);
  EXPECT_HAS(error_of([&] { (void)find_peaks(p, {.f_min = 30, .f_max = 20}); }),
             "lower edge is above its upper edge");
  EXPECT_HAS(error_of([&] { (void)find_peaks(p, {.f_min = 60, .f_max = 70}); }),
             "no spectral line in the band");
}

}  // namespace channels_test
}  // namespace ntn::spectral
