// Model building (kernel/include/ntn/model.hpp): the assembled lumped mass, supports, damping,
// and every init error with the index it reports.
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <set>
#include <string>

#include "ntn/footprint.hpp"  // its static_asserts: the footprint equals sizeof
#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace model_test {

using ntn_test::dof;

constexpr int kDiv = 3;
constexpr ntn::Sizes kS =
    ntn_test::portal_frame_sizes(kDiv, {.time_functions = 1, .time_points = 2, .loads = 1});
ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;

ntn::InitStatus init_frame(void (*edit)(ntn::ModelSpec<kS>&)) {
  spec = {};
  EXPECT_TRUE(ntn_test::portal_frame(spec, kDiv));
  spec.time_points = {{{0, 0}, {1, 1}}};
  spec.time_functions[0] = {0, 2};
  spec.loads[0] = {5, ntn::kUx, 1e3, 0};
  spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(spec)).dt_stable;
  if (edit != nullptr) edit(spec);
  const ntn_test::EigenNoMalloc guard;
  return ntn_test::init_model(spec, model);
}

// The translational mass in each direction is the frame's total mass, sum rho A l over the
// elements, plus point masses (HRZ puts rho A l / 2 on each end): exact up to rounding (1e-13).
TEST(Model, LumpedMassAddsUpToTheTotalMass) {
  ASSERT_TRUE(init_frame([](ntn::ModelSpec<kS>& s) {
                s.nodes[6].added = {500, 500, 500, 10, 20, 30};
              }).ok());
  double total = 500;
  for (const ntn::ElementSpec& e : spec.elements) {
    const ntn::NodeSpec &a = spec.nodes[static_cast<std::size_t>(e.node_i)],
                        &b = spec.nodes[static_cast<std::size_t>(e.node_j)];
    total += e.rho * e.A * std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);
  }
  for (int d = 0; d < 3; ++d) {
    double sum = 0;
    for (std::size_t n = 0; n < kS.nodes; ++n)
      sum += model.mass[dof(n, d)];
    EXPECT_NEAR(sum, total, 1e-13 * total) << "direction " << d;
  }
  EXPECT_GT(model.mass[dof(6, ntn::kRz)], 30.0);  // point inertia added to the element's
}

// Supported DOFs get zero inverse mass (they never move); damping is C = alpha M per DOF, and
// the inverse mass that of the step mass (1 + alpha dt/2) M (damping_velocity = "central").
TEST(Model, SupportsAndDamping) {
  ASSERT_TRUE(init_frame([](ntn::ModelSpec<kS>& s) { s.settings.alpha = 0.7; }).ok());
  EXPECT_EQ(model.mass_factor, 1.0 + 0.7 * (0.5 * model.dt));
  EXPECT_EQ(model.num_supported, 4);
  for (std::size_t n = 0; n < kS.nodes; ++n) {
    for (int d = 0; d < 6; ++d) {
      const std::size_t j = dof(n, d);
      if (n < 4) {
        EXPECT_EQ(model.inv_mass[j], 0.0);
      } else {
        EXPECT_DOUBLE_EQ(model.inv_mass[j] * (model.mass[j] * model.mass_factor), 1.0);
      }
      EXPECT_DOUBLE_EQ(model.damping[j], 0.7 * model.mass[j]);
    }
  }
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(model.supported_nodes[static_cast<std::size_t>(k)], k);
}

TEST(Model, AcceptsTheStableStepAndRefusesAboveIt) {
  ASSERT_TRUE(init_frame(nullptr).ok());
  const double stable = model.stable.dt_stable;
  const int governing = model.stable.governing_element;
  ASSERT_GE(governing, 0);
  EXPECT_TRUE(init_frame([](ntn::ModelSpec<kS>& s) {
                s.settings.dt = ntn::stable_time_step(ntn::view(s)).dt_stable;
              }).ok());
  const ntn::InitStatus above = init_frame([](ntn::ModelSpec<kS>& s) {
    s.settings.dt = 1.001 * ntn::stable_time_step(ntn::view(s)).dt_stable;
  });
  EXPECT_EQ(above.error, ntn::InitError::kTimeStepAboveStable);
  EXPECT_EQ(above.where, governing);  // names the governing element
  EXPECT_TRUE(init_frame([](ntn::ModelSpec<kS>& s) {
                s.settings.dt = 1.5 * ntn::stable_time_step(ntn::view(s)).dt_stable;
                s.settings.allow_unstable = true;
              }).ok());
  EXPECT_DOUBLE_EQ(model.stable.dt_stable, stable);
}

struct BadCase {
  const char* name;
  void (*edit)(ntn::ModelSpec<kS>&);
  ntn::InitError error;
  int where;
};

// Names the case in test listings (CTest shows gtest's parameter printout otherwise).
inline void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class InitErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(InitErrors, ReportsTheErrorAndWhere) {
  const BadCase& c = GetParam();
  const ntn::InitStatus st = init_frame(c.edit);
  EXPECT_EQ(st.error, c.error) << ntn::to_string(st.error);
  EXPECT_EQ(st.where, c.where);
  EXPECT_FALSE(st.ok());
}

