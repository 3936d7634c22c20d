// The stable step's bound of second-order geometry in the summaries: `ntn-run MODEL.toml` and
// `ntn-hil run MODEL.toml --clock virtual` as subprocesses on tests/tools/past_geometry_bound.toml,
// a p_delta bar whose pull passes the bound at 0.114 s (frame 113). Run to 0.2 s, the screen, the
// JSON and stderr (also with -q) say from which frame it was past the bound, how many element
// evaluations were, and that results past it are not valid, and the exit code stays 0 (the run
// went on). Run to 0.1 s, inside the bound, the screen says it held and nothing is flagged.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "hil/subprocess.hpp"

namespace {

using ntn_test::Child;
using ntn_test::read_file;
using ntn_test::TempDir;

const std::string kModel = NTN_PAST_GEOMETRY_BOUND;
const std::string kMeaning =
    "the step left its stable bound for the axial forces and chord rotations reached: results "
    "past it are not valid";

struct Outcome {
  int rc = -1;
  std::string text;  // stdout and stderr
  std::string json;
};

Outcome run(const TempDir& dir, const std::string& tag, std::vector<std::string> args) {
  args.insert(args.end(), {"--summary-json", dir / (tag + ".json")});
  Outcome r;
  Child c(args, dir / (tag + ".txt"));
  r.rc = c.wait(std::chrono::minutes(1));
  r.text = read_file(dir / (tag + ".txt"));
  r.json = read_file(dir / (tag + ".json"));
  return r;
}

// The text of the JSON object or value after "key": (to the matching brace, or the line's end).
std::string json_field(const std::string& json, const std::string& key) {
  const std::string k = "\"" + key + "\": ";
  const std::size_t at = json.find(k);
  if (at == std::string::npos) return {};
  const std::size_t from = at + k.size();
  const std::size_t to = json[from] == '{' ? json.find('}', from) + 1 : json.find('\n', from);
  std::string v = json.substr(from, to - from);
  if (!v.empty() && v.back() == ',') v.pop_back();
  return v;
}

double json_number(const std::string& object, const std::string& key) {
  const std::string k = "\"" + key + "\": ";
  const std::size_t at = object.find(k);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(object.c_str() + at + k.size(), nullptr);
}

// A run past the bound: the summary's line, the JSON and the warning; `label` is the screen's.
void expect_past(const Outcome& r, const std::string& label, double last_frame, int per_frame) {
  EXPECT_EQ(r.rc, 0) << r.text;
  EXPECT_NE(r.text.find(label + "PAST the stable step's bound from the frame at t = 0.11"),
            std::string::npos)
      << r.text;
  EXPECT_NE(r.text.find("element evaluations past it); " + kMeaning), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("warning: past the stable step's bound of second-order geometry from t = "
                        "0.11"),
            std::string::npos)
      << r.text;
  const std::string bound = json_field(r.json, "geometry_bound");
  ASSERT_FALSE(bound.empty()) << r.json;
  EXPECT_EQ(json_number(bound, "elements"), 1) << bound;
  // Quasi-static: the pull reaches Q_max at 0.1138 s; the bar's ringing moves it by a few steps.
  const double first = json_number(bound, "first_frame");
  EXPECT_GE(first, 111) << bound;
  EXPECT_LE(first, 116) << bound;
  EXPECT_NEAR(json_number(bound, "first_time_s"), first * 1e-3, 1e-12) << bound;
  // At most every step from the first frame on, at least most of them (the pull only grows).
  const double evaluations = json_number(bound, "evaluations");
  EXPECT_LE(evaluations, (last_frame + 1 - first) * per_frame) << bound;
  EXPECT_GE(evaluations, 0.9 * (last_frame + 1 - first) * per_frame) << bound;
  EXPECT_EQ(json_field(r.json, "faults"), "[\"geometry_bound\"]") << r.json;
}

// A run inside the bound: it held, nothing flagged, no warning.
void expect_held(const Outcome& r, const std::string& label) {
  EXPECT_EQ(r.rc, 0) << r.text;
  EXPECT_NE(r.text.find(label +
                        "the stable step's bound held in the 1 element with second-order geometry"),
            std::string::npos)
      << r.text;
  EXPECT_EQ(r.text.find("warning"), std::string::npos) << r.text;
  EXPECT_EQ(json_field(r.json, "geometry_bound"),
            "{\"elements\": 1, \"evaluations\": 0, \"first_frame\": -1, \"first_time_s\": null}")
      << r.json;
  EXPECT_EQ(json_field(r.json, "faults"), "[]") << r.json;
}

TEST(GeometryBound, NtnRunSaysTheRunPassedIt) {
  const TempDir dir("geometry_bound_run");
  // 1200 steps of 1/6 ms: frames 0 to 199.
  expect_past(run(dir, "past", {NTN_RUN, kModel, "--duration", "0.2"}), "  geometry    ", 199, 6);
  expect_held(run(dir, "held", {NTN_RUN, kModel, "--duration", "0.1"}), "  geometry    ");
  // --quiet: the warning and the JSON still say it.
  const Outcome quiet = run(dir, "quiet", {NTN_RUN, kModel, "--duration", "0.2", "-q"});
  EXPECT_EQ(quiet.rc, 0) << quiet.text;
  EXPECT_EQ(quiet.text.find("  geometry"), std::string::npos) << quiet.text;
  EXPECT_NE(quiet.text.find("warning: past the stable step's bound"), std::string::npos)
      << quiet.text;
  EXPECT_EQ(json_field(quiet.json, "faults"), "[\"geometry_bound\"]") << quiet.json;
}

TEST(GeometryBound, NtnHilSaysTheRunPassedIt) {
  const TempDir dir("geometry_bound_hil");
  expect_past(run(dir, "past", {NTN_HIL, "run", kModel, "--clock", "virtual", "--frames", "200"}),
              "  geometry ", 199, 6);
  expect_held(run(dir, "held", {NTN_HIL, "run", kModel, "--clock", "virtual", "--frames", "100"}),
              "  geometry ");
}

}  // namespace
