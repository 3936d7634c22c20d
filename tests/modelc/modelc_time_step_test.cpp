// Stage choose_time_step (tools/modelc/src/time_step.cpp): the stable step, dt and the frame
// rule.
#include <gtest/gtest.h>

#include <string>

#include "ntn/time_step.hpp"
#include "stage_fixture.hpp"

namespace ntn::modelc::compile {
namespace modelc_time_step_test {

using testing::column;
using testing::Staged;

void through_checks(Staged& s) {
  ASSERT_TRUE(s.read()) << s.errors();
  s.describe();
  for (auto stage :
       {check_rigid_cycles, check_element_numbers, assemble_mass, check_nodes_have_mass,
        check_force_numbers, set_hinge_stiffness, check_curve_branches, check_kernel_accepts_hinges,
        check_effective_mass, check_hinge_spring_numbers})
    stage(s.comp());
  ASSERT_FALSE(s.sink().failed()) << s.errors();
}

TEST(ModelcTimeStep, AutoTakesTheKernelsStep) {
  Staged s{column("")};
  through_checks(s);
  choose_time_step(s.comp());
  EXPECT_EQ(s.errors(), "");
  const ModelDescription& d = s.d();
  const StableStepReport r = stable_time_step(d.view(), s.comp().mass);
  EXPECT_EQ(d.stable.dt_stable, r.dt_stable);
  EXPECT_GT(d.stable.dt_stable, 0.0);
  EXPECT_EQ(d.settings.dt, auto_time_step(r.dt_stable, 1e-3));
}

TEST(ModelcTimeStep, GivenDtAboveTheStableStep) {
  Staged s{std::string(testing::kColumn).replace(0, 7, "[model]\ndt = 1e-3")};
  through_checks(s);
  choose_time_step(s.comp());
  const std::string e = s.errors();
  EXPECT_EQ(e.rfind("m.toml:2:6: error: key 'model.dt': dt = 0.001 s is above the stable step ", 0),
            0U)
      << e;
  EXPECT_NE(e.find("; use dt = \"auto\" or a smaller dt"), std::string::npos) << e;
}

TEST(ModelcTimeStep, DtMustDivideTheFrame) {
  Staged s{
      std::string(testing::kColumn).replace(0, 7, "[model]\ndt = 3e-7\nallow_unstable = true")};
  through_checks(s);
  choose_time_step(s.comp());
  EXPECT_EQ(s.errors(),
            "m.toml:2:6: error: key 'model.dt': dt = 3e-07 s does not divide the frame period "
            "0.001 s (frame_rate = 1000 Hz) into a whole number of substeps (period / dt = "
            "3333.33); use dt = \"auto\" or the period / N\n");
}

}  // namespace modelc_time_step_test
}  // namespace ntn::modelc::compile
