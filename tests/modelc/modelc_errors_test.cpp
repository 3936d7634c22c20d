// One test per error message of the model compiler: each bad model under tests/modelc/bad/
// must give its errors at the exact line and column, with the key and the message.
// The positions were checked by hand against the fixture text (the value, key or table header
// they name); the table below is the specification.
#include <gtest/gtest.h>

#include <ostream>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "ntn/modelc/load_model.hpp"

namespace {

using ntn::modelc::Diagnostic;
using ntn::modelc::load_model;

std::string bad(const std::string& name) {
  return std::string(NTN_MODELC_BAD_DIR) + "/" + name;
}

struct Expected {
  const char* test;  // test name
  const char* file;  // fixture under bad/
  int line, column;
  const char* key;
  const char* fragment;  // part of the message
};

// clang-format off
const Expected kExpected[] = {
  {"SyntaxError", "syntax.toml", 5, 2, "", "TOML syntax: Error while parsing array: encountered end-of-file"},
  // Unknown key, in every kind of table, pointing at the key itself.
  {"UnknownKeyRoot", "unknown_key.toml", 2, 1, "colour", "unknown key 'colour' (this table takes: model, materials"},
  {"UnknownKeyModel", "unknown_key.toml", 6, 1, "model.speed", "unknown key 'speed'"},
  {"UnknownKeyDamping", "unknown_key.toml", 11, 1, "model.damping.zeta", "unknown key 'zeta' (this table takes: alpha, ratio, frequency)"},
  {"UnknownKeyMaterial", "unknown_key.toml", 18, 1, "materials[0].yield", "unknown key 'yield' (this table takes: id, E, G, nu, rho)"},
  {"UnknownKeySection", "unknown_key.toml", 26, 1, "sections[0].Wy", "unknown key 'Wy'"},
  {"UnknownKeyNode", "unknown_key.toml", 31, 1, "nodes[0].label", "unknown key 'label' (this table takes: id, xyz)"},
  {"UnknownKeyMember", "unknown_key.toml", 42, 1, "members[0].hinge", "unknown key 'hinge'"},
  {"UnknownKeySupport", "unknown_key.toml", 47, 1, "supports[0].spring", "unknown key 'spring' (this table takes: node, fix)"},
  {"UnknownKeyPointMass", "unknown_key.toml", 52, 1, "point_masses[0].weight", "unknown key 'weight'"},
  {"UnknownKeyTimeFunction", "unknown_key.toml", 57, 1, "time_functions[0].kind", "unknown key 'kind' (this table takes: id, points)"},
  {"UnknownKeyLoad", "unknown_key.toml", 63, 1, "loads[0].factor", "unknown key 'factor'"},
  {"UnknownKeyGroundInput", "unknown_key.toml", 69, 1, "inputs[0].node", "unknown key 'node' (this table takes: name, kind, direction, units, min, max)"},
  {"UnknownKeyForceInput", "unknown_key.toml", 76, 1, "inputs[1].units", "unknown key 'units' (this table takes: name, kind, node, dof, scale, min, max)"},
  {"UnknownKeyNodeOutput", "unknown_key.toml", 83, 1, "outputs[0].units", "unknown key 'units' (this table takes: name, kind, node, dof)"},
  {"UnknownKeyForceOutput", "unknown_key.toml", 91, 1, "outputs[1].node", "unknown key 'node' (this table takes: name, kind, member, end, component)"},
  {"UnknownKeyDriftOutput", "unknown_key.toml", 98, 1, "outputs[2].height", "unknown key 'height' (this table takes: name, kind, nodes, direction)"},
  {"UnknownKeyReactionOutput", "unknown_key.toml", 104, 1, "outputs[3].node", "unknown key 'node' (this table takes: name, kind, direction)"},
  // Missing required key or table: at the table's header.
  {"MissingKey", "missing_key.toml", 5, 1, "materials[0].E", "missing required key 'E'"},
  {"MissingLoadDof", "load_missing_dof.toml", 36, 1, "loads[0].dof", "missing required key 'dof' (or give force = [Fx, Fy, Fz, Mx, My, Mz])"},
  {"MissingModelTable", "missing_model.toml", 1, 1, "model", "missing required table [model]"},
  // Wrong types.
  {"WrongTypeBoolean", "wrong_type.toml", 4, 18, "model.rotary_inertia", "expected a boolean, got a string"},
  {"WrongTypeString", "wrong_type.toml", 7, 6, "materials[0].id", "expected a string, got an integer"},
  {"WrongTypeNumber", "wrong_type.toml", 8, 5, "materials[0].E", "expected a number, got a string"},
  {"WrongTypeInteger", "wrong_type.toml", 20, 6, "nodes[0].id", "expected an integer, got a floating-point number"},
  {"WrongTypeArray", "wrong_type.toml", 25, 7, "nodes[1].xyz", "expected an array of 3 values, got a string"},
  {"WrongArrayLength", "wrong_type.toml", 29, 9, "members[0].nodes", "expected 2 values, got 3"},
  {"WrongArrayLengthXyz", "array_length.toml", 20, 7, "nodes[0].xyz", "expected 3 values, got 2"},
  {"WrongTypeArrayOfTables", "wrong_table_type.toml", 2, 13, "materials", "expected an array of tables ([[materials]]), got an integer"},
  {"WrongTypeTableItem0", "wrong_table_type.toml", 3, 10, "nodes[0]", "expected a table, got an integer"},
  {"WrongTypeTableItem1", "wrong_table_type.toml", 3, 13, "nodes[1]", "expected a table, got an integer"},
  {"WrongTypeDampingTable", "wrong_table_type.toml", 7, 11, "model.damping", "expected a table ([model.damping]), got a floating-point number"},
  {"WrongTypeModelTable", "model_not_table.toml", 2, 9, "model", "expected a table ([model]), got a string"},
  // Values out of range.
  {"NonFinite", "non_finite.toml", 7, 5, "materials[0].E", "must be a finite number"},
  {"NonPositiveE", "non_positive.toml", 7, 5, "materials[0].E", "must be positive (got -2.1e+11)"},
  {"NonPositiveG", "non_positive.toml", 8, 5, "materials[0].G", "must be positive (got 0)"},
  {"NonPositiveRho", "non_positive.toml", 9, 7, "materials[0].rho", "must be positive (got -7850)"},
  {"NonPositiveA", "non_positive.toml", 13, 5, "sections[0].A", "must be positive (got 0)"},
  {"NonPositiveIy", "non_positive.toml", 14, 6, "sections[0].Iy", "must be positive (got -0.0001)"},
  {"NonPositiveIz", "non_positive.toml", 15, 6, "sections[0].Iz", "must be positive (got 0)"},
  {"NonPositiveJ", "non_positive.toml", 16, 5, "sections[0].J", "must be positive (got -1e-06)"},
  {"Negative", "negative.toml", 38, 8, "point_masses[0].mass", "must not be negative (got -10)"},
  {"DivisionsBelowOne", "divisions.toml", 35, 13, "members[0].divisions", "must be at least 1 (got 0)"},
  {"DivisionsTooMany", "divisions.toml", 42, 13, "members[1].divisions", "must be at most 1000000 (got 2000000)"},
  {"NuRange", "nu_range.toml", 8, 6, "materials[0].nu", "must be greater than -1 and less than 0.5 (got 0.7)"},
  {"BadChoice", "bad_choice.toml", 38, 7, "loads[0].dof", "must be one of \"ux\", \"uy\", \"uz\", \"rx\", \"ry\", \"rz\" (got \"uw\")"},
  {"BadFix", "bad_fix.toml", 34, 7, "supports[0].fix", "must be \"all\", \"pinned\" or an array of DOF names"},
  {"BadModelName", "bad_name.toml", 3, 8, "model.name", "must be a C++ identifier"},
  {"DtString", "dt_string.toml", 4, 6, "model.dt", "must be \"auto\" or a number of seconds (got \"fast\")"},
  {"InputRange", "input_range.toml", 41, 7, "inputs[0].min", "min = 2 must be less than max = -2"},
  // Keys that exclude or need each other.
  {"Conflict", "conflict.toml", 9, 6, "materials[0].nu", "cannot be given together with 'G'"},
  {"KappaWithoutTimoshenko", "kappa_without_timoshenko.toml", 17, 11, "sections[0].kappa_y", "only applies with shear = \"timoshenko\""},
  {"FrequencyWithAlpha", "damping_alpha_frequency.toml", 7, 13, "model.damping.frequency", "only applies with 'ratio'"},
  // Time functions.
  {"TimeFunctionEmpty", "time_function_empty.toml", 38, 10, "time_functions[0].points", "expected an array of [t, value] points (at least one), got an empty array"},
  {"TimeFunctionNotIncreasing", "time_function_order.toml", 38, 35, "time_functions[0].points[2]", "t = 1 s does not come after the previous point's t = 1 s: times must increase strictly"},
  // References.
  {"UnknownTimeFunction", "unknown_reference.toml", 5, 20, "model.gravity_function", "unknown time function 'quake'"},
  {"UnknownMaterial", "unknown_reference.toml", 31, 12, "members[0].material", "unknown material 'S235'"},
  {"UnknownSection", "unknown_reference.toml", 38, 11, "members[1].section", "unknown section 'IPE999'"},
  {"UnknownNode", "unknown_reference.toml", 43, 9, "members[2].nodes", "unknown node 7"},
  {"UnknownMember", "unknown_reference.toml", 54, 10, "outputs[0].member", "unknown member 'B9'"},
  // Duplicates, at the repeated id.
  {"DuplicateMaterial", "duplicate.toml", 12, 6, "materials[1].id", "duplicate material id 'S' (first defined at line 6)"},
  {"DuplicateSection", "duplicate.toml", 25, 6, "sections[1].id", "duplicate section id 'H' (first defined at line 18)"},
  {"DuplicateNode", "duplicate.toml", 40, 6, "nodes[2].id", "duplicate node id 2 (first defined at line 36)"},
  {"DuplicateMember", "duplicate.toml", 50, 6, "members[1].id", "duplicate member id 'M1' (first defined at line 44)"},
  {"DuplicateTimeFunction", "duplicate.toml", 64, 6, "time_functions[1].id", "duplicate time function id 'ramp' (first defined at line 60)"},
  {"DuplicateInput", "duplicate.toml", 73, 8, "inputs[1].name", "duplicate input name 'ag' (first defined at line 68)"},
  {"DuplicateOutput", "duplicate.toml", 84, 8, "outputs[1].name", "duplicate output name 'tip' (first defined at line 78)"},
  {"DuplicateSupport", "duplicate_support.toml", 37, 8, "supports[1].node", "node 1 already has a support (line 33)"},
  // Geometry.
  {"ZeroLength", "zero_length.toml", 28, 9, "members[0].nodes", "member M1 has zero length: nodes 1 and 2 are both at (0, 0, 3.5)"},
  {"OrientationParallel", "orientation_parallel.toml", 31, 15, "members[0].orientation", "orientation (2, 0, 0) is parallel to the axis of member M1"},
  {"DriftZeroHeight", "drift_zero_height.toml", 39, 9, "outputs[0].nodes", "drift height is zero: nodes 1 and 2 are both at z = 0 m"},
  {"DriftUpsideDown", "drift_upside_down.toml", 39, 9, "outputs[0].nodes", "the upper node 1 (z = 0 m) is below the lower node 2 (z = 3.5 m)"},
  {"ReactionUnsupported", "reaction_unsupported.toml", 43, 13, "outputs[0].direction", "no support holds DOF rz, so this reaction is always zero"},
  // Mass and time step.
  {"NoMembers", "no_members.toml", 1, 1, "members", "the model has no members, so it has no mass"},
  {"MasslessFreeDof", "massless_dof.toml", 27, 6, "nodes[2].id", "node 3 has no mass in its free DOFs rx, ry, rz"},
  {"DtAboveStable", "dt_unstable.toml", 4, 6, "model.dt", "dt = 0.001 s is above the stable step "},
};
// clang-format on

// Names the case in test listings (CTest shows gtest's parameter printout otherwise).
inline void PrintTo(const Expected& c, std::ostream* os) {
  *os << c.test;
}

class ModelError : public ::testing::TestWithParam<Expected> {};

TEST_P(ModelError, ReportedAtItsPlace) {
  const Expected& e = GetParam();
  const auto r = load_model(bad(e.file));
  ASSERT_FALSE(r.ok());
  const auto it = std::find_if(r.errors.begin(), r.errors.end(), [&](const Diagnostic& d) {
    return d.line == e.line && d.column == e.column && d.key == e.key;
  });
  ASSERT_NE(it, r.errors.end()) << "no error at " << e.line << ":" << e.column << " key '" << e.key
                                << "'; got:\n"
                                << ntn::modelc::format_all(r.errors);
  EXPECT_NE(it->message.find(e.fragment), std::string::npos)
      << "message: " << it->message << "\nwanted: " << e.fragment;
  EXPECT_EQ(it->file, bad(e.file));
}

INSTANTIATE_TEST_SUITE_P(BadModels, ModelError, ::testing::ValuesIn(kExpected),
                         [](const ::testing::TestParamInfo<Expected>& p) {
                           return std::string(p.param.test);
                         });

// Every fixture gives exactly the errors listed for it, and every fixture is listed: no
// unexpected extra errors, no fixture left untested.
TEST(ModelErrors, EachFixtureGivesExactlyItsListedErrors) {
  std::map<std::string, int> listed;
  for (const Expected& e : kExpected)
    ++listed[e.file];
  int fixtures = 0;
  for (const auto& entry : std::filesystem::directory_iterator(NTN_MODELC_BAD_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++fixtures;
    const std::string name = entry.path().filename().string();
    const auto r = load_model(entry.path().string());
    EXPECT_EQ(static_cast<int>(r.errors.size()), listed[name]) << name << ":\n"
                                                               << ntn::modelc::format_all(r.errors);
  }
  EXPECT_EQ(fixtures, static_cast<int>(listed.size()));
}

// The dt message names the governing member and element and the kernel's stable step: the same
// file with dt = "auto" gives the stable step that the message must quote.
TEST(ModelErrors, DtAboveStableNamesGoverningElementAndStableStep) {
  const auto r = load_model(bad("dt_unstable.toml"));
  ASSERT_EQ(r.errors.size(), 1U);
  std::string text;
  {
    std::FILE* f = std::fopen(bad("dt_unstable.toml").c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
      text.append(buf, n);
    std::fclose(f);
  }
  const auto pos = text.find("dt = 1.0e-3");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 11, "dt = \"auto\"");
  const auto ok = ntn::modelc::load_model_from_string(text, "auto.toml");
  ASSERT_TRUE(ok.ok()) << ntn::modelc::format_all(ok.errors);
  char stable[64];
  std::snprintf(stable, sizeof stable, "%.6g s", ok.model->stable.dt_stable);
  const std::string& msg = r.errors[0].message;
  EXPECT_NE(msg.find(std::string("above the stable step ") + stable), std::string::npos) << msg;
  // C1 (2 m, 4 elements of 0.5 m) governs over M1 (one 1 m element); its elements are equal, so
  // the first of them is reported.
  const int gov = ok.model->stable.governing_element;
  EXPECT_EQ(ok.model
                ->members[static_cast<std::size_t>(
                    ok.model->element_member[static_cast<std::size_t>(gov)])]
                .name,
            "C1");
  EXPECT_NE(msg.find("set by member C1, element 1 of 4 (model element 1)"), std::string::npos)
      << msg;
}

TEST(ModelErrors, MissingFile) {
  const auto r = load_model(bad("no_such_file.toml"));
  ASSERT_EQ(r.errors.size(), 1U);
  EXPECT_EQ(r.errors[0].line, 1);
  EXPECT_EQ(r.errors[0].column, 1);
  EXPECT_EQ(r.errors[0].message, "cannot open the model file");
}

TEST(ModelErrors, DiagnosticFormat) {
  const Diagnostic d{"m.toml", 7, 5, "materials[0].E", "must be positive (got 0)"};
  EXPECT_EQ(d.format(), "m.toml:7:5: error: key 'materials[0].E': must be positive (got 0)");
  const Diagnostic s{"m.toml", 5, 2, "", "TOML syntax: x"};
  EXPECT_EQ(s.format(), "m.toml:5:2: error: TOML syntax: x");
}

// Errors come sorted by position, whatever order the tables were read in.
TEST(ModelErrors, SortedByPosition) {
  const auto r = load_model(bad("unknown_key.toml"));
  ASSERT_GT(r.errors.size(), 2U);
  EXPECT_TRUE(std::is_sorted(r.errors.begin(), r.errors.end(), [](const auto& a, const auto& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  }));
}

}  // namespace
