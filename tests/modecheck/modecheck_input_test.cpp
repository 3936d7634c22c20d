// Bad input to ntn-check-modes: exit code 2 and a message that says what is wrong and where, for
// each case of tools/modecheck/README.md ("Exit codes"). The program runs as a subprocess; the
// records are small CSVs written here with the test model's channel names
// (tests/modecheck/frame3d_sensors.toml), so nothing is simulated. Too short a record for the
// resolution is checked in modecheck_e2e_test against the real response.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "ntn/modecheck/modecheck.hpp"
#include "test_files.hpp"

namespace modecheck_input_test {

namespace mc = ntn::modecheck;

class ModeCheckInput : public ::testing::Test {
 protected:
  ModeCheckInput() : dir_("modecheck_input") {}

  // 10 s at `fs` (100 Hz) of two tones in the test model's channels; `nan_row` (1-based data row)
  // gets a NaN in roof_uy.
  std::string record(const std::string& name, int nan_row = 0, int fs = 100) {
    std::string s = "time[s],roof_ux[m],roof_uy[m]\n";
    for (int k = 0; k < 10 * fs; ++k) {
      const double t = k / static_cast<double>(fs);
      char row[128];
      std::snprintf(row, sizeof row, "%.9g,%.17g,%.17g\n", t, std::sin(2 * M_PI * 1.7388 * t),
                    std::sin(2 * M_PI * 1.6046 * t));
      s += row;
      if (k + 1 == nan_row) {
        s.resize(s.rfind(',') + 1);
        s += "nan\n";
      }
    }
    const std::string path = dir_ / name;
    ntn_test::write_file(path, s);
    return path;
  }

  // `seconds` at `fs` of the given channels of the test model (name, x(t)), as ntn-run writes.
  std::string channels(const std::string& name,
                       const std::vector<std::pair<std::string, double (*)(double)>>& ch,
                       int seconds = 40, int fs = 100) {
    std::string s = "time[s]";
    for (const auto& c : ch)
      s += "," + c.first + "[m]";
    s += "\n";
    for (int k = 0; k < seconds * fs; ++k) {
      const double t = k / static_cast<double>(fs);
      char v[48];
      std::snprintf(v, sizeof v, "%.9g", t);
      s += v;
      for (const auto& c : ch) {
        std::snprintf(v, sizeof v, ",%.17g", c.second(t));
        s += v;
      }
      s += "\n";
    }
    const std::string path = dir_ / name;
    ntn_test::write_file(path, s);
    return path;
  }

  ntn_test::ProgramResult run(const std::string& args) {
    return ntn_test::run_program(ntn_test::quoted(NTN_CHECK_MODES) + " " + args);
  }

  static std::string model() { return NTN_MODECHECK_MODEL; }

  ntn_test::TempDir dir_;
};

TEST_F(ModeCheckInput, MissingResponseFile) {
  const std::string missing = dir_ / "no_such.csv";
  const auto p = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(missing));
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("error: cannot read the response file '" + missing + "': no such file"),
            std::string::npos)
      << p.output;
}

TEST_F(ModeCheckInput, MissingModelFile) {
  const std::string missing = dir_ / "no_such.toml";
  const auto p = run(ntn_test::quoted(missing) + " " + ntn_test::quoted(record("r.csv")));
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("error: cannot read the model file '" + missing + "': no such file"),
            std::string::npos)
      << p.output;
}

TEST_F(ModeCheckInput, ADirectoryIsNotAFile) {
  const auto p = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(dir_.str()));
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("': it is a directory"), std::string::npos) << p.output;
}

// The model compiler's own diagnostic, file:line:column, passed through.
TEST_F(ModeCheckInput, BadModelGivesTheCompilersFileLineColumn) {
  std::string text = ntn_test::read_file(model());
  const auto at = text.find("E = 210e9");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 9, "E = -210e9");
  const std::string bad = dir_ / "bad_model.toml";
  ntn_test::write_file(bad, text);
  // The line of E in the file, 1-based.
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  const auto p = run(ntn_test::quoted(bad) + " " + ntn_test::quoted(record("r.csv")));
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find(bad + ":" + std::to_string(line) + ":"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("error: key 'materials[0].E'"), std::string::npos) << p.output;
}

// NaN in the data: the reader names the file line (the header is line 1, so data row 250 is
// line 251), the channel and the time.
TEST_F(ModeCheckInput, NanNamesTheChannelAndRow) {
  const std::string path = record("nan.csv", 250);
  const auto p = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(path));
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find(path + ":251:"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("channel 'roof_uy' is NaN at t = 2.49 s"), std::string::npos) << p.output;
}

