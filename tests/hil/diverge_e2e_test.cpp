// Failure behaviour end to end: a model whose dt is ~1.5 x its stable step
// through the explicit override (tests/hil/unstable_cantilever.toml), run by `ntn-hil run
// MODEL.toml` as a subprocess on the virtual clock under El Centro. The loop must catch it, say so
// on screen and in the JSON (the diverged frame, the safe state), exit with code 3, and write a CSV
// without a NaN or Inf whose flag column has the diverged bit from that frame on, with the last
// good frame's values held.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "ntn/hil/packet.hpp"
#include "subprocess.hpp"

namespace {

using ntn_test::Child;
using ntn_test::read_file;
using ntn_test::TempDir;

// The number after "key": in a JSON text (NaN when missing, which fails every comparison).
double json_number(const std::string& text, const std::string& key) {
  const std::string k = "\"" + key + "\":";
  const std::size_t at = text.find(k);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + k.size(), nullptr);
}

TEST(DivergeE2e, UnstableModelGoesToTheSafeState) {
  const TempDir dir("diverge_e2e");
  constexpr int kFrames = 2000;
  Child run({NTN_HIL, "run", NTN_HIL_UNSTABLE, "--clock", "virtual", "--input",
             std::string("ag_x=") + NTN_RECORDS_DIR + "/elCentro.AT2", "--frames",
             std::to_string(kFrames), "--out", dir / "run.csv", "--summary-json", dir / "run.json"},
            dir / "run.txt");
  ASSERT_TRUE(run.started());
  EXPECT_EQ(run.wait(), 3);  // hil_main: 3 = the loop diverged
  const std::string screen = read_file(dir / "run.txt");
  const std::string json = read_file(dir / "run.json");

  const double kd = json_number(json, "diverged_frame");
  ASSERT_GE(kd, 1) << screen;
  const auto frame = static_cast<long long>(kd);
  EXPECT_NE(screen.find("DIVERGED at frame " + std::to_string(frame) + " "), std::string::npos)
      << screen;
  EXPECT_NE(screen.find("kinetic energy above the limit"), std::string::npos) << screen;
  EXPECT_NE(screen.find("SAFE STATE from frame " + std::to_string(frame)), std::string::npos)
      << screen;
  EXPECT_NE(json.find("\"safe_state\": true"), std::string::npos) << json;
  EXPECT_NE(json.find("\"reason\": \"kinetic energy above the limit\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"state_restored\": true"), std::string::npos) << json;
  EXPECT_EQ(json_number(json, "last_good_frame"), kd - 1);
  EXPECT_GT(json_number(json, "kinetic_at_detection_J"), json_number(json, "kinetic_limit_J"));

  // The CSV: one row per frame, every value finite, the diverged bit exactly from frame kd on,
  // and from there the values of frame kd - 1.
  std::ifstream csv(dir / "run.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));  // header
  std::vector<std::vector<double>> rows;
  std::vector<unsigned> flags;
  while (std::getline(csv, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ','))
      row.push_back(std::strtod(cell.c_str(), nullptr));  // strtod reads "nan" and "inf" too
    ASSERT_GE(row.size(), 3U) << line;
    flags.push_back(static_cast<unsigned>(row.back()));
    row.pop_back();
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(kFrames));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    for (double x : rows[k])
      ASSERT_TRUE(std::isfinite(x)) << "frame " << k;
    EXPECT_EQ((flags[k] & ntn::hil::flag::kDiverged) != 0, static_cast<long long>(k) >= frame)
        << "frame " << k;
    if (static_cast<long long>(k) >= frame) {
      for (std::size_t c = 1; c < rows[k].size(); ++c)  // column 0 is the time
        EXPECT_EQ(rows[k][c], rows[static_cast<std::size_t>(frame - 1)][c]) << "frame " << k;
    }
  }
}

// Divergence in frame 0 (the screen used to say "outputs held at frame -1's values"): there
// are no good outputs to hold yet; the screen says so, the outputs are 0 (no NaN), flagged, and
// the JSON's last good frame is -1. Input: a constant 3 g (the input's full range) for 50 ms.
TEST(DivergeE2e, DivergenceInFrameZeroSaysNoFrameWasGood) {
  const TempDir dir("diverge_frame0");
  std::string csv = "time[s],a[g]\n";
  for (int i = 0; i <= 50; ++i)
    csv += std::to_string(i * 1e-3) + ",3\n";
  ntn_test::write_file(dir / "step.csv", csv);
  Child run({NTN_HIL, "run", NTN_HIL_UNSTABLE_2MS, "--clock", "virtual", "--input",
             "ag_x=" + (dir / "step.csv"), "--frames", "20", "--out", dir / "run.csv",
             "--summary-json", dir / "run.json"},
            dir / "run.txt");
  ASSERT_TRUE(run.started());
  EXPECT_EQ(run.wait(), 3);
  const std::string screen = read_file(dir / "run.txt");
  const std::string json = read_file(dir / "run.json");
  EXPECT_NE(screen.find("DIVERGED at frame 0 "), std::string::npos) << screen;
  EXPECT_NE(screen.find("SAFE STATE from frame 0: no more steps; no frame completed before it, "
                        "so the outputs are 0, flagged diverged (bit 14); state kept at the "
                        "initial state"),
            std::string::npos)
      << screen;
  EXPECT_EQ(screen.find("frame -1"), std::string::npos) << screen;
  EXPECT_EQ(json_number(json, "diverged_frame"), 0);
  EXPECT_EQ(json_number(json, "last_good_frame"), -1);
  std::ifstream rows(dir / "run.csv");
  std::string line;
  ASSERT_TRUE(std::getline(rows, line));  // header
  int n = 0;
  for (; std::getline(rows, line); ++n) {
    std::stringstream cells(line);
    std::vector<double> row;
    for (std::string cell; std::getline(cells, cell, ',');)
      row.push_back(std::strtod(cell.c_str(), nullptr));
    ASSERT_GE(row.size(), 3U) << line;
    EXPECT_NE(static_cast<unsigned>(row.back()) & ntn::hil::flag::kDiverged, 0U) << line;
    for (std::size_t c = 1; c + 1 < row.size(); ++c)
      EXPECT_EQ(row[c], 0.0) << line;
  }
  EXPECT_EQ(n, 20);
}

}  // namespace
