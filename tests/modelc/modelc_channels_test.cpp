// Stage add_channels (tools/modelc/src/channels.cpp): inputs and outputs, their units, drift
// heights and reactions.
#include <gtest/gtest.h>

#include <string>

#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_channels_test {

using testing::column;
using testing::Staged;

void run(Staged& s) {
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
}

TEST(ModelcChannels, OutputsGetIndicesAndUnits) {
  Staged s{column(R"([[inputs]]
name = "ag"
kind = "ground_acceleration"
direction = "y"
units = "g"

[[outputs]]
name = "top_rz_v"
kind = "velocity"
node = 2
dof = "rz"

[[outputs]]
name = "drift"
kind = "drift"
nodes = [1, 2]
direction = "x"
alarm = 0.02

[[outputs]]
name = "base_N"
kind = "element_force"
member = "C"
end = "start"
component = "N"

[[outputs]]
name = "Rx"
kind = "reaction"
direction = "x"
)")};
  run(s);
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  ASSERT_EQ(d.inputs.size(), 1U);
  EXPECT_EQ(d.inputs[0].dof, 1);
  EXPECT_EQ(d.inputs[0].scale, 9.80665);
  ASSERT_EQ(d.outputs.size(), 4U);
  EXPECT_EQ(d.output_units[0], "rad/s");
  EXPECT_EQ(d.outputs[1].scale, 1.0 / 3.0);  // drift ratio: 1 / storey height
  EXPECT_EQ(d.output_units[1], "-");
  EXPECT_EQ(d.output_alarms[1].limit, 0.02);
  EXPECT_EQ(d.outputs[2].element, 0);  // the member's first element
  EXPECT_EQ(d.output_units[2], "N");
  EXPECT_EQ(d.output_units[3], "N");
}

TEST(ModelcChannels, ChannelsThatCannotWorkAreErrors) {
  Staged s{column(R"([[outputs]]
name = "drift"
kind = "drift"
nodes = [2, 1]
direction = "x"

[[outputs]]
name = "Mx"
kind = "reaction"
direction = "rx"

[[outputs]]
name = "h"
kind = "hinge_force"
hinge = "C.end"
direction = "ux"

[[supports]]
node = 2
fix = ["ux"]
)")};
  // Node 2's support does not hold rx either; node 1's (all) does: only the drift and the hinge
  // are errors.
  run(s);
  EXPECT_EQ(s.d().outputs.size(), 1U);
  EXPECT_EQ(s.errors(),
            "m.toml:39:9: error: key 'outputs[0].nodes': the upper node 1 (z = 0 m) is below the "
            "lower node 2 (z = 3 m)\n"
            "m.toml:50:9: error: key 'outputs[2].hinge': unknown hinge 'C.end' (hinges are named "
            "by their id, <member>.start and <member>.end for releases, support.<node id> for "
            "supports with axes)\n");
}

}  // namespace modelc_channels_test
}  // namespace ntn::modelc::compile
