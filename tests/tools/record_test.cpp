// Record readers (tools/io): both AT2 header styles of the shipped records, CR/LF mixes,
// Fortran fields that run together, CSV, and an error with file:line:column for each bad file.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "record.hpp"
#include "table.hpp"

namespace {

const std::string kRecords = NTN_RECORDS_DIR;

// Files written by the tests, removed when the test program ends.
struct TempFiles {
  std::vector<std::filesystem::path> paths;
  ~TempFiles() {
    std::error_code ec;
    for (const auto& p : paths)
      std::filesystem::remove(p, ec);
  }
};
TempFiles temp_files;

std::string write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("ntn_record_test_" + name);
  std::ofstream(path, std::ios::binary) << text;
  temp_files.paths.push_back(path);
  return path.string();
}

// El Centro (Peknold version): free-text header, "NPTS=  1559, DT= .02000 SEC", 8F10.5 values.
// First and last values as printed in the file.
TEST(At2, ReadsElCentro) {
  const auto r = ntn::io::read_at2(kRecords + "/elCentro.AT2");
  ASSERT_FALSE(r.error) << r.error->format();
  EXPECT_EQ(r.record->values.size(), 1559U);
  EXPECT_DOUBLE_EQ(r.record->dt, 0.02);
  EXPECT_EQ(r.record->units, "g");
  EXPECT_DOUBLE_EQ(r.record->values.front(), 0.00630);
  EXPECT_DOUBLE_EQ(r.record->values.back(), 0.0);
  EXPECT_NEAR(r.record->peak_abs(), 0.3188, 5e-5);  // the N-S component's PGA, 0.319 g
}

// Northridge Arleta 360 (PEER NGA style, \r\r\n line ends, E-format values without a leading 0).
TEST(At2, ReadsArletaWithCarriageReturns) {
  const auto r = ntn::io::read_at2(kRecords + "/ARL360.AT2");
  ASSERT_FALSE(r.error) << r.error->format();
  EXPECT_EQ(r.record->values.size(), 2000U);
  EXPECT_DOUBLE_EQ(r.record->dt, 0.02);
  EXPECT_EQ(r.record->units, "g");
  EXPECT_DOUBLE_EQ(r.record->values.front(), 0.1297983E-02);
  EXPECT_DOUBLE_EQ(r.record->values[4], 0.1469841E-02);
}

// The older PEER style puts the numbers first: "5  0.01  NPTS, DT". Fixed-width fields may
// touch ("-0.12345-0.23456") and Fortran writes D exponents.
TEST(At2, ReadsOlderHeaderAndTouchingFields) {
  const std::string path = write_temp("old.AT2",
                                      "title\nevent\nUNITS OF G\n    5    0.0100    NPTS, DT\n"
                                      "  0.10000-0.20000  0.3D-01\r\n  4.0E-1\n-0.50000\n");
  const auto r = ntn::io::read_at2(path);
  ASSERT_FALSE(r.error) << r.error->format();
  ASSERT_EQ(r.record->values.size(), 5U);
  EXPECT_DOUBLE_EQ(r.record->dt, 0.01);
  EXPECT_DOUBLE_EQ(r.record->values[1], -0.2);
  EXPECT_DOUBLE_EQ(r.record->values[2], 0.03);
  EXPECT_DOUBLE_EQ(r.record->values[4], -0.5);
}

// Linear interpolation between samples; zero before the start and after the end.
TEST(Record, InterpolatesAndIsZeroOutside) {
  ntn::io::Record r;
  r.dt = 0.5;
  r.values = {1.0, 3.0, -1.0};
  EXPECT_DOUBLE_EQ(r.at(0.0), 1.0);
  EXPECT_DOUBLE_EQ(r.at(0.25), 2.0);
  EXPECT_DOUBLE_EQ(r.at(0.75), 1.0);
  EXPECT_DOUBLE_EQ(r.at(1.0), -1.0);
  EXPECT_DOUBLE_EQ(r.at(1.25), -0.5);  // towards rest after the last sample
  EXPECT_DOUBLE_EQ(r.at(1.5), 0.0);
  EXPECT_DOUBLE_EQ(r.at(-0.1), 0.0);
  EXPECT_DOUBLE_EQ(r.duration(), 1.5);
}

