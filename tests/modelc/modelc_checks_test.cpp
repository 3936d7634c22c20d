// The check stages (tools/modelc/src/check_topology.cpp, check_numbers.cpp, check_mass.cpp,
// hinge_stiffness.cpp), each run after the description stages on a model made to fail it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "check_numbers.hpp"
#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_checks_test {

using testing::column;
using testing::Staged;

void describe(Staged& s) {
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
  ASSERT_FALSE(s.sink().failed()) << s.errors();
}

TEST(ModelcChecks, RigidCycleNamesItsNodes) {
  // Node 2 is supported (joined to the ground) and a rigid hinge joins it to the ground again.
  Staged s{
      column("[[supports]]\nnode = 2\nfix = [\"ux\"]\n\n[[hinges]]\nid = \"H\"\nnodes = [2, "
             "\"ground\"]\n")};
  describe(s);
  check_rigid_cycles(s.comp());
  const std::string e = s.errors();
  EXPECT_NE(e.find("m.toml:42:9: error: key 'hinges[0].nodes': hinge H closes a cycle of rigid "
                   "connections: node 2 - ground - node 2"),
            std::string::npos)
      << e;
}

TEST(ModelcChecks, CheckDerivedBlamesTheFactorFarthestOut) {
  DiagnosticSink sink("m.toml");
  // E A / l = 1e300 x 1e10 / 1: the overflow comes from E (300 > 10 orders of magnitude).
  EXPECT_TRUE(check_derived(sink, 1e3, "x", {{"E", 1e300, 1, Where{5, 1, "E"}, " Pa"}}, false));
  EXPECT_FALSE(check_derived(sink, 1e300 * 1e10, "axial stiffness",
                             {{"E", 1e300, 1, Where{5, 1, "E"}, " Pa"},
                              {"A", 1e10, 1, Where{6, 1, "A"}, " m^2"},
                              {"l", 1, -1, Where{7, 1, "l"}, " m"}},
                             false));
  // Underflow only counts with `normal`: a subnormal mass.
  EXPECT_TRUE(
      check_derived(sink, 1e-310, "x", {{"rho", 1e-310, 1, Where{8, 1, "rho"}, ""}}, false));
  EXPECT_FALSE(
      check_derived(sink, 1e-310, "end mass", {{"rho", 1e-310, 1, Where{8, 1, "rho"}, ""}}, true));
  const auto errors = sink.take_errors();
  ASSERT_EQ(errors.size(), 2U);
  EXPECT_EQ(errors[0].line, 5);  // at E
  EXPECT_EQ(errors[0].message,
            "E = 1e+300 Pa gives a non-finite axial stiffness (E = 1e+300 Pa, A = 1e+10 m^2, l = "
            "1 m): beyond the largest double, 1.8e308");
  EXPECT_EQ(errors[1].line, 8);
  EXPECT_EQ(errors[1].message.rfind("rho = 1e-310 is too small: it gives a zero or subnormal end "
                                    "mass",
                                    0),
            0U);
}

TEST(ModelcChecks, MassIsTheKernelsLumpedMass) {
  Staged s{column("[[point_masses]]\nnode = 2\nmass = 100\n")};
  describe(s);
  assemble_mass(s.comp());
  EXPECT_EQ(s.errors(), "");
  const auto& mass = s.comp().mass;
  ASSERT_EQ(mass.size(), 6U * s.d().nodes.size());
  // Node 2 (index 1): half of the top element (rho A l / 2, l = 1 m) plus its point mass.
  EXPECT_NEAR(mass[6 * 1 + 0], 7850 * 1e-2 * 1.0 / 2 + 100, 1e-9);  // sum of rounded terms
}

TEST(ModelcChecks, LooseNodeAtAnotherNodesPlace) {
  Staged s{column("[[nodes]]\nid = 3\nxyz = [0, 0, 3]\n")};
  describe(s);
  assemble_mass(s.comp());
  check_nodes_have_mass(s.comp());
  const std::string e = s.errors();
  EXPECT_NE(e.find("m.toml:37:6: error: key 'nodes[2].id': node 3 has no mass in its free DOFs "
                   "ux, uy, uz, rx, ry, rz: connect it to a member, give it a point mass (with "
                   "inertia for rotations) or support those DOFs. It is connected to no member or "
                   "hinge, at the same place as node 2 (within 1e-9 m): did you mean that node?"),
            std::string::npos)
      << e;
}

TEST(ModelcChecks, DefaultPenaltyStiffnessFollowsTheStiffestElement) {
  Staged s{column("")};
  describe(s);
  assemble_mass(s.comp());
  set_hinge_stiffness(s.comp());
  EXPECT_EQ(s.errors(), "");
  const Settings& st = s.d().settings;
  // Elements of l = 1 m: E A / l and 4 E max(Iy, Iz) / l, times 1e4.
  EXPECT_EQ(st.penalty_stiffness, 1e4 * (2.1e11 * 1e-2 / 1.0));
  EXPECT_EQ(st.limit_stiffness, st.penalty_stiffness);
  EXPECT_EQ(st.penalty_rotational_stiffness, 1e4 * (4.0 * 2.1e11 * 2e-5 / 1.0));
}

TEST(ModelcChecks, CurveRigidBranchesOnlyAtTheEnds) {
  // Slopes 1e3, 1e20 (at least the limit stiffness 1e9: rigid), 1e3.
  Staged s{column(R"([[curves]]
id = "gap"
points = [[-2, -2e3], [-1, -1e3], [1, 2e20], [2, 2e20]]

[[nodes]]
id = 3
xyz = [0, 0, 3]

[[point_masses]]
node = 3
mass = 10
inertia = [1, 1, 1]

[[hinges]]
id = "H"
nodes = [2, 3]
ux = { curve = "gap" }
)")};
  describe(s);
  s.d().settings.limit_stiffness = 1e9;  // what set_hinge_stiffness would set from a given one
  check_curve_branches(s.comp());
  const std::string e = s.errors();
  EXPECT_NE(e.find("key 'hinges[0].ux': curve 'gap' has a rigid segment (points 1 to 2, slope at "
                   "least the limit stiffness 1e+09 N/m) between softer ones"),
            std::string::npos)
      << e;
}

TEST(ModelcChecks, MechanismIsANote) {
  // A pinned end of a member and nothing else at node 3: rz free and massless.
  Staged s{column(R"([[nodes]]
id = 3
xyz = [4, 0, 3]

[[members]]
id = "B"
nodes = [2, 3]
material = "steel"
section = "s"
release_end = ["rx", "ry", "rz"]

[[supports]]
node = 3
fix = ["ux", "uy", "uz"]
)")};
  describe(s);
  assemble_mass(s.comp());
  check_effective_mass(s.comp());
  EXPECT_EQ(s.errors(), "");
  ASSERT_EQ(s.d().mechanisms.size(), 1U);
  EXPECT_EQ(s.d().mechanisms[0].node, 2);
  const std::string n = s.notes();
  EXPECT_NE(n.find("m.toml:37:6: note: key 'nodes[2].id': node 3 has no effective mass and no "
                   "stiffness in rx, ry, rz (global axes): a mechanism"),
            std::string::npos)
      << n;
}

}  // namespace modelc_checks_test
}  // namespace ntn::modelc::compile
