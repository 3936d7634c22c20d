// Hostile input on the model compiler: input refused before the TOML parser (size, nesting), the
// diagnostics cap, nodes connected to nothing, numbers beyond double named by their key, and the
// frame rule (ntn::frame_substeps) applied to the model. Each case failed on 8679e50: a crash
// (nesting), 1000 listed errors, no note, a misleading or no error, or "ok".
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/limits.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"

namespace modelc_limits_test {

using ntn::modelc::Diagnostic;
using ntn::modelc::load_model_from_string;
using ntn::modelc::LoadResult;

// A valid model: a 1 m cantilever of one member (1 m, S = 210 GPa steel, 0.01 m^2), fixed at 1.
std::string model(const std::string& model_extra = "", const std::string& material = "",
                  const std::string& section = "", const std::string& tail = "") {
  return "[model]\nname = \"m\"\n" + model_extra + "\n[[materials]]\nid = \"S\"\n" +
         (material.empty() ? "E = 210e9\nG = 81e9\nrho = 7850.0\n" : material) +
         "\n[[sections]]\nid = \"H\"\n" +
         (section.empty() ? "A = 1.0e-2\nIy = 1.0e-4\nIz = 5.0e-5\nJ = 1.0e-6\n" : section) +
         R"(
[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [1.0, 0.0, 0.0]

[[supports]]
node = 1
fix = "all"

[[members]]
id = "M1"
nodes = [1, 2]
material = "S"
section = "H"
)" + tail;
}

// The error with this key (the first), or a failure listing what came.
const Diagnostic* error_at(const LoadResult& r, const std::string& key) {
  const auto it = std::find_if(r.errors.begin(), r.errors.end(),
                               [&](const Diagnostic& d) { return d.key == key; });
  if (it == r.errors.end()) {
    ADD_FAILURE() << "no error at key '" << key << "'; got:\n" << ntn::modelc::format_all(r.errors);
    return nullptr;
  }
  return &*it;
}

void expect_error(const std::string& text, const std::string& key,
                  const std::vector<std::string>& fragments) {
  const LoadResult r = load_model_from_string(text, "t.toml");
  ASSERT_FALSE(r.ok()) << key;
  const Diagnostic* d = error_at(r, key);
  if (d == nullptr) return;
  for (const std::string& f : fragments)
    EXPECT_NE(d->message.find(f), std::string::npos) << "'" << f << "' not in: " << d->format();
  // Names and values, not consequences: no "inf" or "nan" as a word.
  const std::string t = d->format();
  for (const char* word : {"inf", "nan"}) {
    for (std::size_t at = t.find(word); at != std::string::npos; at = t.find(word, at + 1)) {
      const bool alone =
          (at == 0 || !std::isalpha(static_cast<unsigned char>(t[at - 1]))) &&
          (at + 3 >= t.size() || !std::isalpha(static_cast<unsigned char>(t[at + 3])));
      EXPECT_FALSE(alone) << t;
    }
  }
}

// ---- Size and nesting (item 1) ----------------------------------------------------------------

// 50 000 to 100 000 levels of a.a.a... (a 200 KB file) overflowed toml++'s stack (SIGSEGV in
// every tool). Now one error at the place where the limit is passed, before parsing.
TEST(ModelLimits, DeepDottedKeyIsRefusedBeforeParsing) {
  for (int levels : {33, 1000, 100000}) {
    std::string text = model() + "\n[x]\n";
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    for (int i = 0; i < levels; ++i)
      text += "a.";
    text += "a = 1\n";
    const LoadResult r = load_model_from_string(text, "deep.toml");
    ASSERT_EQ(r.errors.size(), 1U) << levels;
    const Diagnostic& d = r.errors[0];
    EXPECT_NE(d.message.find("nested deeper than 32 levels"), std::string::npos) << d.format();
    // [x] is level 1, the key's first part level 2: its 31st dot (column 62) starts level 33.
    EXPECT_EQ(d.line, line) << d.format();
    EXPECT_EQ(d.column, 62) << d.format();
  }
}

TEST(ModelLimits, DeepArraysAndInlineTablesAreRefused) {
  for (int levels : {40, 300, 100000}) {
    const std::string arrays = model() +
                               "\nq = " + std::string(static_cast<std::size_t>(levels), '[') +
                               std::string(static_cast<std::size_t>(levels), ']') + "\n";
    std::string tables = model() + "\nq = ";
    for (int i = 0; i < levels; ++i)
      tables += "{a=";
    tables += "1" + std::string(static_cast<std::size_t>(levels), '}') + "\n";
    for (const std::string& text : {arrays, tables}) {
      const LoadResult r = load_model_from_string(text, "deep.toml");
      ASSERT_EQ(r.errors.size(), 1U) << levels;
      EXPECT_NE(r.errors[0].message.find("nested deeper than 32"), std::string::npos)
          << r.errors[0].format();
    }
  }
}

// The scan's levels (limits.hpp): tables per header or key part, arrays and inline tables,
// strings and comments skipped.
TEST(ModelLimits, NestingScanCountsLevels) {
  using ntn::modelc::scan_nesting;
  EXPECT_EQ(scan_nesting("a = 1\n").depth, 1);
  EXPECT_EQ(scan_nesting("[m.d]\nx = [[1]]\n").depth, 5);
  EXPECT_EQ(scan_nesting("[[members]]\nrelease_start.rz.linear = 1e6\n").depth, 5);
  EXPECT_EQ(scan_nesting("[[members]]\nrelease_start = { rz = { linear = 1e6 } }\n").depth, 5);
  EXPECT_EQ(scan_nesting("a = \"[[[{{{a.b.c.d\" # [[[[ {{{ \nb = '[[[.'\n").depth, 1);
  EXPECT_EQ(scan_nesting("a = \"\"\"\n[[[[ \\\"\"\" ]]]]\n\"\"\"\nb = '''x.y.z\n[[[['''\n").depth,
            1);
  EXPECT_EQ(scan_nesting("\"a.b.c\".d = 1\n").depth, 2);
  EXPECT_EQ(scan_nesting("p = [\n  [1, 2],\n  [3, [4]],\n]\n").depth, 4);
  const ntn::modelc::NestingScan s = scan_nesting("x.y.z = 1\n", 2);
  EXPECT_EQ(s.line, 1);
  EXPECT_EQ(s.column, 4);  // the second dot starts level 3
  // The shipped models and every good fixture need at most 7 levels (a backbone's points in a
  // member-end release: good/backbone_portal.toml).
  for (const char* dir : {NTN_CONFIG_DIR, NTN_MODELC_GOOD_DIR}) {
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() != ".toml") continue;
      std::ifstream in(e.path(), std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      EXPECT_LE(scan_nesting(text).depth, 7) << e.path();
    }
  }
}

