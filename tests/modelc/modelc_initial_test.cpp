// Stages add_initial_values and static_preload (tools/modelc/src/initial_state.cpp): [initial]
// and [[initial.nodes]] into NodeSpec::u0, v0, and the static preload against a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ntn/modelc/diagnostic.hpp"
#include "ntn/modelc/load_model.hpp"
#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_initial_test {

using testing::column;
using testing::Staged;

TEST(ModelcInitial, NodeValuesBecomeTheNodesU0AndV0) {
  Staged s{column(R"([[initial.nodes]]
node = 2
u = [0.01, 0, -0.02]

[[initial.nodes]]
node = 2
v = [0, 0.5, 0, 0, 0, 0.25]
)")};
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
  EXPECT_EQ(s.errors(), "");
  const NodeSpec& n = s.d().nodes[1];  // user node 2 is the second node
  EXPECT_EQ(n.u0, (std::array<double, 6>{0.01, 0, -0.02, 0, 0, 0}));
  EXPECT_EQ(n.v0, (std::array<double, 6>{0, 0.5, 0, 0, 0, 0.25}));
  EXPECT_EQ(s.d().nodes[0].u0, (std::array<double, 6>{}));
  EXPECT_EQ(s.d().initial_nodes, 2);
  EXPECT_FALSE(s.d().preload.on);
}

TEST(ModelcInitial, BadValuesAreReportedAtTheirKeys) {
  Staged bad_read{column(R"([initial]
gravity = "later"
mode = 1

[[initial.nodes]]
node = 2
u = [1, 2, 3, 4]

[[initial.nodes]]
node = 2
)")};
  EXPECT_FALSE(bad_read.read());
  EXPECT_EQ(bad_read.errors(),
            "m.toml:37:11: error: key 'initial.gravity': must be one of \"sudden\", \"static\" "
            "(got \"later\")\n"
            "m.toml:38:1: error: key 'initial.mode': unknown key 'mode' (this table takes: "
            "gravity, nodes)\n"
            "m.toml:42:5: error: key 'initial.nodes[0].u': expected 3 values (ux, uy, uz) or 6 "
            "(ux, uy, uz, rx, ry, rz), got 4\n"
            "m.toml:44:1: error: key 'initial.nodes[1]': gives neither 'u' nor 'v' (the node's "
            "initial displacement and velocity)\n");

  Staged bad_refs{column(R"([[time_functions]]
id = "f"
points = [[0, 1]]

[initial]
gravity = "static"

[[initial.nodes]]
node = 7
u = [1, 0, 0]

[[initial.nodes]]
node = 1
v = [0, 0, 0.1]
)")};
  ASSERT_TRUE(bad_refs.read()) << bad_refs.errors();
  bad_refs.describe();
  EXPECT_EQ(bad_refs.errors(),
            "m.toml:44:8: error: key 'initial.nodes[0].node': unknown node 7\n"
            "m.toml:48:8: error: key 'initial.nodes[1].node': node 1: uz is held by a support, "
            "so its initial displacement and velocity are 0 (got u = 0, v = 0.1)\n");
}

// A static preload with a time-varying gravity is a contradiction: refused at [initial] gravity.
TEST(ModelcInitial, StaticPreloadRefusesAGravityFunction) {
  std::string text = column(R"([[time_functions]]
id = "ramp"
points = [[0, 0], [1, 1]]

[initial]
gravity = "static"
)");
  text.replace(text.find("name = \"m\"\n"), 11,
               "name = \"m\"\ngravity = [0, 0, -9.81]\ngravity_function = \"ramp\"\n");
  const LoadResult r = load_model_from_string(text, "m.toml");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(format_all(r.errors),
            "m.toml:43:11: error: key 'initial.gravity': gravity = \"static\" holds gravity "
            "constant from the static preload on, but model.gravity_function 'ramp' varies it: "
            "remove gravity_function, or use gravity = \"sudden\"\n");
}

// The preload of a cantilever column (3 m, 3 Euler-Bernoulli elements, fixed at its base) under
// a constant tip force F along x: cubic elements give the exact nodal values of the beam, so the
// tip deflection is F L^3 / (3 E I) and its rotation F L^2 / (2 E I) to rounding (1e-9). The
// bending about y uses Iy = 1e-5 m^4. A load with a time function stays out (a note says so when
// it is not zero at t = 0), and an unsupported model has no static equilibrium.
TEST(ModelcInitial, StaticPreloadOfACantileverIsTheClosedForm) {
  const double F = 1000.0, L = 3.0, E = 2.1e11, I = 1e-5;
  const std::string loads = R"([[time_functions]]
id = "step"
points = [[0, 1]]

[[loads]]
node = 2
dof = "ux"
value = 1000

[[loads]]
node = 2
dof = "uy"
value = 50
function = "step"

[initial]
gravity = "static"
)";
  const LoadResult r = load_model_from_string(column(loads), "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const ModelDescription& d = *r.model;
  EXPECT_TRUE(d.preload.on);
  EXPECT_EQ(d.preload.loads, 1);
  ASSERT_EQ(d.preload.notes.size(), 1U);
  EXPECT_EQ(d.preload.notes[0],
            "1 load(s) with a time function not zero at t = 0 are not in the preload: they act "
            "suddenly at t = 0");
  const NodeSpec& tip = d.nodes[1];
  EXPECT_NEAR(tip.u0[0], F * L * L * L / (3 * E * I), 1e-9 * F * L * L * L / (3 * E * I));
  EXPECT_NEAR(tip.u0[4], F * L * L / (2 * E * I), 1e-9 * F * L * L / (2 * E * I));
  EXPECT_EQ(tip.u0[1], 0.0);  // the time-function load is not in it
  EXPECT_LT(d.preload.relative_residual, 1e-12);
  EXPECT_EQ(d.preload.max_node, 1);
  EXPECT_EQ(d.preload.max_dof, 0);

  std::string loose = column(loads);
  loose.erase(loose.find("[[supports]]"),
              std::string("[[supports]]\nnode = 1\nfix = \"all\"\n").size());
  const LoadResult u = load_model_from_string(loose, "m.toml");
  ASSERT_FALSE(u.ok());
  EXPECT_NE(format_all(u.errors).find("key 'initial.gravity': gravity = \"static\": no static "
                                      "equilibrium under gravity and the constant loads"),
            std::string::npos)
      << format_all(u.errors);
}

}  // namespace modelc_initial_test
}  // namespace ntn::modelc::compile

namespace ntn::modelc::compile {
namespace modelc_initial_test {

// The preload of a simply supported beam under a uniform member load q (L = 6 m, 6 elements,
// Iy = 1e-5 m^4): the member load's consistent nodal forces and the exact K give the beam's
// nodal values, midspan deflection 5 q L^4 / (384 E I) and end rotation q L^3 / (24 E I), to
// rounding (1e-9; 0.5 % is required).
TEST(ModelcInitial, StaticPreloadOfAUniformlyLoadedBeamIsTheClosedForm) {
  const double q = 2000.0, L = 6.0, E = 2.1e11, I = 1e-5;
  const std::string text = R"([model]
name = "m"

[[materials]]
id = "steel"
E = 2.1e11
nu = 0.3
rho = 7850

[[sections]]
id = "s"
A = 1e-2
Iy = 1e-5
Iz = 2e-5
J = 1e-5

[[nodes]]
id = 1
xyz = [0, 0, 0]

[[nodes]]
id = 2
xyz = [6, 0, 0]

[[members]]
id = "B"
nodes = [1, 2]
material = "steel"
section = "s"
divisions = 6

[[supports]]
node = 1
fix = ["ux", "uy", "uz", "rx"]

[[supports]]
node = 2
fix = ["uy", "uz"]

[[member_loads]]
member = "B"
q = [0, 0, -2000]

[initial]
gravity = "static"
)";
  const LoadResult r = load_model_from_string(text, "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const ModelDescription& d = *r.model;
  const MemberInfo& b = d.members[0];
  const NodeSpec& mid = d.nodes[static_cast<std::size_t>(b.first_interior_node + 2)];
  ASSERT_DOUBLE_EQ(mid.x, 3.0);
  const double w = 5 * q * L * L * L * L / (384 * E * I), theta = q * L * L * L / (24 * E * I);
  EXPECT_NEAR(mid.u0[2], -w, 1e-9 * w);
  EXPECT_NEAR(d.nodes[0].u0[4], theta, 1e-9 * theta);  // rotation about y at x = 0: +w'
  EXPECT_NEAR(d.nodes[1].u0[4], -theta, 1e-9 * theta);
}

}  // namespace modelc_initial_test
}  // namespace ntn::modelc::compile
