// Nodes and frames: [model] plane (stage hold_out_of_plane, plane.cpp), point masses on
// an offset and hinge axes = { member, roll } (hinges_supports.cpp), with one test per new error
// message. The physics of all three is in modelc_nodes_physics_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_nodes_test {

using testing::column;
using testing::Staged;

// The column of stage_fixture.hpp (node 1 at the origin, node 2 at z = 3, member C of 3
// elements, node 1 fixed) with `model` added to its [model] table and `more` after it.
std::string with_model(const std::string& model, const std::string& more) {
  std::string text = column(more);
  const std::string at = "name = \"m\"\n";
  text.replace(text.find(at), at.size(), at + model + "\n");
  return text;
}

void describe(Staged& s) {
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
}

// ---- hinge axes = { member, roll } ----------------------------------------------------------

constexpr const char* kTwoHinges = R"([[nodes]]
id = 3
xyz = [0, 0, 3]

[[hinges]]
id = "F"
nodes = [2, 3]
frame = { member = "C" }
ry = "free"

[[hinges]]
id = "R"
nodes = [2, 3]
axes = { member = "C", roll = %ROLL% }
ry = "free"
)";

std::string two_hinges(const std::string& roll) {
  std::string t = kTwoHinges;
  t.replace(t.find("%ROLL%"), 6, roll);
  return t;
}

TEST(ModelcHingeAxesRoll, RollZeroIsTheMembersFrameExactly) {
  Staged s{column(two_hinges("0"))};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  ASSERT_EQ(s.d().hinges.size(), 2U);
  EXPECT_EQ(s.d().hinges[1].frame, s.d().hinges[0].frame);  // bit for bit
}

TEST(ModelcHingeAxesRoll, RollNinetyEqualsExplicitRows) {
  Staged s{column(two_hinges("90"))};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  ASSERT_EQ(s.d().hinges.size(), 2U);
  // Member C runs along +Z, so its reference is global X (config/README.md, members): local
  // x = Z, z = X, y = z x x = -Y. Turned by +90 degrees about x (right-handed): y' = z = X,
  // z' = -y = Y. Rows written by hand; cos(pi/2) = 6e-17 is the only rounding, hence 1e-15.
  const std::array<double, 9> rows{0, 0, 1, 1, 0, 0, 0, 1, 0};
  for (std::size_t i = 0; i < 9; ++i)
    EXPECT_NEAR(s.d().hinges[1].frame[i], rows[i], 1e-15) << i;
  // The frame = member form is the unturned one: y = -Y.
  EXPECT_EQ(s.d().hinges[0].frame[4], -1.0);
}

