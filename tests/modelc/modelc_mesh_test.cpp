// Stage mesh_members (tools/modelc/src/mesh_members.cpp): nodes, elements, orientation vectors
// and the nodes of member-end releases.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_mesh_test {

using testing::column;
using testing::Staged;

void mesh(Staged& s) {
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  mesh_members(s.comp());
}

TEST(ModelcMesh, DivisionsMakeEqualElementsAndInteriorNodes) {
  Staged s{column("")};
  mesh(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  ASSERT_EQ(d.elements.size(), 3U);
  ASSERT_EQ(d.nodes.size(), 4U);  // 2 user nodes, then 2 interior ones
  EXPECT_EQ(d.node_ids[2], kGeneratedNode);
  EXPECT_EQ(d.nodes[2].z, 0.0 + (1.0 / 3.0) * 3.0);  // x_a + (k / N)(x_b - x_a), as computed
  EXPECT_EQ(d.nodes[3].z, 0.0 + (2.0 / 3.0) * 3.0);
  EXPECT_EQ(d.elements[0].node_i, 0);
  EXPECT_EQ(d.elements[0].node_j, 2);
  EXPECT_EQ(d.elements[2].node_j, 1);
  ASSERT_EQ(d.members.size(), 1U);
  EXPECT_EQ(d.members[0].first_interior_node, 2);
  EXPECT_EQ(d.members[0].element_count, 3);
  // A vertical member takes global X as its reference.
  EXPECT_EQ(d.elements[1].ref_x, 1.0);
  EXPECT_EQ(d.elements[1].ref_y, 0.0);
  EXPECT_EQ(d.elements[1].ref_z, 0.0);
}

TEST(ModelcMesh, RollTurnsTheDefaultReference) {
  // A beam along x: reference global Z, turned by roll = 90 degrees about x to -y
  // (z' = cos(roll) z - sin(roll) y with y = z x x = +y). cos(pi/2) is 6.1e-17, not 0: 1e-15.
  Staged s{column(R"([[nodes]]
id = 3
xyz = [4, 0, 3]

[[members]]
id = "B"
nodes = [2, 3]
material = "steel"
section = "s"
roll = 90
)")};
  mesh(s);
  EXPECT_EQ(s.errors(), "");
  const ElementSpec& e = s.d().elements.back();
  EXPECT_NEAR(e.ref_x, 0.0, 1e-15);
  EXPECT_NEAR(e.ref_y, -1.0, 1e-15);
  EXPECT_NEAR(e.ref_z, 0.0, 1e-15);
}

TEST(ModelcMesh, AReleaseMakesANodeAndAPendingHinge) {
  Staged s{column(R"([[nodes]]
id = 3
xyz = [4, 0, 3]

[[members]]
id = "B"
nodes = [2, 3]
material = "steel"
section = "s"
release_end = ["rz"]
)")};
  mesh(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  ASSERT_EQ(d.members.size(), 2U);
  const int rnode = d.members[1].end_release_node;
  ASSERT_EQ(rnode, static_cast<int>(d.nodes.size()) - 1);
  EXPECT_EQ(d.nodes[static_cast<std::size_t>(rnode)].x, 4.0);  // at the joint (node 3)
  EXPECT_EQ(d.elements.back().node_j, rnode);                  // the end element moved to it
  ASSERT_EQ(s.comp().releases.size(), 1U);
  const PendingHinge& ph = s.comp().releases[0];
  EXPECT_EQ(ph.info.name, "B.end");
  EXPECT_EQ(ph.spec.node1, rnode);
  EXPECT_EQ(ph.spec.node2, 2);       // node 3's index
  EXPECT_EQ(ph.spec.frame[0], 1.0);  // local x along the member: global x
  EXPECT_EQ((*ph.dirs)[5].kind, HingeBehaviour::kFree);
  EXPECT_EQ((*ph.dirs)[0].kind, HingeBehaviour::kRigid);
  EXPECT_TRUE(d.hinges.empty());  // added by add_hinges, after the explicit hinges
}

TEST(ModelcMesh, GeometryErrorsLeaveTheMemberOut) {
  Staged s{column(R"([[members]]
id = "Z"
nodes = [2, 2]
material = "steel"
section = "s"
)")};
  mesh(s);
  EXPECT_EQ(s.d().members.size(), 1U);
  EXPECT_EQ(s.errors(),
            "m.toml:38:9: error: key 'members[1].nodes': member Z has zero length: nodes 2 and 2 "
            "are both at (0, 0, 3)\n");
}

}  // namespace modelc_mesh_test
}  // namespace ntn::modelc::compile
