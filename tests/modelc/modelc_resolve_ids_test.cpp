// Stage resolve_ids (tools/modelc/src/resolve_ids.cpp): indices by id with duplicates reported,
// time functions and curves concatenated, references resolved or reported.
#include <gtest/gtest.h>

#include <string>

#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_resolve_ids_test {

using testing::column;
using testing::Staged;

TEST(ModelcResolveIds, IndexesEveryKind) {
  Staged s{column(R"([[time_functions]]
id = "ramp"
points = [[0, 0], [1, 1]]

[[time_functions]]
id = "step"
points = [[0, 0], [0.5, 1], [2, 1]]

)")};
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  EXPECT_EQ(s.errors(), "");
  const Ids& ids = s.comp().ids;
  EXPECT_EQ(ids.materials.at("steel"), 0);
  EXPECT_EQ(ids.members.at("C"), 0);
  EXPECT_EQ(ids.nodes.at(2), 1);
  // Concatenated: "step" starts after ramp's 2 points.
  ASSERT_EQ(s.d().time_functions.size(), 2U);
  EXPECT_EQ(s.d().time_functions[1].first, 2);
  EXPECT_EQ(s.d().time_functions[1].count, 3);
  EXPECT_EQ(s.d().time_function_ids[1], "step");
  EXPECT_EQ(s.d().time_points[3].value, 1.0);
}

TEST(ModelcResolveIds, DuplicatesNameTheFirstLine) {
  Staged s{
      column("[[materials]]\nid = \"steel\"\nE = 1\nG = 1\nrho = 1\n\n[[nodes]]\nid = "
             "1\nxyz = [1, 0, 0]\n")};
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  const std::string e = s.errors();
  EXPECT_NE(
      e.find("key 'materials[1].id': duplicate material id 'steel' (first defined at line 5)"),
      std::string::npos)
      << e;
  EXPECT_NE(e.find("key 'nodes[2].id': duplicate node id 1 (first defined at line 18)"),
            std::string::npos)
      << e;
}

TEST(ModelcResolveIds, UnknownReferencesAreReportedWhereTheyAre) {
  Staged s{column("")};
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  Compilation& c = s.comp();
  EXPECT_EQ(c.node_ref(2, Where{}), 1);
  EXPECT_EQ(c.node_ref(7, Where{40, 3, "loads[0].node"}), -1);
  EXPECT_EQ(c.ref(c.ids.sections, IdAt{"t", Where{41, 12, "members[0].section"}}, "section"), -1);
  EXPECT_EQ(s.errors(),
            "m.toml:40:3: error: key 'loads[0].node': unknown node 7\n"
            "m.toml:41:12: error: key 'members[0].section': unknown section 't'\n");
}

}  // namespace modelc_resolve_ids_test
}  // namespace ntn::modelc::compile
