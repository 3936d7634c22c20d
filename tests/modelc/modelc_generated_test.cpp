// The headers that ntn_add_model generated at build time for config/frame3d.toml (through the
// generic NTN_MODEL_HEADER / NTN_MODEL_NS a main uses), config/cantilever.toml and
// config/hinged_beam.toml: they compile as constexpr, hold exactly what load_model reads from
// the same files (hinges, curves and hinge settings included, bit for bit), and initialize the
// kernel.
#include <gtest/gtest.h>

#include "backbone_portal_model.hpp"
#include "cantilever_model.hpp"
#include "hinged_beam_model.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"
#include "pinned_joint_model.hpp"
#include "slip_connections_model.hpp"
#include "spec_compare.hpp"
#include "support/init_model.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace frame = NTN_MODEL_NS;
namespace cant = ntn::models::cantilever;
namespace hb = ntn::models::hinged_beam;

// Sizes straight from the files: frame3d has 18 nodes, 26 members of 4 divisions (3 interior
// nodes each), 8 beams pinned at their exterior end (a node and a hinge per released end), 1
// input and 9 outputs; the cantilever 2 nodes and 1 member of 20 divisions; hinged_beam 8 nodes, 3
// members of 4 and 1 of 2 divisions, one released end, 3 explicit hinges and a support with
// axes, one curve of 4 points.
static_assert(frame::kSizes.nodes == 18 + 26 * 3 + 8);
static_assert(frame::kSizes.elements == 26 * 4);
static_assert(frame::kSizes.inputs == 1 && frame::kSizes.outputs == 9);
static_assert(frame::kSizes.hinges == 8 && frame::kSizes.curves == 0);
static_assert(frame::kHingeNames[0] == "BX_A1B1_1.start" &&
              frame::kHingeNames[1] == "BX_B1C1_1.end");
static_assert(frame::kSpec.hinges[0].behaviour[ntn::kRy] == ntn::HingeBehaviour::kFree);
static_assert(frame::kSpec.hinges[0].behaviour[ntn::kRx] == ntn::HingeBehaviour::kRigid);
static_assert(hb::kSizes.nodes == 8 + 3 * 3 + 1 + 1 && hb::kSizes.elements == 3 * 4 + 2);
static_assert(hb::kSizes.hinges == 5 && hb::kSizes.curves == 1 && hb::kSizes.curve_points == 4);
static_assert(hb::kHingeNames[0] == "H_spring" && hb::kHingeNames[3] == "P1.end" &&
              hb::kHingeNames[4] == "support.7");
static_assert(hb::kSpec.hinges[4].node2 == ntn::kGround);
static_assert(hb::kSpec.settings.limit_stiffness == 1.0e12);
static_assert(frame::kSizes.loads == 0 && frame::kSizes.time_functions == 0);
static_assert(cant::kSizes.nodes == 21 && cant::kSizes.elements == 20);
static_assert(cant::kSizes.loads == 1 && cant::kSizes.inputs == 0 && cant::kSizes.outputs == 3);
static_assert(frame::kName == "frame3d" && cant::kName == "cantilever");
static_assert(frame::kInputNames[0] == "ag_x");
static_assert(cant::kSpec.loads[0].value == -1000.0);  // constexpr data, usable at compile time
static_assert(frame::kSpec.settings.dt > 0 && frame::kDtAuto);

ntn::Model<frame::kSizes> g_frame;
ntn::Model<cant::kSizes> g_cant;
ntn::Model<hb::kSizes> g_hinged;
ntn::Model<ntn::models::pinned_joint::kSizes> g_pinned;
ntn::Model<ntn::models::backbone_portal::kSizes> g_backbone;
ntn::Model<ntn::models::slip_connections::kSizes> g_slip;

template <ntn::Sizes S, std::size_t M>
void check(const ntn::ModelSpec<S>& spec, std::string_view source,
           const std::array<std::string_view, S.inputs>& inputs,
           const std::array<std::string_view, S.outputs>& outputs,
           const std::array<std::string_view, S.outputs>& units,
           const std::array<std::string_view, M>& members, ntn::Model<S>& model) {
  const auto r = ntn::modelc::load_model(std::string(source));
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  ntn::test::expect_same_spec(spec, *r.model);
  ntn::test::expect_same_names(inputs, r.model->input_names);
  ntn::test::expect_same_names(outputs, r.model->output_names);
  ntn::test::expect_same_names(units, r.model->output_units);
  std::vector<std::string> member_names;
  for (const auto& m : r.model->members)
    member_names.push_back(m.name);
  ntn::test::expect_same_names(members, member_names);

  const ntn::InitStatus st = ntn_test::init_model(spec, model);
  ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  EXPECT_EQ(model.dt, r.model->settings.dt);
  EXPECT_EQ(model.stable.governing_element, r.model->stable.governing_element);
  EXPECT_EQ(model.stable.dt_stable, r.model->stable.dt_stable);
}

TEST(GeneratedHeader, Frame3dMatchesFileAndInitializes) {
  check(frame::kSpec, frame::kSourceFile, frame::kInputNames, frame::kOutputNames,
        frame::kOutputUnits, frame::kMemberNames, g_frame);
}

