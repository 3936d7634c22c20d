// Scaling a record with no file in the frame loop (hil_sim/README.md): `ntn-hil run MODEL.toml`
// and `ntn-hil-frame3d run` on the virtual clock with `--input ag_x=FILE*FACTOR` and the model
// file's `scale`, and `ntn-feeder --input NAME=FILE*FACTOR` sending the scaled record to the loop
// in lock-step. frame3d under the first 2 s of El Centro, as tests/tools/scale_test.cpp (which
// says why a factor 2 doubles a linear model's response bit for bit: compared exactly here).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "subprocess.hpp"
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
constexpr int kFrames = 2000;  // 2 s at 1 kHz

struct Outcome {
  int rc = -1;
  std::string text, hash;
  ResponseCsv csv;
};

std::string output_hash(const std::string& out) {
  const std::string key = "output hash ";
  const std::size_t at = out.find(key);
  return at == std::string::npos ? "" : out.substr(at + key.size(), 16);
}

// `args` (the program and its `run` arguments) on the virtual clock for kFrames, into dir/tag.csv,
// with the model file's drift alarms off (a scaled response raises them at other frames: the
// flags would differ, as they should).
Outcome run(const TempDir& dir, const std::string& tag, std::vector<std::string> args) {
  args.insert(args.end(),
              {"--clock", "virtual", "--frames", std::to_string(kFrames), "--out",
               dir / (tag + ".csv"), "--alarm", "drift1_x=off", "--alarm", "drift2_x=off", "-q"});
  Outcome r;
  Child c(args, dir / (tag + ".txt"));
  r.rc = c.wait(2min);
  r.text = read_file(dir / (tag + ".txt"));
  r.hash = output_hash(r.text);
  r.csv = read_response_csv(dir / (tag + ".csv"));
  return r;
}

std::vector<std::string> hil(const std::string& model, const std::string& input) {
  return {NTN_HIL, "run", model, "--input", "ag_x=" + input};
}

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

// How many frames have the gate's out-of-range bit (flag::kOutOfRange, bit 3).
std::size_t out_of_range_frames(const ResponseCsv& csv) {
  std::size_t n = 0;
  for (const std::string& f : csv.flags)
    n += (std::strtoul(f.c_str(), nullptr, 10) >> 3) & 1U;
  return n;
}

TEST(HilScale, CommandLineAndModelFileScaleDoubleTheResponse) {
  const TempDir dir("hil_scale");
  const Outcome base = run(dir, "base", hil(kFrame3d, kElCentro));
  ASSERT_EQ(base.rc, 0) << base.text;
  const Outcome cli = run(dir, "cli2", hil(kFrame3d, kElCentro + "*2"));
  ASSERT_EQ(cli.rc, 0) << cli.text;
  EXPECT_TRUE(scaled_response(base.csv, cli.csv, 2.0));
  const std::string file2 = frame3d_scaled(dir, "2.0");
  const Outcome file = run(dir, "file2", hil(file2, kElCentro));
  ASSERT_EQ(file.rc, 0) << file.text;
  EXPECT_TRUE(scaled_response(base.csv, file.csv, 2.0));
  // They compose: 2 x 0.5 is the unscaled run, its hash too.
  const Outcome both = run(dir, "file2_cli_half", hil(file2, kElCentro + "*0.5"));
  ASSERT_EQ(both.rc, 0) << both.text;
  EXPECT_TRUE(scaled_response(base.csv, both.csv, 1.0));
  EXPECT_EQ(both.hash, base.hash);
  // The compiled loop reads the argument with the same code.
  const Outcome compiled =
      run(dir, "compiled2", {NTN_HIL_FRAME3D, "run", "--input", "ag_x=" + kElCentro + "*2"});
  ASSERT_EQ(compiled.rc, 0) << compiled.text;
  EXPECT_EQ(compiled.hash, cli.hash);
  EXPECT_EQ(read_file(dir / "compiled2.csv"), read_file(dir / "cli2.csv"));
}

// The gate holds values outside the input's [min, max] (frame3d: [-3, 3] g) as they arrive: the
// first 2 s of El Centro scaled by 20 on the command line reach 3.44 g and frames are held
// (flagged); the same factor as the model file's scale acts after the gate, and no frame is.
TEST(HilScale, GateSeesTheScaledRecordNotTheModelFileScale) {
  const TempDir dir("hil_scale_gate");
  const Outcome cli = run(dir, "cli20", hil(kFrame3d, kElCentro + "*20"));
  ASSERT_EQ(cli.rc, 0) << cli.text;
  EXPECT_GT(out_of_range_frames(cli.csv), 0U);
  const Outcome file = run(dir, "file20", hil(frame3d_scaled(dir, "20"), kElCentro));
  ASSERT_EQ(file.rc, 0) << file.text;
  EXPECT_EQ(out_of_range_frames(file.csv), 0U);
}

// The feeder scales its records with the same argument: the loop fed `--input ag_x=FILE*2` over
// UDP in lock-step computes what it computes from the file scaled by 2 (its output hash), and the
// feeder's --scale multiplies the factor (4 x 0.5).
TEST(HilScale, FeederSendsTheScaledRecord) {
  const TempDir dir("hil_scale_feeder");
  const Outcome file =
      run(dir, "file", {NTN_HIL_FRAME3D, "run", "--input", "ag_x=" + kElCentro + "*2"});
  ASSERT_EQ(file.rc, 0) << file.text;
  for (const std::vector<std::string>& feed :
       {std::vector<std::string>{"--input", "ag_x=" + kElCentro + "*2"},
        std::vector<std::string>{"--record", kElCentro + "*4", "--scale", "0.5"}}) {
    const auto ports = ntn_test::free_ports(2);
    ASSERT_EQ(ports.size(), 2U);
    Child loop(
        {NTN_HIL_FRAME3D, "run", "--listen", std::to_string(ports[0]), "--reply",
         std::to_string(ports[1]), "--frames", std::to_string(kFrames), "--clock", "virtual", "-q"},
        dir / "loop.txt");
    ASSERT_TRUE(loop.started() && ntn_test::wait_port_bound(ports[0], 10s))
        << read_file(dir / "loop.txt");
    std::vector<std::string> f = {NTN_FEEDER,
                                  "--port",
                                  std::to_string(ports[0]),
                                  "--listen-port",
                                  std::to_string(ports[1]),
                                  "--frames",
                                  std::to_string(kFrames),
                                  "--virtual",
                                  "-q"};
    f.insert(f.end(), feed.begin(), feed.end());
    Child feeder(f, dir / "feeder.txt");
    EXPECT_EQ(feeder.wait(60s), 0) << read_file(dir / "feeder.txt");
    EXPECT_EQ(loop.wait(60s), 0) << read_file(dir / "loop.txt");
    EXPECT_EQ(output_hash(read_file(dir / "loop.txt")), file.hash) << feed.back();
    std::filesystem::remove(dir / "loop.txt");
  }
}

}  // namespace
