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
        BadFile{"short.AT2", "a\nb\n", 1, 1, "4 header lines"},
        BadFile{"nohead.AT2", "a\nb\nc\nno numbers here\n1 2\n", 4, 1, "NPTS and DT"},
        BadFile{"dt0.AT2", "a\nb\nc\nNPTS= 2, DT= 0.0 SEC\n1 2\n", 4, 1, "DT must be positive"},
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
        BadFile{"back.csv", "t,a\n0,1\n-0.1,2\n", 3, 1, "time must increase"},
        BadFile{"inf.csv", "t,a\n0,1\n0.1,inf\n", 3, 5, "not a finite number"}),
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

}  // namespace
