// Scaling a record with no file (config/README.md, [[inputs]] `scale`; tools/run/README.md,
// `--input NAME=FILE*FACTOR`): `ntn-run MODEL.toml` and the compiled `ntn-run-frame3d` as
// subprocesses, on frame3d under the first 2 s of El Centro (18 000 steps).
//
// frame3d is linear: no gravity, no loads, at rest at t = 0, elastic members, and rigid hinges
// tied by the forest's linear projection. Every operation of its step is then a sum, or a product
// of the input with the model's constants. Multiplying every input value by a power of two
// multiplies every intermediate result by it exactly (the significands stay the same, so each
// rounding is the same), as long as nothing overflows or becomes subnormal (this response is
// hundreds of orders of magnitude from both). So a factor 2, on the record (FILE*2, before the
// kernel) or in the model file (scale = 2, value x scale x factor in the kernel), doubles every
// value of the CSV bit for bit, and -1 negates it; those are compared exactly. A factor such as 1.5
// rounds each scaled sample (1.5 x can need one bit more than x has: 1.1e-16 relative), a
// perturbation of the input that goes through the linear response. The displacements and drifts
// then differ from 1.5 times the unscaled ones by about 1e-14 of their peak; the channels computed
// as differences of larger numbers lose the digits that cancel: the element forces and reactions (K
// u of nearly equal end displacements) up to 2e-12, the absolute acceleration (a + a_g, nearly
// opposite) and the pinned beam's axial force up to 4e-11 (measured over 10 s for factors 0.1 to 3;
// 2 s here). So kTolerances: 1e-13 for the first four channels, 1e-10 for the others. A factor
// applied wrongly (once too often, or not at all) is off by 50 % or more.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "hil/subprocess.hpp"
#include "support/response_csv.hpp"

namespace {

using namespace std::chrono_literals;
using ntn_test::Child;
using ntn_test::read_file;
using ntn_test::read_response_csv;
using ntn_test::ResponseCsv;
using ntn_test::scaled_response;
using ntn_test::TempDir;

const std::string kElCentro = std::string(NTN_RECORDS_DIR) + "/elCentro.AT2";
const std::string kFrame3d = std::string(NTN_CONFIG_DIR) + "/frame3d.toml";
// frame3d's channels: roof_ux, floor1_ux, drift1_x, drift2_x, base_shear_x, col_A1_base_My,
// roof_ax, pin_A1_1_V, pin_A1_1_N (header comment).
const std::vector<double> kTolerances = {1e-13, 1e-13, 1e-13, 1e-13, 1e-10,
                                         1e-10, 1e-10, 1e-10, 1e-10};

struct Outcome {
  int rc = -1;
  std::string text;  // stdout and stderr
  std::string hash;  // the output hash, if printed
  ResponseCsv csv;
};

// Runs `program` (ntn-run: with the model file first) on the input argument, 2 s, into dir/tag.csv.
Outcome run(const TempDir& dir, const std::string& tag, std::vector<std::string> args) {
  args.insert(args.end(), {"--duration", "2", "--out", dir / (tag + ".csv"), "-q"});
  Outcome r;
  Child c(args, dir / (tag + ".txt"));
  r.rc = c.wait(2min);
  r.text = read_file(dir / (tag + ".txt"));
  if (const auto at = r.text.find("output hash "); at != std::string::npos)
    r.hash = r.text.substr(at + 12, 16);
  r.csv = read_response_csv(dir / (tag + ".csv"));
  return r;
}

std::vector<std::string> ntn_run(const std::string& model, const std::string& input) {
  return {NTN_RUN, model, "--input", "ag_x=" + input};
}

// frame3d.toml with `scale = <factor>` on its ground acceleration input.
std::string frame3d_scaled(const TempDir& dir, const std::string& factor) {
  std::string text = read_file(kFrame3d);
  const std::string units = "units = \"g\"\n";
  const auto at = text.find(units);
  EXPECT_NE(at, std::string::npos);
  text.insert(at + units.size(), "scale = " + factor + "\n");
  const std::string path = dir / ("frame3d_scale_" + factor + ".toml");
  ntn_test::write_file(path, text);
  return path;
}

class Scale : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("scale_test");
    base_ = new Outcome(run(*dir_, "base", ntn_run(kFrame3d, kElCentro)));
  }
  static void TearDownTestSuite() {
    delete base_;
    delete dir_;
  }
  static const Outcome& base() {
    EXPECT_EQ(base_->rc, 0) << base_->text;
    return *base_;
  }
  static TempDir* dir_;
  static Outcome* base_;
};
TempDir* Scale::dir_ = nullptr;
Outcome* Scale::base_ = nullptr;

TEST_F(Scale, CommandLineFactorTwoDoublesEveryValue) {
  const Outcome r = run(*dir_, "cli2", ntn_run(kFrame3d, kElCentro + "*2"));
  ASSERT_EQ(r.rc, 0) << r.text;
  EXPECT_TRUE(scaled_response(base().csv, r.csv, 2.0));
  EXPECT_NE(r.hash, base().hash);
  // The compiled runner reads the argument with the same code: the same bits.
  const Outcome compiled =
      run(*dir_, "compiled2", {NTN_RUN_FRAME3D, "--input", "ag_x=" + kElCentro + "*2"});
  ASSERT_EQ(compiled.rc, 0) << compiled.text;
  EXPECT_EQ(compiled.hash, r.hash);
  EXPECT_EQ(read_file(*dir_ / "compiled2.csv"), read_file(*dir_ / "cli2.csv"));
}