TEST(ModelcHingeAxesRoll, Errors) {
  {
    Staged s{column(R"([[nodes]]
id = 3
xyz = [0, 0, 3]

[[hinges]]
id = "R"
nodes = [2, 3]
axes = { member = "X", roll = 30 }
)")};
    describe(s);
    EXPECT_EQ(s.errors(), "m.toml:43:19: error: key 'hinges[0].axes.member': unknown member 'X'\n");
  }
  {
    Staged s{column(R"([[nodes]]
id = 3
xyz = [0, 0, 3]

[[hinges]]
id = "R"
nodes = [2, 3]
axes = "C"
)")};
    EXPECT_FALSE(s.read());
    EXPECT_EQ(s.errors(),
              "m.toml:43:8: error: key 'hinges[0].axes': must be rows [[x], [y], [z]] or { member "
              "= \"id\", roll = degrees }, got a string\n");
  }
  {
    Staged s{column(two_hinges("inf"))};
    EXPECT_FALSE(s.read());
    EXPECT_EQ(s.errors(),
              "m.toml:49:31: error: key 'hinges[1].axes.roll': must be a finite number\n");
  }
  {
    Staged s{column(two_hinges("30, pitch = 2"))};
    EXPECT_FALSE(s.read());
    EXPECT_EQ(s.errors(),
              "m.toml:49:35: error: key 'hinges[1].axes.pitch': unknown key 'pitch' (this table "
              "takes: member, roll)\n");
  }
  {
    Staged s{column(R"([[nodes]]
id = 3
xyz = [0, 0, 3]

[[hinges]]
id = "R"
nodes = [2, 3]
axes = { member = "C" }
)")};
    EXPECT_FALSE(s.read());
    EXPECT_EQ(s.errors(),
              "m.toml:43:8: error: key 'hinges[0].axes.roll': missing required key 'roll' "
              "(degrees about the member's local x; without a roll, give frame = { member = "
              "\"id\" })\n");
  }
}

// ---- point masses on an offset ----------------------------------------------------------------

TEST(ModelcPointMassOffset, ANodeAtTheMassCentreOnARigidEccentricHinge) {
  Staged s{column(R"([[point_masses]]
node = 2
mass = 500
inertia = [10, 20, 30]
offset = [0.5, -0.25, 1]

[[point_masses]]
node = 2
mass = 7

[[point_masses]]
node = 2
mass = 100
offset = [0, 0, 0.5]
)")};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  // Nodes: 2 given, 2 interior of C, then the two mass centres in file order.
  ASSERT_EQ(d.nodes.size(), 6U);
  const NodeSpec& c = d.nodes[4];
  EXPECT_EQ(c.x, 0.5);
  EXPECT_EQ(c.y, -0.25);
  EXPECT_EQ(c.z, 4.0);
  EXPECT_EQ(c.added, (std::array<double, 6>{500, 500, 500, 10, 20, 30}));
  EXPECT_EQ(d.node_ids[4], kGeneratedNode);
  // Without an offset a point mass stays on its node.
  EXPECT_EQ(d.nodes[1].added, (std::array<double, 6>{7, 7, 7, 0, 0, 0}));
  ASSERT_EQ(d.hinges.size(), 2U);
  const HingeSpec& h = d.hinges[0];
  EXPECT_EQ(h.node1, 1);
  EXPECT_EQ(h.node2, 4);
  EXPECT_EQ(h.eccentricity, (std::array<double, 3>{0.5, -0.25, 1}));
  EXPECT_EQ(h.frame, (std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
  for (HingeBehaviour b : h.behaviour)
    EXPECT_EQ(b, HingeBehaviour::kRigid);
  EXPECT_EQ(d.hinge_info[0].origin, HingeOrigin::kPointMass);
  EXPECT_EQ(d.describe_hinge(0), "the rigid offset of the point mass at node 2 (offset)");
  EXPECT_EQ(d.describe_hinge(1), "the rigid offset of the point mass at node 2 (offset 2)");
  EXPECT_EQ(d.describe_node(4),
            "the mass centre of the point mass at node 2 (offset) (model node 4)");
  EXPECT_EQ(s.comp().hinge_at[0].key, "point_masses[0].offset");
}

TEST(ModelcPointMassOffset, PenaltyLeavesRotationsWithoutInertiaFree) {
  // Under "penalty" a rigid direction is a spring, which needs mass on both nodes: the mass
  // centre's rotations without inertia are left free (a mechanism note), the others rigid.
  Staged s{with_model("hinge_method = \"penalty\"", R"([[point_masses]]
node = 2
mass = 500
inertia = [0, 4, 0]
offset = [0.5, 0, 0]
)")};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  ASSERT_EQ(s.d().hinges.size(), 1U);
  const auto& b = s.d().hinges[0].behaviour;
  for (int k : {kUx, kUy, kUz, kRy})
    EXPECT_EQ(b[static_cast<std::size_t>(k)], HingeBehaviour::kRigid) << k;
  EXPECT_EQ(b[kRx], HingeBehaviour::kFree);
  EXPECT_EQ(b[kRz], HingeBehaviour::kFree);
}

TEST(ModelcPointMassOffset, Errors) {
  {
    Staged s{with_model("hinge_method = \"ntn_paper\"", R"([[point_masses]]
node = 2
mass = 500
offset = [0.5, 0, 0]
)")};
    describe(s);
    EXPECT_EQ(s.errors(),
              "m.toml:40:10: error: key 'point_masses[0].offset': a point mass on an offset is an "
              "eccentric rigid hinge, which needs hinge_method = \"ntn_exact\" or \"penalty\": "
              "the seed's algorithm (\"ntn_paper\", S 17-37) has no eccentricity\n");
  }
  {
    Staged s{column(R"([[point_masses]]
node = 2
mass = 500
offset = [0.5, 0]
)")};
    EXPECT_FALSE(s.read());
    EXPECT_NE(s.errors().find("key 'point_masses[0].offset': expected 3"), std::string::npos);
  }
  {
    Staged s{column(R"([[point_masses]]
node = 2
mass = 500
offset = [0.5, nan, 0]
)")};
    EXPECT_FALSE(s.read());
    EXPECT_EQ(s.errors(),
              "m.toml:39:16: error: key 'point_masses[0].offset[1]': must be a finite number\n");
  }
}

// ---- [model] plane
// -------------------------------------------------------------------------------

// A portal in x-z: columns 1-2 (the fixture's C) and 3-4, beam 2-4 released at its end.
constexpr const char* kPortal = R"([[nodes]]
id = 3
xyz = [4, 0, 0]

[[nodes]]
id = 4
xyz = [4, 0, 3]

[[members]]
id = "C2"
nodes = [3, 4]
material = "steel"
section = "s"

[[members]]
id = "B"
nodes = [2, 4]
material = "steel"
section = "s"
divisions = 2
release_end = %RELEASE%

[[supports]]
node = 3
fix = "pinned"
)";

std::string portal(const std::string& release) {
  std::string t = kPortal;
  t.replace(t.find("%RELEASE%"), 9, release);
  return t;
}

TEST(ModelcPlane, HoldsEachNodeOrTreeOnce) {
  Staged s{with_model("plane = \"xz\"", portal("[\"ry\"]"))};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  // Nodes: 1-4 given, C's interior 4 and 5, B's interior 6 and its end node 7 (released).
  ASSERT_EQ(d.nodes.size(), 8U);
  constexpr std::uint8_t kXz = (1U << kUy) | (1U << kRx) | (1U << kRz);
  EXPECT_EQ(d.nodes[0].fixed, 0x3F);        // "all" already holds them
  EXPECT_EQ(d.nodes[2].fixed, 0x07 | kXz);  // "pinned" + plane
  for (int n : {1, 3, 4, 5, 6})
    EXPECT_EQ(d.nodes[static_cast<std::size_t>(n)].fixed, kXz) << n;
  // The release node hangs from node 4 by its hinge, whose uy, rx, rz are rigid already (local
  // y of a beam along x is global y): no bits, so the tree reaches the ground once.
  EXPECT_EQ(d.nodes[7].fixed, 0);
  EXPECT_EQ(d.plane, "xz");
  EXPECT_EQ(d.plane_held_dofs, 5 * 3 + 2);  // nodes 2, 4..7 (less the release node): 3 each;
                                            // node 3: ry is free, uy already held
  EXPECT_EQ(d.plane_rigid_directions, 0);
}

TEST(ModelcPlane, OutOfPlaneHingeDirectionsBecomeRigid) {
  // A release of ry and rz: rz turns the beam out of the x-z plane, so it is made rigid.
  Staged s{with_model("plane = \"xz\"", portal("{ ry = \"free\", rz = { linear = 1e5 } }"))};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  const HingeSpec& h = s.d().hinges[0];
  EXPECT_EQ(h.behaviour[kRy], HingeBehaviour::kFree);
  EXPECT_EQ(h.behaviour[kRz], HingeBehaviour::kRigid);
  EXPECT_EQ(h.stiffness[kRz], 0.0);
  EXPECT_EQ(s.d().plane_rigid_directions, 1);
}

TEST(ModelcPlane, ATreeWithASupportOrAGroundHingeTakesNoOtherBits) {
  // Node 3 (supported) is the joint of a hinge to node 5: the bits go on node 3 only. Node 4 is
  // held by a support with axes (a hinge to the ground) and takes no bits at all.
  Staged s{with_model("plane = \"xy\"", R"([[nodes]]
id = 3
xyz = [4, 0, 0]

[[nodes]]
id = 4
xyz = [4, 0, 3]

[[nodes]]
id = 5
xyz = [4, 0, 0]

[[members]]
id = "C2"
nodes = [5, 4]
material = "steel"
section = "s"

[[hinges]]
id = "H"
nodes = [5, 3]
rz = "free"

[[supports]]
node = 3
fix = ["ux"]

[[supports]]
node = 4
fix = ["ux"]
axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
)")};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  constexpr std::uint8_t kXy = (1U << kUz) | (1U << kRx) | (1U << kRy);
  EXPECT_EQ(d.nodes[2].fixed, 0x01 | kXy);
  EXPECT_EQ(d.nodes[3].fixed, 0);
  EXPECT_EQ(d.nodes[4].fixed, 0);
  const HingeSpec& ground = d.hinges[1];
  EXPECT_EQ(ground.node2, kGround);
  for (int k : {kUz, kRx, kRy})
    EXPECT_EQ(ground.behaviour[static_cast<std::size_t>(k)], HingeBehaviour::kRigid);
  EXPECT_EQ(ground.behaviour[kUy], HingeBehaviour::kFree);
  EXPECT_EQ(d.plane_rigid_directions, 3);
}

TEST(ModelcPlane, APointMassOnAnOffsetIsHeldThroughItsNode) {
  // The mass centre hangs from node 2 by a hinge rigid in all six: the tree {2, centre} takes
  // the bits on node 2 (the lower index) only, and the hinge is left as it is.
  Staged s{with_model("plane = \"yz\"", R"([[point_masses]]
node = 2
mass = 50
offset = [0, 0.5, 0]
)")};
  describe(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  ASSERT_EQ(d.nodes.size(), 5U);  // 1, 2, C's interior 3 and 4, the mass centre
  constexpr std::uint8_t kYz = (1U << kUx) | (1U << kRy) | (1U << kRz);
  EXPECT_EQ(d.nodes[1].fixed, kYz);
  EXPECT_EQ(d.nodes[4].fixed, 0);
  EXPECT_EQ(d.plane_rigid_directions, 0);
  EXPECT_EQ(d.plane_held_dofs, 3 * 3);  // nodes 2, 3, 4; node 1 is held already
}

TEST(ModelcPlane, Errors) {
  {
    Staged s{with_model("plane = \"xw\"", "")};
    EXPECT_FALSE(s.read());
    EXPECT_EQ(s.errors(),
              "m.toml:3:9: error: key 'model.plane': must be one of \"xz\", \"xy\", \"yz\" (got "
              "\"xw\")\n");
  }
  {
    // A hinge with a free direction whose frame has no axis along y (turned 30 degrees about the
    // column's axis) cannot hold the plane.
    Staged s{with_model("plane = \"xz\"", R"([[nodes]]
id = 3
xyz = [0, 0, 3]

[[hinges]]
id = "R"
nodes = [2, 3]
axes = { member = "C", roll = 30 }
ry = "free"
)")};
    describe(s);
    EXPECT_EQ(s.errors(),
              "m.toml:43:9: error: key 'hinges[0].nodes': hinge R has a free or spring direction "
              "but no axis normal to the plane of the model (plane = \"xz\", normal y): in a "
              "planar model such a hinge's frame needs an axis along y so that its directions are "
              "in plane or out of plane\n");
  }
}

}  // namespace modelc_nodes_test
}  // namespace ntn::modelc::compile