TEST_F(ModeCheckInput, InfinityNamesTheChannelAndRow) {
  std::string text = ntn_test::read_file(record("r.csv"));
  const auto line5 = [&text] {
    std::size_t at = 0;
    for (int k = 0; k < 5; ++k)
      at = text.find('\n', at) + 1;
    return at;  // start of file line 6 (data row 5)
  }();
  const auto comma = text.find(',', line5);
  const auto comma2 = text.find(',', comma + 1);
  text.replace(comma + 1, comma2 - comma - 1, "inf");
  const std::string path = dir_ / "inf.csv";
  ntn_test::write_file(path, text);
  const auto p = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(path));
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find(path + ":6:"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("channel 'roof_ux' is infinite at t = 0.04 s"), std::string::npos)
      << p.output;
}

TEST_F(ModeCheckInput, UnknownChannelListsTheFilesChannels) {
  const std::string path = record("r.csv");
  const auto p =
      run(ntn_test::quoted(model()) + " " + ntn_test::quoted(path) + " --channels roof_ux,roof_z");
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("error: unknown channel 'roof_z': " + path +
                          " has the channels roof_ux, roof_uy"),
            std::string::npos)
      << p.output;
}

// 10 s at 100 Hz: the default resolution (1 % x 1.6 Hz / 2 = 0.008 Hz, 125 s) does not fit, so the
// whole record is one segment, with a note; an explicit 0.05 Hz needs 20 s: exit 2.
TEST_F(ModeCheckInput, TooShortForAnExplicitResolution) {
  const std::string path = record("r.csv");
  const auto p =
      run(ntn_test::quoted(model()) + " " + ntn_test::quoted(path) + " --resolution 0.05");
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("too short for a resolution of 0.05 Hz: it is 10 s (1000 samples at "
                          "100 Hz), and one segment of 20 s (2000 samples) is needed"),
            std::string::npos)
      << p.output;
}

// A mode above the record's Nyquist frequency cannot be checked: the frame's mode 7 (5.9 Hz) is
// above the 5 Hz of a 10 Hz record.
TEST_F(ModeCheckInput, ModesAboveNyquist) {
  const auto p =
      run(ntn_test::quoted(model()) + " " + ntn_test::quoted(record("r10.csv", 0, 10)) + " -n 7");
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("model mode 7 ("), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("is not below the record's Nyquist frequency 5 Hz"), std::string::npos)
      << p.output;
}

TEST_F(ModeCheckInput, BadOptions) {
  const std::string args = ntn_test::quoted(model()) + " " + ntn_test::quoted(record("r.csv"));
  auto p = run(args + " --window triangle");
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("triangle"), std::string::npos) << p.output;
  p = run(args + " --direction w");
  EXPECT_EQ(p.exit_code, 2);
  p = run(args + " --tolerance -1");
  EXPECT_EQ(p.exit_code, 2);
}

// Regression: a dead sensor (0.01 m for 40 s) "identified" both modes from its rounding
// residue (PSD ~1e-63) and passed. A constant channel is bad input, named, with its value.
TEST_F(ModeCheckInput, AConstantChannelIsADeadSensor) {
  const std::string path = channels("dead.csv", {{"roof_ux", [](double) { return 0.01; }}});
  const auto p = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(path) + " -n 2");
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_NE(p.output.find("ntn-check-modes: error: channel 'roof_ux' is constant (a dead "
                          "sensor?): every sample is 0.01 m"),
            std::string::npos)
      << p.output;
  // All zeros too (no value to go wrong on).
  const std::string zeros = channels("zeros.csv", {{"roof_ux", [](double) { return 0.0; }},
                                                   {"roof_uy", [](double) { return 0.0; }}});
  const auto z = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(zeros) + " -n 2");
  EXPECT_EQ(z.exit_code, 2) << z.output;
  EXPECT_NE(z.output.find("channel 'roof_ux' is constant (a dead sensor?): every sample is 0 m"),
            std::string::npos)
      << z.output;
}

// A dead channel beside a live one: the check refuses it by name (not the live one); without it
// (--channels) the live channel's PSD finds the mode it carries.
TEST_F(ModeCheckInput, AConstantChannelBesideALiveOne) {
  const std::string path =
      channels("dead_and_live.csv",
               {{"roof_ux", [](double) { return 0.01; }},
                {"roof_uy", [](double t) { return 1e-3 * std::sin(2 * M_PI * 1.6046 * t); }}});
  const std::string args = ntn_test::quoted(model()) + " " + ntn_test::quoted(path);
  const auto p = run(args + " -n 1");
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_NE(p.output.find("channel 'roof_ux' is constant (a dead sensor?): every sample is 0.01 m"),
            std::string::npos)
      << p.output;
  EXPECT_EQ(p.output.find("'roof_uy' is constant"), std::string::npos) << p.output;
  const auto live = run(args + " -n 1 --channels roof_uy");
  EXPECT_EQ(live.exit_code, 0) << live.output;
  EXPECT_NE(live.output.find("PASS: 1 of 1 modes"), std::string::npos) << live.output;
}