TEST(Csv, ReadsAColumnByName) {
  const std::string path =
      write_temp("ok.csv", "time[s],a[m/s2],b[g]\n0,1,10\n0.001,2,20\n0.002,3,30\n");
  const auto r = ntn::io::read_csv(path, "b");
  ASSERT_FALSE(r.error) << r.error->format();
  EXPECT_EQ(r.record->units, "g");
  EXPECT_DOUBLE_EQ(r.record->dt, 0.001);
  EXPECT_EQ(r.record->values, (std::vector<double>{10, 20, 30}));
  EXPECT_EQ(ntn::io::read_record(path).record->values, (std::vector<double>{1, 2, 3}));
}

// A CSV as ntn-run and ntn-hil write it: times with 9 significant digits. At 1 024 Hz those are
// rounded (1/1024 = 0.0009765625 is printed 0.000976562), so spacing taken from the first two
// rows drifted off the grid at the 1 025th row. The grid from the end points is exact to the
// rounding of one printed time over the record: dt within 1e-9 relative.
TEST(Csv, ReadsNineDigitTimesAtAnyRate) {
  std::string text = "time,a\n";
  for (int k = 0; k < 3 * 1024; ++k) {
    char row[64];
    std::snprintf(row, sizeof row, "%.9g,%d\n", k / 1024.0, k % 7);
    text += row;
  }
  const std::string path = write_temp("rate1024.csv", text);
  const auto r = ntn::io::read_csv(path, "a");
  ASSERT_FALSE(r.error) << r.error->format();
  EXPECT_NEAR(r.record->dt, 1.0 / 1024, 1e-9 / 1024);
  EXPECT_EQ(r.record->values.size(), 3U * 1024);
}

struct BadFile {
  const char* name;
  const char* text;
  int line;
  int column;
  const char* message;
};

// Names the case in test listings (CTest shows gtest's parameter printout otherwise).
inline void PrintTo(const BadFile& c, std::ostream* os) {
  *os << c.name;
}

class BadRecords : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadRecords, ErrorNamesFileLineAndColumn) {
  const BadFile& b = GetParam();
  const std::string path = write_temp(b.name, b.text);
  const auto r = ntn::io::read_record(path);
  ASSERT_TRUE(r.error);
  EXPECT_FALSE(r.record);
  EXPECT_EQ(r.error->file, path);
  EXPECT_EQ(r.error->line, b.line);
  EXPECT_EQ(r.error->column, b.column);
  EXPECT_NE(r.error->message.find(b.message), std::string::npos) << r.error->message;
  EXPECT_EQ(r.error->format().rfind(path + ":" + std::to_string(b.line) + ":", 0), 0U);
}