INSTANTIATE_TEST_SUITE_P(
    Model, InitErrors,
    ::testing::Values(
        BadCase{"element_node_out_of_range",
                [](ntn::ModelSpec<kS>& s) { s.elements[7].node_j = kS.nodes; },
                ntn::InitError::kBadReference, 7},
        BadCase{"negative_node", [](ntn::ModelSpec<kS>& s) { s.elements[2].node_i = -1; },
                ntn::InitError::kBadReference, 2},
        BadCase{"load_node_out_of_range", [](ntn::ModelSpec<kS>& s) { s.loads[0].node = 99; },
                ntn::InitError::kBadReference, 0},
        BadCase{"load_dof_out_of_range", [](ntn::ModelSpec<kS>& s) { s.loads[0].dof = 6; },
                ntn::InitError::kBadReference, 0},
        BadCase{"load_time_function_out_of_range",
                [](ntn::ModelSpec<kS>& s) { s.loads[0].time_function = 1; },
                ntn::InitError::kBadReference, 0},
        BadCase{"gravity_function_out_of_range",
                [](ntn::ModelSpec<kS>& s) { s.settings.gravity_function = 3; },
                ntn::InitError::kBadReference, -1},
        BadCase{"time_function_past_its_points",
                [](ntn::ModelSpec<kS>& s) {
                  s.time_functions[0] = {1, 2};
                },
                ntn::InitError::kBadTimeFunction, 0},
        BadCase{"time_function_without_points",
                [](ntn::ModelSpec<kS>& s) {
                  s.time_functions[0] = {0, 0};
                },
                ntn::InitError::kBadTimeFunction, 0},
        BadCase{"time_points_not_increasing", [](ntn::ModelSpec<kS>& s) { s.time_points[1].t = 0; },
                ntn::InitError::kBadTimeFunction, 0},
        BadCase{"zero_E", [](ntn::ModelSpec<kS>& s) { s.elements[4].E = 0; },
                ntn::InitError::kBadProperty, 4},
        BadCase{"negative_G", [](ntn::ModelSpec<kS>& s) { s.elements[4].G = -1; },
                ntn::InitError::kBadProperty, 4},
        BadCase{"zero_rho", [](ntn::ModelSpec<kS>& s) { s.elements[5].rho = 0; },
                ntn::InitError::kBadProperty, 5},
        BadCase{"zero_A", [](ntn::ModelSpec<kS>& s) { s.elements[1].A = 0; },
                ntn::InitError::kBadProperty, 1},
        BadCase{"zero_Iy", [](ntn::ModelSpec<kS>& s) { s.elements[1].Iy = 0; },
                ntn::InitError::kBadProperty, 1},
        BadCase{"zero_Iz", [](ntn::ModelSpec<kS>& s) { s.elements[1].Iz = 0; },
                ntn::InitError::kBadProperty, 1},
        BadCase{"zero_J", [](ntn::ModelSpec<kS>& s) { s.elements[1].J = 0; },
                ntn::InitError::kBadProperty, 1},
        BadCase{"nan_E", [](ntn::ModelSpec<kS>& s) { s.elements[3].E = std::nan(""); },
                ntn::InitError::kBadProperty, 3},
        BadCase{"negative_shear_area",
                [](ntn::ModelSpec<kS>& s) { s.elements[3].shear_area_z = -1; },
                ntn::InitError::kBadProperty, 3},
        BadCase{"zero_length",
                [](ntn::ModelSpec<kS>& s) { s.elements[6].node_j = s.elements[6].node_i; },
                ntn::InitError::kZeroLength, 6},
        BadCase{"orientation_parallel",  // a column (along z) with reference z
                [](ntn::ModelSpec<kS>& s) { s.elements[0].ref_x = 0, s.elements[0].ref_z = 1; },
                ntn::InitError::kOrientation, 0},
        BadCase{"massless_node",  // a top node cut loose from its elements, not supported
                [](ntn::ModelSpec<kS>& s) {
                  for (ntn::ElementSpec& e : s.elements) {
                    if (e.node_i == 7) e.node_i = 6;
                    if (e.node_j == 7) e.node_j = 6;
                  }
                  for (ntn::ElementSpec& e : s.elements) {  // drop the now zero-length ones
                    if (e.node_i == e.node_j) e.node_j = e.node_i == 6 ? 5 : 6;
                  }
                },
                ntn::InitError::kMassless, 6 * 7},
        BadCase{"zero_dt", [](ntn::ModelSpec<kS>& s) { s.settings.dt = 0; },
                ntn::InitError::kBadTimeStep, -1},
        BadCase{"nan_dt", [](ntn::ModelSpec<kS>& s) { s.settings.dt = std::nan(""); },
                ntn::InitError::kBadTimeStep, -1}),
    [](const ::testing::TestParamInfo<BadCase>& i) { return std::string(i.param.name); });

TEST(Status, EveryInitErrorHasItsOwnMessage) {
  std::set<std::string> seen;
  for (int e = 0; e <= static_cast<int>(ntn::InitError::kMechanism); ++e) {
    const std::string s = ntn::to_string(static_cast<ntn::InitError>(e));
    EXPECT_FALSE(s.empty());
    EXPECT_NE(s, "unknown");
    EXPECT_TRUE(seen.insert(s).second) << s;
  }
}

}  // namespace model_test