// NaN (and infinite) option values are refused with the option named: CLI11's range checks let
// NaN through (every comparison is false), so the library's validate() refuses them, and
// `--min-prominence nan` no longer passes every local maximum.
TEST_F(ModeCheckInput, NanOptionsAreRefused) {
  const std::string args = ntn_test::quoted(model()) + " " + ntn_test::quoted(record("r.csv"));
  for (const char* option :
       {"--tolerance", "--min-mac", "--min-prominence", "--band", "--min-level", "--min-mass",
        "--min-visibility", "--overlap", "--resolution"}) {
    for (const char* value : {"nan", "inf"}) {
      SCOPED_TRACE(std::string(option) + " " + value);
      const auto p = run(args + " " + option + " " + value);
      EXPECT_EQ(p.exit_code, 2) << p.output;
      EXPECT_NE(p.output.find(option), std::string::npos) << p.output;
    }
  }
  // The command line refuses it first (ntn::cli validators: the range with %g numbers, never
  // DBL_MAX in full); the library's own message is LibraryRefusesNanOptions below.
  const auto p = run(args + " --min-prominence nan");
  EXPECT_NE(p.output.find("--min-prominence: wants a number in [1, 1e+12], got 'nan'"),
            std::string::npos)
      << p.output;
}

// The same through the library (programmatic use): check_files refuses NaN options.
TEST_F(ModeCheckInput, LibraryRefusesNanOptions) {
  const std::string path = record("r.csv");
  const double nan = std::nan("");
  for (double mc::Options::*field :
       {&mc::Options::tolerance, &mc::Options::min_mac, &mc::Options::min_prominence,
        &mc::Options::search_band, &mc::Options::min_level, &mc::Options::resolution_hz,
        &mc::Options::overlap, &mc::Options::min_mass_fraction, &mc::Options::min_visibility}) {
    mc::Options o;
    o.*field = nan;
    EXPECT_THROW((void)mc::check_files(model(), path, o), mc::InputError);
  }
}

// --plot into a directory that does not exist: the plot library's message, exit 2 (after the
// table, which is still printed).
TEST_F(ModeCheckInput, PlotIntoAMissingDirectory) {
  const std::string base = dir_ / "no_such_dir" + "/plot";
  const auto p = run(ntn_test::quoted(model()) + " " + ntn_test::quoted(record("r.csv")) +
                     " --plot " + ntn_test::quoted(base));
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_NE(p.output.find("ntn-check-modes: error: the plot: "), std::string::npos) << p.output;
  EXPECT_NE(p.output.find(" mode   model Hz"), std::string::npos) << p.output;
}

// A PEER AT2 record reads as one channel named after the file, which maps to no output of the
// model: its PSD, frequencies only, no visibility and no MAC (the verdict depends on the record,
// here a ground motion, not a response, so only the path is checked).
TEST_F(ModeCheckInput, AnAt2RecordIsOneUnmappedChannel) {
  const mc::Report r = mc::check_files(model(), NTN_RECORDS_DIR "/elCentro.AT2", mc::Options{});
  EXPECT_EQ(r.identification.method, "PSD");
  ASSERT_EQ(r.selection.channels.size(), 1u);
  EXPECT_EQ(r.selection.channels[0].name, "elCentro");
  EXPECT_FALSE(r.selection.shapes);
  EXPECT_DOUBLE_EQ(r.fs, 50.0);
  for (const mc::ModeCheck& c : r.modes)
    EXPECT_FALSE(c.mac.has_value());
  EXPECT_TRUE(r.model.visibility.empty());
}

// The same cases through the library: InputError, nothing else.
TEST_F(ModeCheckInput, LibraryThrowsInputError) {
  const std::string path = record("r.csv");
  mc::Options o;
  EXPECT_THROW((void)mc::check_files(dir_ / "none.toml", path, o), mc::InputError);
  EXPECT_THROW((void)mc::check_files(model(), dir_ / "none.csv", o), mc::InputError);
  EXPECT_THROW((void)mc::check_files(model(), record("nan.csv", 3), o), mc::InputError);
  o.channels = {"nope"};
  EXPECT_THROW((void)mc::check_files(model(), path, o), mc::InputError);
  o.channels = {};
  o.resolution_hz = 0.01;
  EXPECT_THROW((void)mc::check_files(model(), path, o), mc::InputError);
}

}  // namespace modecheck_input_test