INSTANTIATE_TEST_SUITE_P(
    Records, BadRecords,
    ::testing::Values(
        BadFile{"short.AT2", "a\nb\n", 1, 1, "3 free-text header lines and a fourth"},
        BadFile{"nohead.AT2", "a\nb\nc\nno numbers here\n1 2\n", 4, 1, "NPTS and DT"},
        BadFile{"dt0.AT2", "a\nb\nc\nNPTS= 2, DT= 0.0 SEC\n1 2\n", 4, 1,
                "DT = 0 s is outside the accepted sample interval [1e-06, 1] s"},
        BadFile{"npts.AT2", "a\nb\nc\nNPTS= 2.5, DT= 0.01 SEC\n1 2\n", 4, 1, "whole number"},
        BadFile{"text.AT2", "a\nb\nc\nNPTS= 3, DT= 0.01 SEC\n 0.1  0.2\n 0.3x\n", 6, 5,
                "not a finite number"},
        BadFile{"nan.AT2", "a\nb\nc\nNPTS= 2, DT= 0.01 SEC\n 0.1  nan\n", 5, 7,
                "not a finite number"},
        BadFile{"few.AT2", "a\nb\nc\nNPTS= 4, DT= 0.01 SEC\n 0.1  0.2\n 0.3\n", 6, 1,
                "holds 3 values"},
        BadFile{"many.AT2", "a\nb\nc\nNPTS= 2, DT= 0.01 SEC\n 0.1  0.2\n 0.3\n", 6, 1,
                "more values than NPTS"},
        BadFile{"cols.csv", "t,a\n0,1\n0.1,2,3\n", 3, 1, "expected 2 values"},
        BadFile{"uneven.csv", "t,a\n0,1\n0.1,2\n0.2,3\n0.35,4\n0.4,5\n", 5, 1,
                "not uniformly spaced"},
        BadFile{"back.csv", "t,a\n0,1\n-0.1,2\n", 3, 1, "time does not increase"},
        BadFile{"inf.csv", "t,a\n0,1\n0.1,inf\n", 3, 5, "not a finite number"},
        // Regressions: DT = 1e308 gave an infinite duration and std::length_error in the
        // runner; DT = 1e-300 gave a run of 0 steps reported as success. Both are
        // refused by the sample-interval rule, naming DT and its value.
        BadFile{"dt_huge.AT2", "a\nb\nUNITS OF G\nNPTS= 3, DT= 1e308 SEC\n1 2 3\n", 4, 1,
                "DT = 1e+308 s is outside the accepted sample interval"},
        BadFile{"dt_tiny.AT2", "a\nb\nUNITS OF G\nNPTS= 3, DT= 1e-300 SEC\n1 2 3\n", 4, 1,
                "DT = 1e-300 s is outside the accepted sample interval"},
        BadFile{"dt_ms.AT2", "a\nb\nUNITS OF G\nNPTS= 3, DT= 20 SEC\n1 2 3\n", 4, 1,
                "DT = 20 s is outside"},
        BadFile{"step_tiny.csv", "t,a\n0,1\n1e-300,2\n2e-300,3\n", 3, 1,
                "the time step = 1e-300 s is outside the accepted sample interval"},
        // The first extra value of NPTS = 3 is value 4 (was: "value 3
        // onwards", the first value of the line that overflowed).
        BadFile{"extra.AT2", "a\nb\nc\nNPTS= 3, DT= 0.01 SEC\n 0.1  0.2\n 0.3  0.4\n", 6, 1,
                "more values than NPTS = 3 (value 4 onwards)"},
        // A missing header line: say so, not "NPTS must be a positive whole number".
        BadFile{"two_lines.AT2", "title\nUNITS OF G\nNPTS= 3, DT= 0.01 SEC\n1 2 3\n", 3, 1,
                "1 header line is missing"},
        BadFile{"no_npts.AT2", "title\nevent\nUNITS OF G\n 0.1 0.2 0.3 0.4\n 0.5\n", 4, 1,
                "is a header line missing?"},
        // Times at its row, relative to the step (t ~ 1.7e9: the old 1e-8 |t|
        // allowance was 17 s). A row moved by half a step of 1 s; two rows swapped.
        BadFile{"epoch_jitter.csv",
                "t,a\n1700000000,1\n1700000001,2\n1700000002,3\n1700000003.5,4\n1700000004,5\n", 5,
                1, "time is not uniformly spaced: t = 1700000003.5 s"},
        BadFile{"epoch_order.csv",
                "t,a\n1700000000.00,1\n1700000000.02,2\n1700000000.01,3\n1700000000.03,4\n", 4, 1,
                "time does not increase"},
        // A row 2 % of a step off (t = 0.302 in steps of 0.1): beyond the 1 % of a step allowed.
        BadFile{"jitter2pct.csv", "t,a\n0,1\n0.1,2\n0.2,3\n0.302,4\n0.4,5\n0.5,6\n", 5, 1,
                "time is not uniformly spaced"},
        // The bad time at its own row (was reported at row 2).
        BadFile{"late_back.csv", "t,a\n0,1\n0.1,2\n0.2,3\n0.3,4\n0.25,5\n", 6, 1,
                "time does not increase (t = 0.25 s after 0.3 s)"},
        BadFile{"ms.csv", "time[ms],a\n0,1\n1,2\n", 1, 1, "the time column must be in s"},
        // Item 16: a header that names two units, or speaks of units and names none known.
        BadFile{"two_units.AT2", "a\nUNITS OF G\nIN CM/S/S\nNPTS= 1, DT= 0.01 SEC\n1\n", 3, 1,
                "two different units, 'g' and 'cm/s2'"},
        BadFile{"odd_units.AT2", "a\nb\nUNITS OF FURLONG/FORTNIGHT2\nNPTS= 1, DT= 0.01\n1\n", 3, 1,
                "speaks of units but names none that ntn knows"}),
    [](const ::testing::TestParamInfo<BadFile>& i) {
      std::string n = i.param.name;
      for (char& c : n)
        c = (c == '.') ? '_' : c;
      return n;
    });

