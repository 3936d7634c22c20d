// Stage add_loads (tools/modelc/src/loads.cpp).
#include <gtest/gtest.h>

#include <string>

#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_loads_test {

using testing::column;
using testing::Staged;

TEST(ModelcLoads, ForceComponentsBecomeKernelLoads) {
  Staged s{column(R"([[time_functions]]
id = "ramp"
points = [[0, 0], [1, 1]]

[[loads]]
node = 2
force = [0, 5, 0, 0, 0, -7]
function = "ramp"

[[loads]]
node = 2
dof = "uz"
value = -9
)")};
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  mesh_members(s.comp());
  add_loads(s.comp());
  EXPECT_EQ(s.errors(), "");
  const auto& loads = s.d().loads;
  ASSERT_EQ(loads.size(), 3U);  // the zero components are left out
  EXPECT_EQ(loads[0].node, 1);
  EXPECT_EQ(loads[0].dof, 1);
  EXPECT_EQ(loads[0].value, 5.0);
  EXPECT_EQ(loads[0].time_function, 0);
  EXPECT_EQ(loads[1].dof, 5);
  EXPECT_EQ(loads[1].value, -7.0);
  EXPECT_EQ(loads[2].time_function, kConstant);
  ASSERT_EQ(s.comp().load_at.size(), 3U);
  EXPECT_EQ(s.comp().load_at[1].key, "loads[0].node");
  EXPECT_EQ(s.comp().load_at[2].key, "loads[1].node");
}

TEST(ModelcLoads, UnknownNodeOrFunctionAddsNothing) {
  Staged s{
      column("[[loads]]\nnode = 9\ndof = \"ux\"\nvalue = 1\n\n[[loads]]\nnode = 2\ndof = "
             "\"ux\"\nvalue = 1\nfunction = \"nope\"\n")};
  ASSERT_TRUE(s.read()) << s.errors();
  resolve_ids(s.comp());
  mesh_members(s.comp());
  add_loads(s.comp());
  EXPECT_TRUE(s.d().loads.empty());
  EXPECT_EQ(s.errors(),
            "m.toml:37:8: error: key 'loads[0].node': unknown node 9\n"
            "m.toml:45:12: error: key 'loads[1].function': unknown time function 'nope'\n");
}

}  // namespace modelc_loads_test
}  // namespace ntn::modelc::compile