TEST_F(Scale, ModelFileScaleTwoDoublesEveryValue) {
  const Outcome r = run(*dir_, "file2", ntn_run(frame3d_scaled(*dir_, "2.0"), kElCentro));
  ASSERT_EQ(r.rc, 0) << r.text;
  EXPECT_TRUE(scaled_response(base().csv, r.csv, 2.0));
}

// The command line's factor multiplies the model file's: 2 x 0.5 is the unscaled run to the bit
// (its output hash too), 2 x 2 four times it.
TEST_F(Scale, ModelFileAndCommandLineCompose) {
  const std::string file2 = frame3d_scaled(*dir_, "2.0");
  const Outcome half = run(*dir_, "file2_cli_half", ntn_run(file2, kElCentro + "*0.5"));
  ASSERT_EQ(half.rc, 0) << half.text;
  EXPECT_TRUE(scaled_response(base().csv, half.csv, 1.0));
  EXPECT_EQ(half.hash, base().hash);
  const Outcome four = run(*dir_, "file2_cli2", ntn_run(file2, kElCentro + "*2"));
  ASSERT_EQ(four.rc, 0) << four.text;
  EXPECT_TRUE(scaled_response(base().csv, four.csv, 4.0));
}

TEST_F(Scale, NegativeFactorReversesTheMotion) {
  const Outcome cli = run(*dir_, "cli_minus", ntn_run(kFrame3d, kElCentro + "*-1"));
  ASSERT_EQ(cli.rc, 0) << cli.text;
  EXPECT_TRUE(scaled_response(base().csv, cli.csv, -1.0));
  const Outcome file = run(*dir_, "file_minus", ntn_run(frame3d_scaled(*dir_, "-1.0"), kElCentro));
  ASSERT_EQ(file.rc, 0) << file.text;
  EXPECT_TRUE(scaled_response(base().csv, file.csv, -1.0));
}

// Not a power of two: each scaled sample is rounded once (header comment: kTolerances).
TEST_F(Scale, OtherFactorsScaleTheResponseToRounding) {
  const Outcome cli = run(*dir_, "cli1_5", ntn_run(kFrame3d, kElCentro + "*1.5"));
  ASSERT_EQ(cli.rc, 0) << cli.text;
  EXPECT_TRUE(scaled_response(base().csv, cli.csv, 1.5, kTolerances));
  const Outcome both =
      run(*dir_, "file1_5_cli3", ntn_run(frame3d_scaled(*dir_, "1.5"), kElCentro + "*3"));
  ASSERT_EQ(both.rc, 0) << both.text;
  EXPECT_TRUE(scaled_response(base().csv, both.csv, 4.5, kTolerances));
}

// The input's accepted range (frame3d: [-3, 3] g) is of the values the channel receives: the
// record times the command line's factor (as a feeder would send it scaled), before the model
// file's scale. El Centro's peak is 0.319 g: x 10 leaves the range and is refused before the
// run; the model file's scale = 10 on the unscaled record runs.
TEST_F(Scale, RangeAppliesToTheScaledRecordNotTheModelFileScale) {
  const Outcome cli = run(*dir_, "cli10", ntn_run(kFrame3d, kElCentro + "*10"));
  EXPECT_EQ(cli.rc, 2) << cli.text;
  EXPECT_NE(cli.text.find("g (the record x 10) is outside the accepted range [-3, 3] of input "
                          "'ag_x'"),
            std::string::npos)
      << cli.text;
  const Outcome file = run(*dir_, "file10", ntn_run(frame3d_scaled(*dir_, "10"), kElCentro));
  ASSERT_EQ(file.rc, 0) << file.text;
  EXPECT_TRUE(scaled_response(base().csv, file.csv, 10.0, kTolerances));
}

// A '*' in a file name is part of it unless a number follows the last one.
TEST_F(Scale, StarInAFileName) {
  const std::string odd = *dir_ / "el*centro.AT2";
  std::filesystem::copy_file(kElCentro, odd);
  const Outcome plain = run(*dir_, "odd", ntn_run(kFrame3d, odd));
  ASSERT_EQ(plain.rc, 0) << plain.text;
  EXPECT_EQ(plain.hash, base().hash);
  const Outcome doubled = run(*dir_, "odd2", ntn_run(kFrame3d, odd + "*2"));
  ASSERT_EQ(doubled.rc, 0) << doubled.text;
  EXPECT_TRUE(scaled_response(base().csv, doubled.csv, 2.0));
}

TEST_F(Scale, BadFactorsAreRefused) {
  for (const char* f : {"nan", "inf", "-inf", "0", "1e999"}) {
    const Outcome r = run(*dir_, "bad", ntn_run(kFrame3d, kElCentro + "*" + f));
    EXPECT_EQ(r.rc, 2) << f;
    EXPECT_NE(r.text.find("--input ag_x=" + kElCentro + "*" + f +
                          ": the scale factor after '*' must be a finite number other than 0"),
              std::string::npos)
        << r.text;
  }
  const Outcome word = run(*dir_, "bad", ntn_run(kFrame3d, kElCentro + "*x2"));
  EXPECT_EQ(word.rc, 2);
  EXPECT_NE(word.text.find("'x2' after the last '*' is not a number"), std::string::npos)
      << word.text;
  const Outcome name =
      run(*dir_, "bad", {NTN_RUN, kFrame3d, "--input", "nope=" + kElCentro + "*2"});
  EXPECT_EQ(name.rc, 2);
  EXPECT_NE(name.text.find("the model has no input channel 'nope'"), std::string::npos)
      << name.text;
}

}  // namespace