TEST(Records, MissingFileIsAnErrorNotACrash) {
  const auto r = ntn::io::read_record("/nonexistent/record.AT2");
  ASSERT_TRUE(r.error);
  EXPECT_NE(r.error->message.find("cannot open"), std::string::npos);
}

// A file that cannot be opened has no position ("FILE:0:0:" was printed)
// and the reason is given; a directory is named as one (every reader, also the TableReader of
// ntn::spectral and ntn::plot).
TEST(Records, CannotOpenSaysWhyWithoutAPosition) {
  const auto r = ntn::io::read_record("/nonexistent/record.csv");
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->format(),
            "/nonexistent/record.csv: error: cannot open: No such file or directory");
  const std::string dir = std::filesystem::temp_directory_path().string();
  const auto d = ntn::io::read_record(dir);
  ASSERT_TRUE(d.error);
  EXPECT_EQ(d.error->format(), dir + ": error: cannot open: it is a directory");
  ntn::io::TableReader t;
  const auto e = t.open(dir, "time[s],a");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->format(), dir + ": error: cannot open: it is a directory");
  const auto m = t.open("/nonexistent/x.csv", "time[s],a");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->format(), "/nonexistent/x.csv: error: cannot open: No such file or directory");
}

// Item 13: a time column counted from an epoch is held to a fraction of the step like any other:
// 1.7e9 s + k 0.01 s printed with 10 decimals is read, its step right to the double's
// resolution at 1.7e9 (2.4e-7 s over 999 steps: 1e-9 s), and its origin kept as t0.
TEST(Csv, ReadsEpochTimesToAFractionOfTheStep) {
  std::string text = "time[s],a[g]\n";
  for (int k = 0; k < 1000; ++k) {
    char row[64];
    std::snprintf(row, sizeof row, "%.10f,%d\n", 1.7e9 + k * 0.01, k % 5);
    text += row;
  }
  const auto r = ntn::io::read_csv(write_temp("epoch.csv", text), "a");
  ASSERT_FALSE(r.error) << r.error->format();
  EXPECT_NEAR(r.record->dt, 0.01, 1e-9);
  EXPECT_DOUBLE_EQ(r.record->t0, 1.7e9);
  EXPECT_EQ(r.record->values.size(), 1000U);
}

// Item 13 (time origin): a record's time origin is its first row. A CSV starting at -1 s (a
// pre-trigger segment) is read with t0 = -1 kept for the runner's summary, and played from its
// first row: at(0) is the first value.
TEST(Csv, KeepsTheFirstTimeAsT0AndPlaysFromTheFirstRow) {
  const auto r = ntn::io::read_csv(write_temp("pre.csv", "time[s],a\n-1,5\n-0.5,6\n0,7\n"), "a");
  ASSERT_FALSE(r.error) << r.error->format();
  EXPECT_DOUBLE_EQ(r.record->t0, -1.0);
  EXPECT_DOUBLE_EQ(r.record->dt, 0.5);
  EXPECT_DOUBLE_EQ(r.record->at(0.0), 5.0);
  EXPECT_DOUBLE_EQ(r.record->at(1.0), 7.0);
}

// Within 1 % of a step: 0.5 % jitter of single rows (a logger's rounding) is accepted.
TEST(Csv, AcceptsJitterWithinOnePercentOfAStep) {
  const auto r = ntn::io::read_csv(
      write_temp("jitter05.csv", "t,a\n0,1\n0.1005,2\n0.2,3\n0.2995,4\n0.4,5\n"), "a");
  ASSERT_FALSE(r.error) << r.error->format();
  // The fitted step moves with the jitter of 2 rows of 5: within 0.2 % (it is 0.0999).
  EXPECT_NEAR(r.record->dt, 0.1, 2e-3 * 0.1);
}

