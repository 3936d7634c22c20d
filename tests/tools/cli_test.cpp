// The shared command-line checks (tools/io/cli.hpp): every hostile number class, counts written
// other than as whole numbers, unwritable output paths and NAME=FILE[:COLUMN] parsing.
#include "cli.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "support/temp_files.hpp"

namespace {

// What a validator says of `text` (empty: accepted).
std::string says(const ntn::cli::Validator& v, std::string text) {
  return v(text);
}

TEST(Cli, PositiveRefusesEveryNonPositiveOrNonFiniteValue) {
  const ntn::cli::Validator v = ntn::cli::Positive();
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "0", "-0", "-1", "1e400", "abc", "", "1x"}) {
    EXPECT_NE(says(v, bad), "") << bad;
  }
  for (const char* good : {"1e-300", "1", "1e308", "0x1p-3"})
    EXPECT_EQ(says(v, good), "") << good;
}

TEST(Cli, RangeMessagesPrintNumbersShort) {
  const ntn::cli::Validator v = ntn::cli::Number(0.0, 1.7976931348623157e308);
  const std::string m = says(v, "-1");
  EXPECT_NE(m.find("got '-1'"), std::string::npos) << m;
  EXPECT_NE(m.find("1.79769e+308"), std::string::npos) << m;
  // No number of 20 or more digits: CLI11's own Range prints DBL_MAX in full.
  int run = 0, longest = 0;
  for (char c : m)
    longest = std::max(longest, run = (c >= '0' && c <= '9') ? run + 1 : 0);
  EXPECT_LT(longest, 20) << m;
  EXPECT_EQ(says(ntn::cli::Number(0, 1), "1"), "");
  EXPECT_NE(says(ntn::cli::Number(0, 1, true), "0"), "");
  EXPECT_EQ(says(ntn::cli::NonNegative(), "0"), "");
  EXPECT_NE(says(ntn::cli::Finite(), "nan"), "");
}

// What parsing `args` prints (CLI11's message on stderr) and returns (nothing, or the exit code).
struct Parsed {
  std::optional<int> code;
  std::string message;
};
Parsed parse(ntn::cli::App& app, std::vector<std::string> args) {
  args.insert(args.begin(), "prog");
  std::vector<const char*> argv;
  for (const std::string& a : args)
    argv.push_back(a.c_str());
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();  // --help
  Parsed p;
  p.code = ntn::cli::parse(app, static_cast<int>(argv.size()), argv.data());
  p.message = testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  return p;
}

TEST(Cli, CliElevenPutsTheOptionNameInFront) {
  ntn::cli::App app;
  double duration = 1;
  std::int64_t frames = 1;
  app.add_option("-t,--duration", duration)->check(ntn::cli::Positive());
  app.add_option("-n,--frames", frames)->check(ntn::cli::Integer(1, 1000));
  const Parsed nan = parse(app, {"-t", "nan"});
  EXPECT_EQ(nan.code, 2) << "a usage error exits 2";
  EXPECT_NE(nan.message.find("--duration"), std::string::npos) << nan.message;
  EXPECT_NE(parse(app, {"-n", "1e308"}).message.find("--frames"), std::string::npos);
  const Parsed good = parse(app, {"-t", "2.5", "-n", "7"});
  EXPECT_FALSE(good.code) << good.message;
  EXPECT_EQ(duration, 2.5);
  EXPECT_EQ(frames, 7);
}

// The few CLI11 features the tools use, through cli.hpp's classes (cli.cpp): subcommands, a
// member of a list, options that need or exclude others, counts, --help.
TEST(Cli, TheParserBehindCliHppKeepsCliElevensRules) {
  ntn::cli::App app{"test"};
  app.require_subcommand(1);
  ntn::cli::App* run = app.add_subcommand("run", "run");
  ntn::cli::App* other = app.add_subcommand("other", "other");
  std::string clock = "real", model;
  std::vector<double> values;
  bool fast = false;
  run->add_option("--clock", clock)->check(ntn::cli::IsMember({"real", "virtual"}));
  ntn::cli::Option* sampling = run->add_option("--sampling", model);
  run->add_flag("--fast", fast)->excludes(sampling);
  run->add_option("--values", values)->delimiter(',');
  other->add_option("--clock", clock);
  other->add_option("--hinge", model)->needs("--clock");

  EXPECT_EQ(parse(app, {}).code, 2) << "a subcommand is required";
  EXPECT_EQ(parse(app, {"--help"}).code, 0);
  const Parsed bad_clock = parse(app, {"run", "--clock", "wall"});
  EXPECT_EQ(bad_clock.code, 2);
  EXPECT_NE(bad_clock.message.find("--clock"), std::string::npos) << bad_clock.message;
  EXPECT_EQ(parse(app, {"run", "--fast", "--sampling", "hold"}).code, 2) << "excluded";
  EXPECT_EQ(parse(app, {"other", "--hinge", "h"}).code, 2) << "--hinge needs --clock";

  const Parsed good = parse(app, {"run", "--clock", "virtual", "--values", "1,2.5", "--fast"});
  ASSERT_FALSE(good.code) << good.message;
  EXPECT_TRUE(run->parsed());
  EXPECT_FALSE(other->parsed());
  EXPECT_EQ(clock, "virtual");
  EXPECT_EQ(values, (std::vector<double>{1, 2.5}));
  EXPECT_TRUE(fast);
  EXPECT_EQ(run->count("--clock"), 1U);
  EXPECT_EQ(run->count("--sampling"), 0U);
}