TEST(ModelLimits, OversizedFileIsRefusedWithoutReadingItAll) {
  const auto path = std::filesystem::temp_directory_path() / "ntn_modelc_oversized.toml";
  { std::ofstream f(path, std::ios::binary | std::ios::trunc); }
  std::filesystem::resize_file(path, ntn::modelc::kMaxModelFileBytes + 1);  // sparse: no disk
  const LoadResult r = ntn::modelc::load_model(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(r.errors.size(), 1U);
  EXPECT_FALSE(r.unreadable);
  EXPECT_NE(r.errors[0].message.find("a model file may have at most 67108864"), std::string::npos)
      << r.errors[0].format();
}

TEST(ModelLimits, UnreadableFilesAreSaidSo) {
  const LoadResult dir = ntn::modelc::load_model(NTN_CONFIG_DIR);
  EXPECT_TRUE(dir.unreadable);
  EXPECT_NE(dir.errors.at(0).message.find("it is a directory"), std::string::npos);
  const LoadResult missing = ntn::modelc::load_model(std::string(NTN_CONFIG_DIR) + "/no_such.toml");
  EXPECT_TRUE(missing.unreadable);
  EXPECT_EQ(missing.error_count, 1U);
}

// ---- The diagnostics cap and connected-to-nothing nodes ("Messages to make clear") -----------

// 1000 nodes connected to nothing: 50 errors listed and one note for the other 950 (a million
// printed 238 MB); the count of errors stays exact.
TEST(ModelDiagnostics, EachKindIsCappedAtFiftyWithASummary) {
  std::string tail;
  for (int i = 0; i < 1000; ++i)
    tail += "[[nodes]]\nid = " + std::to_string(100 + i) + "\nxyz = [" + std::to_string(i) +
            ".5, 3.0, 0.0]\n";
  const LoadResult r = load_model_from_string(model("", "", "", tail), "t.toml");
  EXPECT_EQ(r.error_count, 1000U);
  ASSERT_EQ(r.errors.size(), 51U);
  int notes = 0;
  for (const Diagnostic& d : r.errors) {
    if (d.severity != ntn::modelc::Severity::kNote) continue;
    ++notes;
    EXPECT_EQ(d.key, "nodes[].id");
    EXPECT_NE(d.message.find("... and 950 more errors of this kind"), std::string::npos)
        << d.format();
  }
  EXPECT_EQ(notes, 1);
  // Below the cap nothing changes.
  std::string few;
  for (int i = 0; i < 50; ++i)
    few += "[[nodes]]\nid = " + std::to_string(100 + i) + "\nxyz = [" + std::to_string(i) +
           ".5, 3.0, 0.0]\n";
  const LoadResult f = load_model_from_string(model("", "", "", few), "t.toml");
  EXPECT_EQ(f.errors.size(), 50U);
  EXPECT_EQ(f.error_count, 50U);
}

// A node at the same place as another, connected to nothing: a typo for that node. With a
// point mass it loads (a note); without mass the error says it too.
TEST(ModelDiagnostics, CoincidentLooseNodeIsNamed) {
  const std::string twin = "[[nodes]]\nid = 3\nxyz = [1.0, 0.0, 0.0]\n";
  const std::string mass = "[[point_masses]]\nnode = 3\nmass = 10.0\ninertia = [1.0, 1.0, 1.0]\n";
  const LoadResult with_mass = load_model_from_string(model("", "", "", twin + mass), "t.toml");
  ASSERT_TRUE(with_mass.ok()) << ntn::modelc::format_all(with_mass.errors);
  ASSERT_EQ(with_mass.notes.size(), 1U);
  EXPECT_EQ(with_mass.notes[0].key, "nodes[2].id");
  EXPECT_NE(with_mass.notes[0].message.find("node 3 moves on its own"), std::string::npos);
  EXPECT_NE(with_mass.notes[0].message.find("at the same place as node 2 (within 1e-9 m)"),
            std::string::npos)
      << with_mass.notes[0].format();
  expect_error(model("", "", "", twin), "nodes[2].id",
               {"node 3 has no mass", "at the same place as node 2"});
  // A loose node elsewhere gets no note.
  const LoadResult apart = load_model_from_string(
      model("", "", "", "[[nodes]]\nid = 3\nxyz = [5.0, 0.0, 0.0]\n" + mass), "t.toml");
  ASSERT_TRUE(apart.ok());
  EXPECT_TRUE(apart.notes.empty());
}

TEST(ModelDiagnostics, NamesWithControlCharactersAreRefused) {
  const std::string out =
      "[[outputs]]\nname = \"tip\\nforged: error\"\nkind = \"displacement\"\nnode = 2\ndof = "
      "\"uz\"\n";
  expect_error(model("", "", "", out), "outputs[0].name",
               {"must not contain control characters", "0x0A"});
}

// ---- Numbers beyond double (item 9) ------------------------------------------------------------

TEST(ModelNumbers, ExtremePropertiesNameTheirKeyAndValue) {
  // E = 1e308: 12 E I overflows; was "a spring acts on a DOF without mass" or silence.
  expect_error(model("", "E = 1e308\nG = 81e9\nrho = 7850.0\n"), "materials[0].E",
               {"E = 1e+308 Pa gives a non-finite bending stiffness"});
  expect_error(model("", "", "A = 1e308\nIy = 1.0e-4\nIz = 5.0e-5\nJ = 1.0e-6\n"), "sections[0].A",
               {"A = 1e+308 m^2 gives a non-finite axial stiffness E A / l"});
  // Subnormal rho: was "no mass ... connect it to a member".
  expect_error(model("", "E = 210e9\nG = 81e9\nrho = 1e-310\n"), "materials[0].rho",
               {"rho = 1e-310 kg/m^3 is too small", "end mass rho A l / 2"});
  // The default penalty stiffness 1e4 E A / l overflows for E A / l above 1.8e304.
  expect_error(model("", "E = 1e307\nG = 81e9\nrho = 7850.0\n",
                     "A = 0.1\nIy = 1.0e-4\nIz = 5.0e-5\nJ = 1.0e-6\n"),
               "materials[0].E",
               {"default penalty and limit stiffness", "give model.penalty_stiffness"});
  // Damping ratio x frequency beyond double.
  expect_error(model("[model.damping]\nratio = 1e300\nfrequency = 1e10\n"), "model.damping.ratio",
               {"gives alpha = 2 ratio (2 pi frequency) beyond the largest double"});
  // Gravity on the mass: M g beyond double.
  expect_error(
      model("gravity = [0.0, 0.0, -1e300]\n", "", "", "[[point_masses]]\nnode = 2\nmass = 1e10\n"),
      "model.gravity", {"|gravity| = 1e+300 m/s^2 gives a non-finite gravity force"});
  // A lone point mass that is subnormal.
  expect_error(model("", "", "",
                     "[[nodes]]\nid = 3\nxyz = [4.0, 0.0, 0.0]\n[[point_masses]]\nnode = 3\nmass = "
                     "1e-310\ninertia = [1e-310, 1e-310, 1e-310]\n"),
               "nodes[2].id", {"subnormal: too small to be a mass"});
}

// A hinge between the member's tip and a second member, with a spring and dashpot about ry.
std::string hinged(const std::string& behaviour, const std::string& model_extra = "") {
  return model(model_extra, "", "", R"(
[[nodes]]
id = 3
xyz = [1.0, 0.0, 0.0]

[[nodes]]
id = 4
xyz = [2.0, 0.0, 0.0]

[[members]]
id = "M2"
nodes = [3, 4]
material = "S"
section = "H"

[[hinges]]
id = "H1"
nodes = [3, 2]
ry = )" + behaviour + "\n");
}

TEST(ModelNumbers, HingeSpringsAndDashpotsBeyondDouble) {
  ASSERT_TRUE(load_model_from_string(hinged("{ linear = 1e6, dashpot = 10.0 }"), "t.toml").ok());
  // k = 1e308 was dropped from the stable step (NaN weights): the step stayed the elements'.
  expect_error(hinged("{ linear = 1e308 }"), "hinges[0].ry",
               {"linear = 1e+308 N m/rad gives a non-finite frequency^2 k (1/m1 + 1/m2) of hinge "
                "H1, direction ry"});
  // c = 1e300: a step of about 2 / (c w), far below any frame: refused by the frame rule,
  // naming the hinge that sets the step (it was dropped too: xi^2 overflowed).
  expect_error(
      hinged("{ linear = 0.0, dashpot = 1e300 }"), "model.dt",
      {"dt = \"auto\" needs", "more than the limit 1000000", "set by hinge H1, direction ry"});
}

// ---- The frame rule (item 10) ------------------------------------------------------------------

TEST(ModelFrames, StepsAndRatesThatCannotRunAreRefused) {
  expect_error(model("dt = 1e-300\n"), "model.dt",
               {"dt = 1e-300 s gives 1e+297 substeps in the frame period 0.001 s",
                "more than the limit 1000000"});
  expect_error(model("dt = 3e-6\n"), "model.dt",
               {"does not divide the frame period 0.001 s", "333.333"});
  expect_error(model("dt = 2e-3\nallow_unstable = true\n"), "model.dt",
               {"dt = 0.002 s is longer than the frame period 0.001 s"});
  expect_error(model("frame_rate = 1e-300\n"), "model.frame_rate",
               {"must be between 0.001 and 1e+06 Hz (got 1e-300 Hz)"});
  expect_error(model("frame_rate = 1e300\n"), "model.frame_rate", {"(got 1e+300 Hz)"});
  // alpha = 1e308: the step is 2 / alpha (it was "stable dt inf"), alpha counting in the step
  // (lagged; central: alpha drops out).
  expect_error(model("damping_velocity = \"lagged\"\n[model.damping]\nalpha = 1e308\n"), "model.dt",
               {"dt = \"auto\" needs", "the stable step is 2e-308 s"});
  // Nodes 1e-12 m apart: dt = 9.3e-30 s wanted 1e26 substeps ("check: ok").
  std::string close = model();
  close.replace(close.find("xyz = [1.0, 0.0, 0.0]"), 21, "xyz = [1e-12, 0.0, 0.0]");
  expect_error(close, "model.dt", {"dt = \"auto\" needs", "substeps", "set by member M1"});
}

// A model that loads runs: its step passes the kernel's rule, and `info` prints its count.
TEST(ModelFrames, LoadedModelsPassTheRuleAndInfoPrintsTheCount) {
  for (const char* name : {"frame3d.toml", "cantilever.toml", "hinged_beam.toml"}) {
    const LoadResult r = ntn::modelc::load_model(std::string(NTN_CONFIG_DIR) + "/" + name);
    ASSERT_TRUE(r.ok()) << name;
    const ntn::Substeps n =
        ntn::frame_substeps(r.model->settings.dt, r.model->settings.frame_period);
    ASSERT_TRUE(n.ok()) << name;
    const std::string info = ntn::modelc::info_text(*r.model);
    EXPECT_NE(info.find("substeps     " + std::to_string(n.count) + " per frame"),
              std::string::npos)
        << info;
  }
  // dt = 1e-5 with 100 Hz frames: 1000 substeps.
  const LoadResult r = load_model_from_string(model("dt = 1e-5\nframe_rate = 100.0\n"), "t.toml");
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  EXPECT_NE(ntn::modelc::info_text(*r.model).find("substeps     1000 per frame of 10 ms (100 Hz)"),
            std::string::npos);
}

// `info` prints numbers with %g: a point mass of 1e300 kg was printed with %.1f, 301 digits.
TEST(ModelFrames, InfoHasNoRunawayNumbers) {
  const LoadResult r = load_model_from_string(
      model("gravity = [0.0, 0.0, -9.81]\n", "", "", "[[point_masses]]\nnode = 2\nmass = 1e300\n"),
      "t.toml");
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  const std::string info = ntn::modelc::info_text(*r.model);
  int run = 0, longest = 0;
  for (char c : info) {
    run = (c >= '0' && c <= '9') ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  EXPECT_LE(longest, 17) << info;
}

}  // namespace modelc_limits_test