TEST(GeneratedHeader, HingedBeamMatchesFileAndInitializes) {
  check(hb::kSpec, hb::kSourceFile, hb::kInputNames, hb::kOutputNames, hb::kOutputUnits,
        hb::kMemberNames, g_hinged);
  const auto r = ntn::modelc::load_model(std::string(hb::kSourceFile));
  ASSERT_TRUE(r.ok());
  std::vector<std::string> hinge_names;
  for (const auto& h : r.model->hinge_info)
    hinge_names.push_back(h.name);
  ntn::test::expect_same_names(hb::kHingeNames, hinge_names);
  EXPECT_EQ(g_hinged.stable.governing_hinge, r.model->stable.governing_hinge);
}

// Backbone laws (rule, points, limits) in the header, bit for bit as the file reads at run time.
TEST(GeneratedHeader, BackbonePortalMatchesFileAndInitializes) {
  namespace bp = ntn::models::backbone_portal;
  static_assert(bp::kSizes.hystereses == 2);
  static_assert(bp::kSpec.hystereses[0].rule == ntn::HysteresisRule::kKinematic);
  static_assert(bp::kSpec.hystereses[1].rule == ntn::HysteresisRule::kPeakOriented);
  static_assert(bp::kSpec.hystereses[1].backbone_neg[2].force == 2.0e4);
  check(bp::kSpec, bp::kSourceFile, bp::kInputNames, bp::kOutputNames, bp::kOutputUnits,
        bp::kMemberNames, g_backbone);
}

// The slip connections (friction circle, hardening with the slip, a spring that breaks,
// fixed_if with a control and on its own force) in the header, bit for bit as the file reads.
TEST(GeneratedHeader, SlipConnectionsMatchFileAndInitialize) {
  namespace sc = ntn::models::slip_connections;
  static_assert(sc::kSizes.hystereses == 5);
  static_assert(sc::kSizes.curves == 2);  // "contact" and the stop fixed_if makes
  check(sc::kSpec, sc::kSourceFile, sc::kInputNames, sc::kOutputNames, sc::kOutputUnits,
        sc::kMemberNames, g_slip);
  int brittle = 0, circles = 0, fixed_if = 0;
  for (const auto& h : sc::kSpec.hystereses) {
    brittle += h.rule == ntn::HysteresisRule::kBrittle ? 1 : 0;
    circles += h.circle >= 0 ? 1 : 0;
    fixed_if += h.fixed_if != 0 ? 1 : 0;
  }
  EXPECT_EQ(brittle, 1);
  EXPECT_EQ(circles, 2);
  EXPECT_EQ(fixed_if, 1);
}

// The compiler's mechanisms are the DOFs the kernel holds at zero (DESIGN §7.1): the pinned
// joint's rotation about z, nothing else.
TEST(GeneratedHeader, MechanismIsWhatTheKernelHolds) {
  namespace pj = ntn::models::pinned_joint;
  const auto r = ntn::modelc::load_model(std::string(pj::kSourceFile));
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  ntn::test::expect_same_spec(pj::kSpec, *r.model);
  const ntn::InitStatus st = ntn_test::init_model(pj::kSpec, g_pinned);
  ASSERT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  int compiler_dofs = 0;
  std::vector<std::uint8_t> bits(pj::kSizes.nodes, 0);
  for (const auto& m : r.model->mechanisms) {
    bits[static_cast<std::size_t>(m.node)] = m.dofs;
    for (int d = 0; d < 6; ++d)
      compiler_dofs += (m.dofs >> d) & 1;
  }
  EXPECT_EQ(compiler_dofs, 1);
  EXPECT_EQ(g_pinned.held_dofs, compiler_dofs);
  for (std::size_t n = 0; n < pj::kSizes.nodes; ++n)
    EXPECT_EQ(g_pinned.held[n], bits[n]) << "node " << n;
}

TEST(GeneratedHeader, CantileverMatchesFileAndInitializes) {
  check(cant::kSpec, cant::kSourceFile, cant::kInputNames, cant::kOutputNames, cant::kOutputUnits,
        cant::kMemberNames, g_cant);
}

// The alarm tables beside the output names hold the [[outputs]] alarm keys bit for bit (limit 0
// where a channel has none); the kernel's ModelSpec does not carry them.
template <std::size_t N>
void expect_same_alarms(std::string_view source, const std::array<double, N>& limits,
                        const std::array<double, N>& hysteresis) {
  const auto r = ntn::modelc::load_model(std::string(source));
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  ASSERT_EQ(r.model->output_alarms.size(), N);
  for (std::size_t c = 0; c < N; ++c) {
    ntn::test::expect_bits(limits[c], r.model->output_alarms[c].limit, "alarm limit", c);
    ntn::test::expect_bits(hysteresis[c], r.model->output_alarms[c].hysteresis, "hysteresis", c);
  }
}

TEST(GeneratedHeader, AlarmTablesMatchFile) {
  expect_same_alarms(frame::kSourceFile, frame::kAlarmLimits, frame::kAlarmHysteresis);
  expect_same_alarms(cant::kSourceFile, cant::kAlarmLimits, cant::kAlarmHysteresis);
  expect_same_alarms(hb::kSourceFile, hb::kAlarmLimits, hb::kAlarmHysteresis);
  // frame3d has alarms (its storey drifts), so the comparison covered non-zero entries.
  int with_alarm = 0;
  for (double limit : frame::kAlarmLimits)
    with_alarm += limit > 0 ? 1 : 0;
  EXPECT_GT(with_alarm, 0);
}

}  // namespace