TEST(Cli, IntegerWantsDigitsWithinBounds) {
  const ntn::cli::Validator v = ntn::cli::Integer(1, 1000000);
  for (const char* bad : {"0", "-1", "1.5", "1e3", "nan", "inf", "1000001", "99999999999999999999",
                          "", "+", "-", "12a", " 3"}) {
    EXPECT_NE(says(v, bad), "") << bad;
  }
  for (const char* good : {"1", "+7", "1000000"})
    EXPECT_EQ(says(v, good), "") << good;
  EXPECT_NE(says(v, "0").find("[1, 1000000]"), std::string::npos);
}

// write_output_file: a regular file is replaced whole (beside itself, then renamed); through a
// symbolic link its target is, and the link stays; a FIFO (as a device: /dev/null) is written
// into and stays a FIFO, never replaced by a regular file; a directory is refused.
TEST(Cli, OutputFilesAreReplacedOnlyWhenRegular) {
  ntn_test::TempDir dir("cli_write");
  using ntn::cli::write_output_file;
  const std::string file = dir / "out.hpp";
  EXPECT_FALSE(write_output_file(file, "first", "--output"));
  EXPECT_FALSE(write_output_file(file, "second", "--output"));
  EXPECT_EQ(ntn_test::read_file(file), "second");
  EXPECT_FALSE(std::filesystem::exists(file + ".tmp"));
  const std::string link = dir / "link.hpp";
  std::filesystem::create_symlink("out.hpp", link);
  EXPECT_FALSE(write_output_file(link, "through the link", "--output"));
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(ntn_test::read_file(file), "through the link");
  const std::string fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string got;
  std::thread reader([&] { got = ntn_test::read_file(fifo); });
  EXPECT_FALSE(write_output_file(fifo, "into the pipe", "--output"));
  reader.join();
  EXPECT_EQ(got, "into the pipe");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  const auto refused = write_output_file(dir.str(), "x", "--output");
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->find("--output"), std::string::npos);
  EXPECT_NE(refused->find("directory"), std::string::npos);
}

