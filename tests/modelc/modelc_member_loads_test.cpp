// [[member_loads]] and points inside members ({ member, at / at_m } for a node id): every error
// with its file:line:column and key, the note of an empty load, and what the stages make
// (collect_member_points, mesh_members, add_member_loads). Each error's place is found in the
// model text itself (the value or table it names), not written down.
#include <gtest/gtest.h>

#include <string>

#include "ntn/modelc/load_model.hpp"
#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_member_loads_test {

using testing::column;
using testing::kColumn;

// "line:column" of the first `needle` after the fixture column (kColumn).
std::string place_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle, kColumn.size());
  EXPECT_NE(at, std::string::npos) << needle;
  int line = 1;
  std::size_t start = 0;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') ++line, start = i + 1;
  }
  return std::to_string(line) + ":" + std::to_string(at - start + 1);
}

// All errors of the whole compiler on `more` appended to the column.
std::string errors_of(const std::string& text) {
  const auto r = load_model_from_string(text, "m.toml");
  return format_all(r.errors);
}

struct Case {
  const char* name;
  const char* more;    // appended to the column (member C, 3 m, 3 divisions)
  const char* needle;  // where the error is
  const char* key;
  const char* message;
};

// clang-format off
const Case kCases[] = {
  {"UnknownMember", "[[member_loads]]\nmember = \"X\"\nq = [1, 0, 0]\n", "\"X\"", "member_loads[0].member", "unknown member 'X'"},
  {"UnknownFunction", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfunction = \"nope\"\n", "\"nope\"", "member_loads[0].function", "unknown time function 'nope'"},
  {"QAndQStart", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nq_start = [1, 0, 0]\nq_end = [1, 0, 0]\n", "[1, 0, 0]\nq_end", "member_loads[0].q_start", "cannot be given together with 'q'"},
  {"MissingQEnd", "[[member_loads]]\nmember = \"C\"\nq_start = [1, 0, 0]\n", "[[member_loads]]", "member_loads[0].q_end", "missing required key 'q_end' (a linearly varying load needs both q_start and q_end)"},
  {"MissingQ", "[[member_loads]]\nmember = \"C\"\n", "[[member_loads]]", "member_loads[0].q", "missing required key 'q' (or q_start and q_end for a linearly varying load)"},
  {"FromNotBeforeTo", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfrom = 0.6\nto = 0.4\n", "0.4", "member_loads[0].to", "from = 0.6 must be less than to = 0.4"},
  {"FromOutside", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfrom = -0.1\n", "-0.1", "member_loads[0].from", "must be between 0 and 1 (a fraction of the member's length; got -0.1)"},
  {"ToOutside", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nto = 1.5\n", "1.5", "member_loads[0].to", "must be between 0 and 1 (a fraction of the member's length; got 1.5)"},
  {"ToMBeyondLength", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfrom_m = 1\nto_m = 4\n", "4\n", "member_loads[0].to_m", "must be between 0 and the length of member C, L = 3 m (got 4 m)"},
  {"FromMAtEnd", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfrom_m = 3\n", "3\n", "member_loads[0].from_m", "from_m = 3 must be less than to_m = 3 m (the member's length when to_m is not given)"},
  {"FromMNegative", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfrom_m = -1\n", "-1", "member_loads[0].from_m", "must be between 0 and the member's length (got -1 m)"},
  {"MixFromAndToM", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\nfrom = 0.1\nto_m = 2\n", "2\n", "member_loads[0].to_m", "cannot be given together with 'from'"},
  {"NonFinite", "[[member_loads]]\nmember = \"C\"\nq = [0, nan, 0]\n", "nan", "member_loads[0].q[1]", "must be a finite number"},
  {"BadAxes", "[[member_loads]]\nmember = \"C\"\nq = [1, 0, 0]\naxes = \"local\"\n", "\"local\"", "member_loads[0].axes", "must be one of \"global\", \"member\" (got \"local\")"},
  {"PointUnknownMember", "[[supports]]\nnode = { member = \"X\", at = 0.5 }\nfix = \"all\"\n", "\"X\"", "supports[1].node.member", "unknown member 'X'"},
  {"PointAtOutside", "[[point_masses]]\nnode = { member = \"C\", at = 1.5 }\nmass = 1\n", "1.5", "point_masses[0].node.at", "must be between 0 and 1 (a fraction of the member's length; got 1.5)"},
  {"PointAtMBeyondLength", "[[loads]]\nnode = { member = \"C\", at_m = 5 }\ndof = \"ux\"\nvalue = 1\n", "5 }", "loads[0].node.at_m", "must be between 0 and the length of member C, L = 3 m (got 5 m)"},
  {"PointAtAndAtM", "[[loads]]\nnode = { member = \"C\", at = 0.5, at_m = 1 }\ndof = \"ux\"\nvalue = 1\n", "1 }", "loads[0].node.at_m", "cannot be given together with 'at'"},
  {"PointOtherKey", "[[outputs]]\nname = \"u\"\nkind = \"displacement\"\nnode = { member = \"C\", at = 0.5, x = 1 }\ndof = \"ux\"\n", "x = 1", "outputs[0].node.x", "unknown key 'x' (this table takes: member, at, at_m)"},
  {"PointNoAt", "[[outputs]]\nname = \"u\"\nkind = \"displacement\"\nnode = { member = \"C\" }\ndof = \"ux\"\n", "{ member", "outputs[0].node", "a point inside a member needs 'at' (a fraction of the length, 0 to 1) or 'at_m' (metres from the member's start)"},
  {"PointNotATable", "[[outputs]]\nname = \"d\"\nkind = \"drift\"\nnodes = [1, \"C\"]\ndirection = \"x\"\n", "\"C\"]", "outputs[0].nodes[1]", "expected a node id or a point inside a member ({ member = \"B1\", at = 0.5 } or { member = \"B1\", at_m = 2.0 }), got a string"},
};
// clang-format on

class MemberLoadError : public ::testing::TestWithParam<Case> {};

TEST_P(MemberLoadError, GivesExactlyItsError) {
  const Case& c = GetParam();
  const std::string text = column(c.more);
  EXPECT_EQ(errors_of(text), "m.toml:" + place_of(text, c.needle) + ": error: key '" + c.key +
                                 "': " + c.message + "\n");
}

INSTANTIATE_TEST_SUITE_P(MemberLoads, MemberLoadError, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& p) {
                           return std::string(p.param.name);
                         });

// An all-zero load is not an error: a note at its member key, and no nodal loads.
TEST(MemberLoads, ZeroLoadIsANote) {
  const std::string text = column("[[member_loads]]\nmember = \"C\"\nq = [0, 0, 0]\n");
  const auto r = load_model_from_string(text, "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  EXPECT_EQ(format_all(r.notes), "m.toml:" + place_of(text, "\"C\"\nq") +
                                     ": note: key 'member_loads[0].member': the load is zero "
                                     "everywhere: it adds no forces\n");
  EXPECT_TRUE(r.model->loads.empty());
}

// Several member loads on one member add up; the time function is on every nodal load; a load
// on part of the member touches only the elements it overlaps (the column's 3 elements of 1 m:
// [0.5, 1] m lies in the first, whose nodes are the base and the first interior node).
TEST(MemberLoads, StageMakesNodalLoadsOfOverlappedElements) {
  testing::Staged s{column(R"([[time_functions]]
id = "ramp"
points = [[0, 0], [1, 1]]

[[member_loads]]
member = "C"
q = [100, 0, 0]
from_m = 0.5
to_m = 1.0
function = "ramp"

[[member_loads]]
member = "C"
q = [100, 0, 0]
)")};
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
  EXPECT_EQ(s.errors(), "");
  const auto& d = s.d();
  ASSERT_EQ(d.member_loads.size(), 2U);
  const auto& first = d.member_loads[0];
  EXPECT_EQ(first.total[0], 50.0);  // 100 N/m over 0.5 m
  for (int k = first.first_load; k < first.first_load + first.load_count; ++k) {
    const LoadSpec& l = d.loads[static_cast<std::size_t>(k)];
    EXPECT_EQ(l.time_function, 0);
    EXPECT_TRUE(l.node == 0 || l.node == d.members[0].first_interior_node) << l.node;
  }
  EXPECT_EQ(d.member_loads[1].total[0], 300.0);
  EXPECT_NEAR(d.member_loads[1].nodal[0], 300.0, 1e-12 * 300);  // round-off of 3 elements
  EXPECT_EQ(d.member_loads[1].first_load, first.first_load + first.load_count);
  EXPECT_EQ(s.comp().load_at.size(), d.loads.size());
}

// A drift between the column's base and its midpoint (a member point splitting the middle
// element of 3), and a node output at a release's end: the point at the member's end is the
// joint, not the release node.
TEST(MemberLoads, PointsInDriftAndAtReleasedEnd) {
  std::string text = column(R"([[outputs]]
name = "d"
kind = "drift"
nodes = [1, { member = "C", at = 0.5 }]
direction = "x"

[[outputs]]
name = "top"
kind = "displacement"
node = { member = "C", at = 1 }
dof = "ux"
)");
  text.replace(text.find("divisions = 3"), 13, "divisions = 3\nrelease_end = [\"ry\"]");
  testing::Staged s{text};
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
  EXPECT_EQ(s.errors(), "");
  const auto& d = s.d();
  ASSERT_EQ(d.outputs.size(), 2U);
  EXPECT_EQ(d.nodes[static_cast<std::size_t>(d.outputs[0].node2)].z, 1.5);
  EXPECT_EQ(d.outputs[0].scale, 1.0 / 1.5);
  EXPECT_EQ(d.outputs[1].node, d.members[0].end_node);
  EXPECT_EQ(d.members[0].element_count, 4);
}

// At a released end the end element's node is the release node (on the member's side of the
// hinge): the member load's forces go there, none to the joint.
TEST(MemberLoads, ReleasedEndLoadsTheReleaseNode) {
  std::string text = column("[[member_loads]]\nmember = \"C\"\nq = [100, 0, 0]\n");
  text.replace(text.find("divisions = 3"), 13, "divisions = 3\nrelease_end = [\"ry\"]");
  testing::Staged s{text};
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
  EXPECT_EQ(s.errors(), "");
  const auto& d = s.d();
  bool on_release = false;
  for (const LoadSpec& l : d.loads) {
    EXPECT_NE(l.node, d.members[0].end_node);
    on_release = on_release || l.node == d.members[0].end_release_node;
  }
  EXPECT_TRUE(on_release);
}

}  // namespace modelc_member_loads_test
}  // namespace ntn::modelc::compile