// Item 16: units. parse_unit reads the common spellings; others are not guessed.
TEST(Units, ParsesCommonSpellings) {
  using ntn::io::parse_unit;
  using ntn::io::Quantity;
  for (const char* g : {"g", "G", "g "}) {
    ASSERT_TRUE(parse_unit(g)) << g;
    EXPECT_EQ(parse_unit(g)->name, "g");
    EXPECT_EQ(parse_unit(g)->si, 9.80665);
  }
  for (const char* gal : {"gal", "Gal", "GALS"})
    EXPECT_EQ(parse_unit(gal)->si, 0.01) << gal;
  for (const char* cm : {"cm/s2", "cm/s/s", "CM/SEC/SEC", "cm/s^2", "cm/sec**2", "cm/s\xc2\xb2"})
    EXPECT_EQ(parse_unit(cm)->si, 0.01) << cm;
  for (const char* m : {"m/s2", "m/s^2", "m/s/s", "m/sec2", "M/S2"})
    EXPECT_EQ(parse_unit(m)->si, 1.0) << m;
  EXPECT_EQ(parse_unit("mm/s2")->si, 1e-3);
  EXPECT_EQ(parse_unit("in/s2")->si, 0.0254);
  EXPECT_EQ(parse_unit("mg")->si, 9.80665e-3);
  EXPECT_EQ(parse_unit("kN")->quantity, Quantity::kForce);
  EXPECT_EQ(parse_unit("kN")->si, 1e3);
  EXPECT_EQ(parse_unit("N m")->quantity, Quantity::kMoment);
  for (const char* bad : {"", "m", "s", "furlong", "g/s", "m/s", "km/h"})
    EXPECT_FALSE(parse_unit(bad)) << bad;
}

// Item 16 with a real header style in gal: the Arleta record (PEER, in g) written as an AT2 whose
// third line says "ACCELERATION TIME HISTORY IN GAL (CM/S/S)" with every value x 980.665. The
// header test matched the substring "in g" and reported and used it as g (980 times too large).
// Now it is read as gal and converted to a g input to 1e-14 relative (the values are printed
// with 17 significant digits; one multiplication by 0.01 / 9.80665 rounds twice).
TEST(Units, At2InGalIsConvertedToAGInput) {
  const auto g = ntn::io::read_at2(kRecords + "/ARL360.AT2");
  ASSERT_FALSE(g.error) << g.error->format();
  std::string text =
      "PACIFIC ENGINEERING AND ANALYSIS STRONG-MOTION DATA\r\r\n"
      "NORTHRIDGE 01/17/94 1231, ARLETA, 360\r\r\n"
      "ACCELERATION TIME HISTORY IN GAL (CM/S/S)\r\r\n"
      "NPTS=  2000, DT= .02000 SEC\r\r\n";
  for (std::size_t k = 0; k < g.record->values.size(); ++k) {
    char v[40];
    std::snprintf(v, sizeof v, "%25.17E%s", g.record->values[k] * 980.665,
                  k % 5 == 4 ? "\r\r\n" : "");
    text += v;
  }
  auto gal = ntn::io::read_at2(write_temp("arleta_gal.AT2", text));
  ASSERT_FALSE(gal.error) << gal.error->format();
  EXPECT_EQ(gal.record->units, "gal");
  const ntn::io::Unit input = ntn::io::input_unit(true, 0, 9.80665);
  EXPECT_EQ(input.name, "g");
  ASSERT_FALSE(gal.record->to_unit(input));
  EXPECT_EQ(gal.record->units, "g");
  EXPECT_EQ(gal.record->converted_from, "gal");
  ASSERT_EQ(gal.record->values.size(), g.record->values.size());
  for (std::size_t k = 0; k < g.record->values.size(); ++k)
    EXPECT_NEAR(gal.record->values[k], g.record->values[k], 1e-14 * g.record->peak_abs()) << k;
}