TEST(Cli, OutputPathProblemsAreFoundBeforeARun) {
  ntn_test::TempDir dir("cli");
  const std::string file = dir / "a_file";
  ntn_test::write_file(file, "x");
  using ntn::cli::output_path_problem;
  EXPECT_FALSE(output_path_problem(dir / "out.csv", "--out"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv")) << "the check leaves no empty file";
  EXPECT_FALSE(output_path_problem(file, "--out"));
  EXPECT_EQ(ntn_test::read_file(file), "x") << "an existing file is not truncated by the check";

  const auto under_file = output_path_problem(file + "/out.csv", "--out");
  ASSERT_TRUE(under_file);
  EXPECT_NE(under_file->find("--out"), std::string::npos);
  EXPECT_NE(under_file->find("is not a directory"), std::string::npos) << *under_file;
  const auto is_dir = output_path_problem(dir.str(), "--summary-json");
  ASSERT_TRUE(is_dir);
  EXPECT_NE(is_dir->find("--summary-json"), std::string::npos);
  EXPECT_NE(is_dir->find("is a directory"), std::string::npos);
  EXPECT_TRUE(output_path_problem(dir / "no_such_dir/out.csv", "--out"));
  EXPECT_TRUE(output_path_problem("/proc/x/y", "--out"));
  EXPECT_TRUE(output_path_problem("", "--out"));
  // Created on request, as ntn-modelc and the runner do for a build tree.
  EXPECT_FALSE(output_path_problem(dir / "new/deeper/out.csv", "--out", true));
  EXPECT_TRUE(std::filesystem::is_directory(dir / "new/deeper"));
  EXPECT_TRUE(output_path_problem(file + "/sub/out.csv", "--out", true));
  EXPECT_TRUE(output_path_problem("/proc/x/y", "--out", true));
}

TEST(Cli, InputArgumentsAreReadOneWay) {
  const ntn::cli::InputArgs ok =
      ntn::cli::parse_input_args({"ag_x=a.AT2", "ag_y=b.csv:acc", "ag_z=C:/c.csv"});
  ASSERT_FALSE(ok.error);
  ASSERT_EQ(ok.args.size(), 3u);
  EXPECT_EQ(ok.args[0].name, "ag_x");
  EXPECT_EQ(ok.args[0].file, "a.AT2");
  EXPECT_EQ(ok.args[0].column, "");
  EXPECT_EQ(ok.args[1].file, "b.csv");
  EXPECT_EQ(ok.args[1].column, "acc");
  EXPECT_EQ(ok.args[2].file, "C:/c.csv") << "a drive letter is not a column";

  for (const char* bad : {"ag_x", "=a.AT2", "ag_x="}) {
    const auto r = ntn::cli::parse_input_args({bad});
    ASSERT_TRUE(r.error) << bad;
    EXPECT_NE(r.error->find("--input"), std::string::npos);
    EXPECT_NE(r.error->find(bad), std::string::npos);
  }
  const auto twice = ntn::cli::parse_input_args({"ag_x=a.AT2", "ag_x=b.AT2"});
  ASSERT_TRUE(twice.error);
  EXPECT_NE(twice.error->find("'ag_x' is given twice"), std::string::npos) << *twice.error;
}

// NAME=FILE[:COLUMN][*FACTOR]: the factor is what follows the last '*' when it reads as a
// number; otherwise the '*' is part of the file name. The factor must be finite and not 0.
TEST(Cli, InputArgumentsTakeAScaleFactor) {
  const ntn::cli::InputArgs ok =
      ntn::cli::parse_input_args({"a=rec.AT2*1.5", "b=b.csv:acc*-2", "c=we*ird.AT2",
                                  "d=odd.AT2*2*1", "e=C:/c.csv*0x1p-3", "f=rec.AT2", "g=x*2e-1"});
  ASSERT_FALSE(ok.error) << *ok.error;
  ASSERT_EQ(ok.args.size(), 7u);
  EXPECT_EQ(ok.args[0].file, "rec.AT2");
  EXPECT_EQ(ok.args[0].factor, 1.5);
  EXPECT_EQ(ok.args[1].file, "b.csv");
  EXPECT_EQ(ok.args[1].column, "acc");
  EXPECT_EQ(ok.args[1].factor, -2.0);
  EXPECT_EQ(ok.args[2].file, "we*ird.AT2") << "no number after the '*': part of the name";
  EXPECT_EQ(ok.args[2].factor, 1.0);
  EXPECT_EQ(ok.args[3].file, "odd.AT2*2") << "only the last '*' can start a factor";
  EXPECT_EQ(ok.args[3].factor, 1.0);
  EXPECT_EQ(ok.args[4].file, "C:/c.csv");
  EXPECT_EQ(ok.args[4].factor, 0.125);
  EXPECT_EQ(ok.args[5].factor, 1.0);
  EXPECT_EQ(ok.args[6].file, "x");
  EXPECT_EQ(ok.args[6].factor, 0.2);

  for (const char* f : {"nan", "inf", "-inf", "0", "-0", "1e999", "1e-999"}) {
    const std::string arg = std::string("ag_x=rec.AT2*") + f;
    const auto r = ntn::cli::parse_input_args({arg});
    ASSERT_TRUE(r.error) << f;
    EXPECT_NE(r.error->find("--input " + arg +
                            ": the scale factor after '*' must be a finite "
                            "number other than 0, got '" +
                            f + "'"),
              std::string::npos)
        << *r.error;
  }
  const auto empty = ntn::cli::parse_input_args({"ag_x=*2"});
  ASSERT_TRUE(empty.error);
  EXPECT_NE(empty.error->find("wants NAME=FILE[:COLUMN][*FACTOR]"), std::string::npos);

  // A '*' followed by no number where the file before it exists and the whole name does not: a
  // mistyped factor, said so. Where the whole name exists it is the file.
  const ntn_test::TempDir dir("cli_scale");
  ntn_test::write_file(dir / "rec.AT2", "x");
  for (const char* tail : {"x2", "1,5", ""}) {
    const std::string arg = "ag_x=" + dir / "rec.AT2" + "*" + tail;
    const auto r = ntn::cli::parse_input_args({arg}, "--record/--input");
    ASSERT_TRUE(r.error) << tail;
    EXPECT_NE(r.error->find("--record/--input " + arg + ": '" + tail +
                            "' after the last '*' is not a number, and there is no file"),
              std::string::npos)
        << *r.error;
  }
  ntn_test::write_file(dir / "rec.AT2*x2", "x");
  const auto named = ntn::cli::parse_input_args({"ag_x=" + dir / "rec.AT2*x2"});
  ASSERT_FALSE(named.error) << *named.error;
  EXPECT_EQ(named.args[0].file, dir / "rec.AT2*x2");
}

}  // namespace
