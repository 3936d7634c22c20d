// The reader (tools/modelc/src/read_model.cpp): text -> SourceModel with the place of every
// value; the size and nesting limits before the parser; every table's problems reported.
#include <gtest/gtest.h>

#include <string>

#include "ntn/modelc/limits.hpp"
#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_reader_test {

using testing::column;
using testing::kColumn;
using testing::Staged;

TEST(ModelcReader, KeepsThePlaceOfEveryValue) {
  Staged s{std::string(kColumn)};
  ASSERT_TRUE(s.read()) << s.errors();
  const SourceModel& p = s.source();
  ASSERT_EQ(p.nodes.size(), 2U);
  // node 2's id is line 22 ("id = 2"), its value at column 6.
  EXPECT_EQ(p.nodes[1].id, 2);
  EXPECT_EQ(p.nodes[1].at.line, 22);
  EXPECT_EQ(p.nodes[1].at.column, 6);
  EXPECT_EQ(p.nodes[1].at.key, "nodes[1].id");
  ASSERT_EQ(p.members.size(), 1U);
  EXPECT_EQ(p.members[0].nodes_at.key, "members[0].nodes");
  EXPECT_EQ(p.members[0].nodes_at.line, 27);
  EXPECT_EQ(p.members[0].divisions, 3);
  EXPECT_EQ(p.members[0].material.id, "steel");
}

TEST(ModelcReader, DerivesGFromNuAndPointsAtE) {
  Staged s{std::string(kColumn)};
  ASSERT_TRUE(s.read()) << s.errors();
  const Material& m = s.source().materials[0];
  EXPECT_EQ(m.G, 2.1e11 / (2.0 * (1.0 + 0.3)));  // the same expression: exact
  EXPECT_EQ(m.G_at.line, m.E_at.line);
  EXPECT_EQ(m.G_at.key, "materials[0].E");
}

TEST(ModelcReader, ReportsEveryTableAndMakesNoModel) {
  // Two problems in two tables: both reported, no SourceModel.
  Staged s{
      column("[[nodes]]\nid = -1\nxyz = [0, 0, 1]\n\n[[point_masses]]\nnode = 2\nmass = -5\n")};
  EXPECT_FALSE(s.read());
  const std::string e = s.errors();
  EXPECT_NE(e.find("key 'nodes[2].id': must be at least 0 (got -1)"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'point_masses[0].mass': must not be negative (got -5)"), std::string::npos)
      << e;
}

TEST(ModelcReader, LimitsComeBeforeTheParser) {
  // Nested deeper than kMaxNesting and not valid TOML either: the limit is the one error.
  std::string text = "a = ";
  for (int i = 0; i <= kMaxNesting; ++i)
    text += "[";
  Staged s{text};
  EXPECT_FALSE(s.read());
  EXPECT_EQ(s.sink().error_count(), 1U);
  const std::string e = s.errors();
  EXPECT_NE(e.find("error: nested deeper than 32 levels"), std::string::npos) << e;
  EXPECT_EQ(e.find("TOML syntax"), std::string::npos) << e;
}

TEST(ModelcReader, SyntaxErrorsAtTheirPlace) {
  Staged s{"[model]\nname = \n"};
  EXPECT_FALSE(s.read());
  const std::string e = s.errors();
  EXPECT_EQ(e.rfind("m.toml:2:", 0), 0U) << e;
  EXPECT_NE(e.find("error: TOML syntax: "), std::string::npos) << e;
}

TEST(ModelcReader, HingeAxesMustBeARotation) {
  // A support frame with a left-handed z row: the axes check (read_axes) refuses it.
  Staged s{
      column("[[supports]]\nnode = 2\nfix = [\"ux\"]\naxes = [[1, 0, 0], [0, 1, 0], [0, 0, "
             "-1]]\n")};
  EXPECT_FALSE(s.read());
  const std::string e = s.errors();
  EXPECT_NE(e.find("key 'supports[1].axes': axes must be right-handed (z = x cross y); these "
                   "have det = -1"),
            std::string::npos)
      << e;
}

}  // namespace modelc_reader_test
}  // namespace ntn::modelc::compile
