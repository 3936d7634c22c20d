// Stages add_hinges, add_supports, add_point_masses (tools/modelc/src/hinges_supports.cpp).
#include <gtest/gtest.h>

#include <string>

#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_hinges_supports_test {

using testing::column;
using testing::Staged;

void run(Staged& s) {
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  mesh_members(s.comp());
  add_hinges(s.comp());
  add_supports(s.comp());
  add_point_masses(s.comp());
}

constexpr const char* kBeamWithRelease = R"([[nodes]]
id = 3
xyz = [4, 0, 3]

[[nodes]]
id = 4
xyz = [4, 0, 3]

[[members]]
id = "B"
nodes = [2, 3]
material = "steel"
section = "s"
release_start = ["ry"]

[[hinges]]
id = "H"
nodes = [3, 4]
rz = { linear = 1e6, dashpot = 10 }

[[supports]]
node = 4
fix = ["ux", "uz"]
axes = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]

[[point_masses]]
node = 4
mass = 100
inertia = [1, 2, 3]

[[point_masses]]
node = 4
mass = 20
)";

TEST(ModelcHingesSupports, HingesInOrderExplicitReleasesSupports) {
  Staged s{column(kBeamWithRelease)};
  run(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  ASSERT_EQ(d.hinges.size(), 3U);
  EXPECT_EQ(d.hinge_info[0].name, "H");
  EXPECT_EQ(d.hinge_info[1].name, "B.start");
  EXPECT_EQ(d.hinge_info[2].name, "support.4");
  EXPECT_EQ(d.hinges[0].behaviour[5], HingeBehaviour::kLinear);
  EXPECT_EQ(d.hinges[0].stiffness[5], 1e6);
  EXPECT_EQ(d.hinges[0].dashpot[5], 10.0);
  EXPECT_EQ(d.members[1].start_hinge, 1);
  // The support with axes is a hinge to the ground, rigid in its fixed local directions; the
  // node's own support bits stay 0.
  EXPECT_EQ(d.hinges[2].node2, kGround);
  EXPECT_EQ(d.hinges[2].frame[1], 1.0);
  EXPECT_EQ(d.hinges[2].behaviour[0], HingeBehaviour::kRigid);
  EXPECT_EQ(d.hinges[2].behaviour[1], HingeBehaviour::kFree);
  EXPECT_EQ(d.hinges[2].behaviour[2], HingeBehaviour::kRigid);
  EXPECT_EQ(d.nodes[3].fixed, 0);
  EXPECT_EQ(d.nodes[0].fixed, 0x3F);
  // Each hinge's directions keep the place of the value that set them.
  ASSERT_EQ(s.comp().dir_at.size(), 3U);
  EXPECT_EQ(s.comp().dir_at[0][5].key, "hinges[0].rz");
  EXPECT_EQ(s.comp().dir_at[0][0].key, "hinges[0].nodes");
  EXPECT_EQ(s.comp().hinge_at[2].key, "supports[1].axes");
  // Point masses add up on their node.
  EXPECT_EQ(d.nodes[3].added[0], 120.0);
  EXPECT_EQ(d.nodes[3].added[5], 3.0);
}

TEST(ModelcHingesSupports, ExplicitHingesAreChecked) {
  Staged s{column(R"([[nodes]]
id = 3
xyz = [0, 0, 3.5]

[[hinges]]
id = "H"
nodes = [2, 3]

[[hinges]]
id = "B.end"
nodes = [2, "ground"]
eccentric = true

[[supports]]
node = 1
fix = "pinned"
)")};
  run(s);
  EXPECT_EQ(
      s.errors(),
      "m.toml:42:9: error: key 'hinges[0].nodes': nodes 2 and 3 do not coincide (they are 0.5 m "
      "apart): set eccentric = true for an eccentric hinge (e = x2 - x1), or give the nodes the "
      "same position\n"
      "m.toml:47:13: error: key 'hinges[1].eccentric': a hinge to the ground cannot be eccentric "
      "(the ground has no position): leave out eccentric\n"
      "m.toml:50:8: error: key 'supports[1].node': node 1 already has a support (line 33)\n");
}

}  // namespace modelc_hinges_supports_test
}  // namespace ntn::modelc::compile