// The same unit is no conversion at all: El Centro in g fed to a g input keeps every bit (the
// runner's output hash depends on it).
TEST(Units, SameUnitKeepsTheBits) {
  const auto a = ntn::io::read_at2(kRecords + "/elCentro.AT2");
  ASSERT_FALSE(a.error);
  ntn::io::Record r = *a.record;
  ASSERT_FALSE(r.to_unit(ntn::io::input_unit(true, 0, 9.80665)));
  EXPECT_EQ(r.values, a.record->values);
  EXPECT_TRUE(r.converted_from.empty());
  EXPECT_FALSE(r.unit_assumed);
}

// A CSV column in m/s2 fed to a g input is divided by g; in m (a length) or an unknown unit it is
// refused naming the unit; a column without a unit is taken as the input's unit, and says so.
TEST(Units, CsvColumnsAreConvertedOrRefused) {
  const std::string path = write_temp("units.csv",
                                      "time[s],a[m/s2],d[m],f[kN],x[furlong],n\n"
                                      "0,9.80665,1,2,3,4\n0.01,19.6133,1,2,3,4\n");
  const ntn::io::Unit g = ntn::io::input_unit(true, 0, 9.80665);
  auto a = ntn::io::read_csv(path, "a");
  ASSERT_FALSE(a.error) << a.error->format();
  ASSERT_FALSE(a.record->to_unit(g));
  EXPECT_DOUBLE_EQ(a.record->values[0], 1.0);
  EXPECT_DOUBLE_EQ(a.record->values[1], 2.0);
  EXPECT_EQ(a.record->converted_from, "m/s2");

  auto d = ntn::io::read_csv(path, "d");
  const auto de = d.record->to_unit(g);
  ASSERT_TRUE(de);
  EXPECT_NE(de->find("unit 'm' is not one ntn knows"), std::string::npos) << *de;

  auto f = ntn::io::read_csv(path, "f");
  const auto fe = f.record->to_unit(g);
  ASSERT_TRUE(fe);
  EXPECT_NE(fe->find("unit 'kN' is a force; the input wants an acceleration in g"),
            std::string::npos)
      << *fe;
  ASSERT_FALSE(f.record->to_unit(ntn::io::input_unit(false, 1, 1.0)));  // a force input in N
  EXPECT_DOUBLE_EQ(f.record->values[0], 2000.0);

  auto x = ntn::io::read_csv(path, "x");
  ASSERT_TRUE(x.record->to_unit(g));

  auto n = ntn::io::read_csv(path, "n");
  ASSERT_FALSE(n.record->to_unit(g));
  EXPECT_TRUE(n.record->unit_assumed);
  EXPECT_DOUBLE_EQ(n.record->values[0], 4.0);
}

// Words, not substrings: "IN GAL" is not "in g", and a "G" in a station name is no unit; the
// older PEER spellings of g are still read.
TEST(Units, At2HeaderWords) {
  auto units_of = [](const std::string& name, const std::string& line3) {
    const auto r = ntn::io::read_at2(
        write_temp(name, "t\nSTATION G, COMPONENT N\n" + line3 + "\nNPTS= 1, DT= 0.01 SEC\n1\n"));
    return r.error ? "error: " + r.error->message : r.record->units;
  };
  EXPECT_EQ(units_of("u1.AT2", "ACCELERATION TIME HISTORY IN UNITS OF G"), "g");
  EXPECT_EQ(units_of("u2.AT2", "The units are (g)"), "g");
  EXPECT_EQ(units_of("u3.AT2", "ACCELERATION IN G"), "g");
  EXPECT_EQ(units_of("u4.AT2", "ACCELERATION TIME HISTORY IN GAL (CM/S/S)"), "gal");
  EXPECT_EQ(units_of("u5.AT2", "ACCELERATION IN CM/SEC/SEC"), "cm/s2");
  EXPECT_EQ(units_of("u6.AT2", "UNITS: M/S2"), "m/s2");
  EXPECT_EQ(units_of("u7.AT2", "ACCELERATION TIME HISTORY"), "");
  EXPECT_EQ(units_of("u8.AT2", "COMMUNITY HOSPITAL (read as g) UNITS OF G"), "g");
}

}  // namespace
