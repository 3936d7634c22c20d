// The model compiler on plastic hinge directions: { plastic = k, yield = F,
// yield_negative = F, hardening = b, dashpot = c } in releases and explicit hinges, each with a
// history slot of its own (ntn::HysteresisSpec), the new output kinds, the modal analysis and
// stable step at the elastic stiffness, and every error with its place.
#include <gtest/gtest.h>

#include <string>

#include "ntn/hysteresis.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"

namespace modelc_plastic_test {

using ntn::HingeBehaviour;
using ntn::modelc::format_all;
using ntn::modelc::load_model_from_string;

// A cantilever column (3 m, 3 elements) whose base is a plastic hinge to the ground (an
// explicit hinge from node 1, fixed in nothing, to the ground) and whose top has a beam stub
// with a plastic release about y. %BASE% and %STUB% are the two plastic directions' tables.
std::string model(const std::string& base, const std::string& stub, const std::string& more = "") {
  std::string t = R"([model]
name = "m"

[[materials]]
id = "S"
E = 210e9
nu = 0.3
rho = 7850

[[sections]]
id = "H"
A = 1e-2
Iy = 1e-4
Iz = 5e-5
J = 1e-6

[[nodes]]
id = 1
xyz = [0, 0, 0]

[[nodes]]
id = 2
xyz = [0, 0, 3]

[[nodes]]
id = 3
xyz = [2, 0, 3]

[[members]]
id = "C"
nodes = [1, 2]
material = "S"
section = "H"
divisions = 3

[[members]]
id = "B"
nodes = [2, 3]
material = "S"
section = "H"
release_start = { ry = %STUB% }

[[hinges]]
id = "base"
nodes = [1, "ground"]
ry = %BASE%
)";
  t.replace(t.find("%STUB%"), 6, stub);
  t.replace(t.find("%BASE%"), 6, base);
  return t + more;
}

TEST(ModelcPlastic, DirectionsGetTheirLawsAndHistorySlots) {
  const auto r = load_model_from_string(
      model("{ plastic = 1e9, yield = 2e5, hardening = 0.05 }",
            "{ plastic = 5e8, yield = 1e5, yield_negative = 8e4, dashpot = 10 }",
            R"(
[[outputs]]
name = "base_dp"
kind = "hinge_plastic_deformation"
hinge = "base"
direction = "ry"

[[outputs]]
name = "stub_energy"
kind = "hinge_dissipated_energy"
hinge = "B.start"
direction = "ry"
)"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  ASSERT_EQ(d.hystereses.size(), 2U);
  ASSERT_EQ(d.sizes().hystereses, 2U);
  const ntn::HingeSpec& base = d.hinges[0];  // explicit hinges first
  const ntn::HingeSpec& stub = d.hinges[1];
  EXPECT_EQ(base.behaviour[4], HingeBehaviour::kPlastic);
  EXPECT_EQ(base.stiffness[4], 1e9);
  EXPECT_EQ(base.hysteresis[4], 0);
  EXPECT_EQ(d.hystereses[0].yield_pos, 2e5);
  EXPECT_EQ(d.hystereses[0].yield_neg, 2e5);  // symmetric unless yield_negative is given
  EXPECT_EQ(d.hystereses[0].hardening, 0.05);
  EXPECT_EQ(stub.behaviour[4], HingeBehaviour::kPlastic);
  EXPECT_EQ(stub.stiffness[4], 5e8);
  EXPECT_EQ(stub.dashpot[4], 10.0);
  EXPECT_EQ(stub.hysteresis[4], 1);
  EXPECT_EQ(d.hystereses[1].yield_neg, 8e4);
  EXPECT_EQ(d.hystereses[1].hardening, 0.0);
  EXPECT_EQ(d.outputs[0].kind, ntn::OutputKind::kHingePlastic);
  EXPECT_EQ(d.outputs[1].kind, ntn::OutputKind::kHingeDissipated);
  EXPECT_EQ(d.output_units[0], "rad");
  EXPECT_EQ(d.output_units[1], "J");
  // The stable step takes the elastic stiffness, the largest tangent a bilinear law reaches
  // (hardening < 1): the same step as the same model with linear directions of that k.
  const auto lin =
      load_model_from_string(model("{ linear = 1e9 }", "{ linear = 5e8, dashpot = 10 }"), "m.toml");
  ASSERT_TRUE(lin.ok()) << format_all(lin.errors);
  EXPECT_EQ(d.stable.dt_stable, lin.model->stable.dt_stable);
  // Modal analysis below yield: the elastic stiffness, the same modes, and a note saying so.
  ntn::modal::ModalOptions o;
  o.modes = 3;
  const auto mp = ntn::modal::modal_analysis(d.view(), o);
  const auto ml = ntn::modal::modal_analysis(lin.model->view(), o);
  ASSERT_TRUE(mp.ok() && ml.ok()) << mp.error << ml.error;
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(mp.frequency(i), ml.frequency(i));
  bool noted = false;
  for (const std::string& n : mp.notes)
    noted = noted || n.find("plastic hinge directions at their elastic stiffness") == 0;
  EXPECT_TRUE(noted);
}

// A backbone (ASCE 41 points B, C, D, E) with its rule: k = f_B / d_B, the points into the law
// as given (the negative sense: the same unless given; its B put on the elastic line exactly),
// the stable step and the modes at k like a linear direction of that k.
TEST(ModelcPlastic, BackbonesGetTheirPointsRuleAndElasticStiffness) {
  const auto r = load_model_from_string(
      model("{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]], rule = "
            "\"kinematic\", io = 0.005, ls = 0.02, cp = 0.03 }",
            "{ backbone = [[0.001, 1e5], [0.02, 1.1e5], [0.025, 2e4], [0.04, 2e4]], "
            "backbone_negative = [[0.0008, 8.00000001e4], [0.01, 9e4], [0.01, 1e4], [0.03, 0]], "
            "rule = \"peak_oriented\" }"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  ASSERT_EQ(d.hystereses.size(), 2U);
  const ntn::HysteresisSpec& base = d.hystereses[0];
  const ntn::HysteresisSpec& stub = d.hystereses[1];
  EXPECT_EQ(base.rule, ntn::HysteresisRule::kKinematic);
  EXPECT_EQ(stub.rule, ntn::HysteresisRule::kPeakOriented);
  EXPECT_EQ(d.hinges[0].stiffness[4], 2e5 / 0.002);
  EXPECT_EQ(d.hinges[1].stiffness[4], 1e5 / 0.001);
  EXPECT_EQ(base.backbone_pos[1].d, 0.03);
  EXPECT_EQ(base.backbone_pos[2].force, 4e4);
  EXPECT_EQ(base.backbone_neg[3].d, 0.05);  // symmetric unless backbone_negative is given
  EXPECT_EQ(base.yield_pos, 2e5);
  EXPECT_EQ(stub.yield_neg, 8.00000001e4);
  EXPECT_EQ(stub.backbone_neg[0].d, 8.00000001e4 / 1e8);  // on the elastic line, exactly
  EXPECT_EQ(stub.backbone_neg[3].force, 0.0);
  EXPECT_EQ(base.limits, (std::array<double, 3>{0.005, 0.02, 0.03}));
  EXPECT_TRUE(ntn::hysteresis_valid(base, d.hinges[0].stiffness[4], 0.0));
  EXPECT_TRUE(ntn::hysteresis_valid(stub, d.hinges[1].stiffness[4], 0.0));
  const auto lin = load_model_from_string(model("{ linear = 1e8 }", "{ linear = 1e8 }"), "m.toml");
  ASSERT_TRUE(lin.ok()) << format_all(lin.errors);
  EXPECT_EQ(d.stable.dt_stable, lin.model->stable.dt_stable);
  EXPECT_NE(ntn::modelc::info_text(d).find("2 hysteretic directions (1 backbone kinematic, 1 "
                                           "backbone peak_oriented), yield 8e+04 to 2e+05"),
            std::string::npos)
      << ntn::modelc::info_text(d);
}

// rigid_plastic: a history slot with its yields; under ntn_exact rigid below yield
// (the stable step and the modes as a rigid direction's), refused under ntn_paper at the key.
TEST(ModelcPlastic, RigidPlasticDirectionsGetTheirYieldsAndSlots) {
  const auto r = load_model_from_string(
      model("{ rigid_plastic = 2e5, yield_negative = 1e5, io = 0.01, ls = 0.02, cp = 0.04 }",
            "{ plastic = 5e8, yield = 1e5 }",
            "\n[[outputs]]\nname = \"slip\"\nkind = \"hinge_plastic_deformation\"\nhinge = "
            "\"base\"\ndirection = \"ry\"\n"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  EXPECT_EQ(d.hinges[0].behaviour[4], HingeBehaviour::kRigidPlastic);
  EXPECT_EQ(d.hinges[0].hysteresis[4], 0);
  EXPECT_EQ(d.hystereses[0].yield_pos, 2e5);
  EXPECT_EQ(d.hystereses[0].yield_neg, 1e5);
  EXPECT_EQ(d.hystereses[0].rule, ntn::HysteresisRule::kBilinear);
  EXPECT_EQ(d.outputs[0].kind, ntn::OutputKind::kHingePlastic);
  const auto rigid =
      load_model_from_string(model("\"rigid\"", "{ plastic = 5e8, yield = 1e5 }"), "m.toml");
  ASSERT_TRUE(rigid.ok()) << format_all(rigid.errors);
  EXPECT_EQ(d.stable.dt_stable, rigid.model->stable.dt_stable);
  std::string paper = model("{ rigid_plastic = 2e5 }", "{ plastic = 5e8, yield = 1e5 }");
  paper.replace(paper.find("name = \"m\""), 10, "name = \"m\"\nhinge_method = \"ntn_paper\"");
  const auto p = load_model_from_string(paper, "m.toml");
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(format_all(p.errors),
            "m.toml:47:6: error: key 'hinges[0].ry': a rigid_plastic direction needs hinge_method "
            "= \"ntn_exact\" (exact stick and slip) or \"penalty\" (an elasto-plastic penalty "
            "spring): the seed's algorithm (\"ntn_paper\") gives no constraint force to test "
            "against the limit\n");
}

// friction: mu, cohesion and the normal direction into the law (default normal ux).
TEST(ModelcPlastic, FrictionDirectionsGetMuCohesionAndNormal) {
  const auto r = load_model_from_string(
      model("{ friction = 0.4, cohesion = 50, normal = \"uz\" }", "{ plastic = 5e8, yield = 1e5 }"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  EXPECT_EQ(d.hinges[0].behaviour[4], HingeBehaviour::kRigidPlastic);
  EXPECT_EQ(d.hystereses[0].normal, 2);
  EXPECT_EQ(d.hystereses[0].mu, 0.4);
  EXPECT_EQ(d.hystereses[0].cohesion, 50.0);
  EXPECT_TRUE(ntn::hysteresis_valid(d.hystereses[0], 0.0, 0.0));
}

// failure: a bolt's limit, rigid until then (a brittle law); under penalty the
// penalty spring breaks; { linear = k, failure = F } a spring that breaks, under every method.
TEST(ModelcPlastic, FailureDirectionsGetTheirLimit) {
  const auto r = load_model_from_string(
      model("{ failure = 3e4 }", "{ plastic = 5e8, yield = 1e5 }"), "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  EXPECT_EQ(d.hinges[0].behaviour[4], HingeBehaviour::kRigidPlastic);
  EXPECT_EQ(d.hystereses[0].rule, ntn::HysteresisRule::kBrittle);
  EXPECT_EQ(d.hystereses[0].yield_pos, 3e4);
  EXPECT_EQ(d.hystereses[0].yield_neg, 3e4);
  std::string penalty = model("{ failure = 3e4 }", "{ plastic = 5e8, yield = 1e5 }");
  penalty.replace(penalty.find("name = \"m\""), 10, "name = \"m\"\nhinge_method = \"penalty\"");
  const auto p = load_model_from_string(penalty, "m.toml");
  ASSERT_TRUE(p.ok()) << format_all(p.errors);
  std::string paper = model("{ linear = 2e6, failure = 3e4 }", "{ plastic = 5e8, yield = 1e5 }");
  paper.replace(paper.find("name = \"m\""), 10, "name = \"m\"\nhinge_method = \"ntn_paper\"");
  const auto q = load_model_from_string(paper, "m.toml");
  ASSERT_TRUE(q.ok()) << format_all(q.errors);
  EXPECT_EQ(q.model->hinges[0].behaviour[4], HingeBehaviour::kPlastic);
  EXPECT_EQ(q.model->hinges[0].stiffness[4], 2e6);
  EXPECT_EQ(q.model->hystereses[0].rule, ntn::HysteresisRule::kBrittle);
  EXPECT_TRUE(ntn::hysteresis_valid(q.model->hystereses[0], 2e6, 0.0));
}

// hardening_stiffness: rigid_plastic's hardening with the slip, the direction's stiffness.
TEST(ModelcPlastic, RigidPlasticHardeningIsTheDirectionsStiffness) {
  const auto r = load_model_from_string(
      model("{ rigid_plastic = 3e4, hardening_stiffness = 2e5 }", "{ plastic = 5e8, yield = 1e5 }"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  EXPECT_EQ(r.model->hinges[0].behaviour[4], HingeBehaviour::kRigidPlastic);
  EXPECT_EQ(r.model->hinges[0].stiffness[4], 2e5);
  EXPECT_EQ(r.model->hystereses[0].hardening, 0.0);
}

// fixed_if: on its own force a stop at d = 0 (the curve the compiler makes, rigid on
// the side of the sign); with another direction as its control a slip direction held while
// that direction's force has the sign. The slip-state and hinge-velocity channels.
TEST(ModelcPlastic, FixedIfIsAStopOnItsOwnForceAndASlipDirectionOnAnother) {
  const auto r = load_model_from_string(
      model("{ fixed_if = \"negative\", control = \"uz\" }\nux = { fixed_if = \"positive\" }",
            "{ plastic = 5e8, yield = 1e5 }",
            R"(
[[outputs]]
name = "state"
kind = "hinge_slip_state"
hinge = "base"
direction = "ry"

[[outputs]]
name = "slip_velocity"
kind = "hinge_velocity"
hinge = "base"
direction = "ry"
)"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  const ntn::HingeSpec& base = d.hinges[0];
  EXPECT_EQ(base.behaviour[4], HingeBehaviour::kRigidPlastic);
  const auto& law = d.hystereses[static_cast<std::size_t>(base.hysteresis[4])];
  EXPECT_EQ(law.fixed_if, -1);
  EXPECT_EQ(law.normal, 2);
  EXPECT_TRUE(ntn::hysteresis_valid(law, 0.0, 0.0));
  ASSERT_EQ(base.behaviour[0], HingeBehaviour::kCurve);  // fixed if positive: a stop on d > 0
  const ntn::CurveSpec& c = d.curves[static_cast<std::size_t>(base.curve[0])];
  ASSERT_EQ(c.count, 3);
  const ntn::CurveBranches b =
      ntn::curve_branches(d.curve_points, c, ntn::branch_slope_limit(d.settings, 0));
  ASSERT_TRUE(b.valid);
  EXPECT_EQ(b.lower, -1e300);  // free for d < 0
  EXPECT_EQ(b.upper, 0.0);     // held at d = 0 against d > 0
  EXPECT_EQ(d.outputs[0].kind, ntn::OutputKind::kHingeSlipState);
  EXPECT_EQ(d.outputs[1].kind, ntn::OutputKind::kHingeVelocity);
  EXPECT_EQ(d.output_units[1], "rad/s");
  EXPECT_NE(ntn::modelc::info_text(d).find(
                "2 hysteretic directions (1 plastic (bilinear, kinematic hardening), 1 fixed_if)"),
            std::string::npos)
      << ntn::modelc::info_text(d);
}

// The friction circle: the pair's laws name each other.
TEST(ModelcPlastic, FrictionCircleDirectionsNameEachOther) {
  const auto r = load_model_from_string(
      model("{ friction = 0.3, normal = \"uz\", circle = \"rx\" }\nrx = { friction = 0.3, "
            "normal = \"uz\" }",
            "{ plastic = 5e8, yield = 1e5 }"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& d = *r.model;
  const ntn::HingeSpec& base = d.hinges[0];
  const auto& ry = d.hystereses[static_cast<std::size_t>(base.hysteresis[4])];
  const auto& rx = d.hystereses[static_cast<std::size_t>(base.hysteresis[3])];
  EXPECT_EQ(ry.circle, 3);
  EXPECT_EQ(rx.circle, 4);
  EXPECT_TRUE(ntn::hysteresis_valid(ry, 0.0, 0.0));
}

// Acceptance limits io, ls, cp: into the law, and the levels they grade (performance_level:
// 0 no plastic deformation, 1 within IO, 2 within LS, 3 within CP, 4 beyond).
TEST(ModelcPlastic, AcceptanceLimitsGradeThePeakPlasticDeformation) {
  const auto r = load_model_from_string(
      model("{ plastic = 1e9, yield = 2e5, io = 0.005, ls = 0.02, cp = 0.03 }",
            "{ plastic = 5e8, yield = 1e5 }",
            "\n[[outputs]]\nname = \"lvl\"\nkind = \"hinge_performance_level\"\nhinge = "
            "\"base\"\ndirection = \"ry\"\n"),
      "m.toml");
  ASSERT_TRUE(r.ok()) << format_all(r.errors);
  const auto& law = r.model->hystereses[0];
  EXPECT_EQ(law.limits, (std::array<double, 3>{0.005, 0.02, 0.03}));
  EXPECT_EQ(r.model->hystereses[1].limits, (std::array<double, 3>{}));
  EXPECT_EQ(r.model->outputs[0].kind, ntn::OutputKind::kHingeLevel);
  EXPECT_EQ(r.model->output_units[0], "-");
  EXPECT_TRUE(ntn::hysteresis_valid(law, 1e9, 0.0));
  const std::array<double, 3> lim = law.limits;
  EXPECT_EQ(ntn::performance_level(lim, 0.0), 0);
  EXPECT_EQ(ntn::performance_level(lim, 1e-9), 1);
  EXPECT_EQ(ntn::performance_level(lim, 0.005), 1);  // at a limit: still within it
  EXPECT_EQ(ntn::performance_level(lim, 0.0051), 2);
  EXPECT_EQ(ntn::performance_level(lim, 0.025), 3);
  EXPECT_EQ(ntn::performance_level(lim, 0.04), 4);
  EXPECT_EQ(ntn::performance_level({}, 0.04), 1);  // no limits: yielded or not
  // ntn-model info counts them: the yields' range, how many have limits.
  EXPECT_NE(
      ntn::modelc::info_text(*r.model).find(
          "plastic      2 hysteretic directions (2 plastic (bilinear, kinematic hardening)), yield "
          "1e+05 to 2e+05 N or N m, 1 with IO/LS/CP limits"),
      std::string::npos)
      << ntn::modelc::info_text(*r.model);
  ntn::HysteresisSpec bad = law;
  bad.limits = {0.02, 0.005, 0.03};
  EXPECT_FALSE(
      ntn::hysteresis_valid(bad, 1e9, 0.0));  // the kernel refuses what the compiler refuses
}

// A plastic direction far stiffer than the members it joins sets the stable step: a note at the
// direction says so and by how much (the model still loads); a moderate one gives no note.
TEST(ModelcPlastic, AStiffPlasticDirectionThatSetsTheStepIsNoted) {
  const auto stiff = load_model_from_string(
      model("{ plastic = 1e13, yield = 2e5 }", "{ plastic = 5e8, yield = 1e5 }"), "m.toml");
  ASSERT_TRUE(stiff.ok()) << format_all(stiff.errors);
  const std::string notes = format_all(stiff.notes);
  EXPECT_NE(notes.find("m.toml:46:6: note: key 'hinges[0].ry': the elastic stiffness of this "
                       "plastic direction (k = 1e+13 N m/rad) sets the stable step"),
            std::string::npos)
      << notes;
  EXPECT_LE(stiff.model->stable.dt_stable, 0.5 * stiff.model->stable.dt_elements);
  const auto soft = load_model_from_string(
      model("{ plastic = 1e7, yield = 2e5 }", "{ plastic = 1e7, yield = 1e5 }"), "m.toml");
  ASSERT_TRUE(soft.ok()) << format_all(soft.errors);
  EXPECT_EQ(format_all(soft.notes).find("sets the stable step"), std::string::npos);
}

struct BadCase {
  const char* name;
  std::string base, stub, more;
  std::string error;  // the one error's text after "m.toml:"
};

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class ModelcPlasticBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(ModelcPlasticBad, IsRefusedAtItsKey) {
  const BadCase& c = GetParam();
  const auto r = load_model_from_string(model(c.base, c.stub, c.more), "m.toml");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(format_all(r.errors), "m.toml:" + c.error + "\n");
}

const std::string kOk = "{ plastic = 1e9, yield = 2e5 }";

INSTANTIATE_TEST_SUITE_P(
    Errors, ModelcPlasticBad,
    ::testing::Values(
        BadCase{"ZeroStiffness", "{ plastic = 0, yield = 2e5 }", kOk, "",
                "46:18: error: key 'hinges[0].ry.plastic': must be positive (got 0)"},
        BadCase{"ZeroYield", "{ plastic = 1e9, yield = 0 }", kOk, "",
                "46:31: error: key 'hinges[0].ry.yield': must be positive (got 0)"},
        BadCase{"MissingYield", "{ plastic = 1e9 }", kOk, "",
                "46:6: error: key 'hinges[0].ry.yield': missing required key 'yield'"},
        BadCase{"NegativeYieldNegative", kOk, "{ plastic = 1e9, yield = 2e5, yield_negative = -1 }",
                "",
                "41:71: error: key 'members[1].release_start.ry.yield_negative': must be "
                "positive (got -1)"},
        BadCase{"HardeningOne", "{ plastic = 1e9, yield = 2e5, hardening = 1.0 }", kOk, "",
                "46:48: error: key 'hinges[0].ry.hardening': must be at least 0 and less than 1: "
                "the tangent after yield is hardening x k (got 1)"},
        BadCase{"YieldWithoutPlastic", "{ linear = 1e9, yield = 2e5 }", kOk, "",
                "46:30: error: key 'hinges[0].ry.yield': only applies with 'plastic' or 'imk'"},
        BadCase{"LinearAndPlastic", "{ linear = 1e9, plastic = 1e9, yield = 2e5 }", kOk, "",
                "46:32: error: key 'hinges[0].ry.plastic': cannot be given together with "
                "'linear'"},
        BadCase{"HistoryOfANonPlasticDirection", kOk, kOk,
                "\n[[outputs]]\nname = \"x\"\nkind = \"hinge_plastic_deformation\"\nhinge = "
                "\"base\"\ndirection = \"rx\"\n",
                "52:13: error: key 'outputs[0].direction': direction rx of hinge base is not "
                "plastic: it has no plastic deformation or dissipated energy (give it { plastic "
                "= k, yield = F })"},
        BadCase{"LimitsIncomplete", "{ plastic = 1e9, yield = 2e5, io = 0.01, cp = 0.03 }", kOk, "",
                "46:6: error: key 'hinges[0].ry.ls': missing: give all three acceptance "
                "limits io, ls and cp, or none"},
        BadCase{"LimitsDecrease",
                "{ plastic = 1e9, yield = 2e5, io = 0.01, ls = 0.005, cp = 0.03 }", kOk, "",
                "46:52: error: key 'hinges[0].ry.ls': ls = 0.005 is below io = 0.01: the "
                "limits must not decrease (io <= ls <= cp)"},
        BadCase{"BackboneOutOfOrder",
                "{ backbone = [[0.002, 2e5], [0.001, 2.2e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\" }",
                kOk, "",
                "46:34: error: key 'hinges[0].ry.backbone[1]': points out of order: C "
                "(capping) at deformation 0.001 must lie beyond B (yield) at 0.002"},
        BadCase{"BackboneDBeforeC",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.02, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\" }",
                kOk, "",
                "46:49: error: key 'hinges[0].ry.backbone[2]': points out of order: D "
                "(residual) at deformation 0.02 must not lie before C (capping) at 0.03 (equal "
                "deformations: a vertical drop)"},
        BadCase{"BackboneCappingBelowYield",
                "{ backbone = [[0.002, 2e5], [0.03, 1.9e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\" }",
                kOk, "",
                "46:34: error: key 'hinges[0].ry.backbone[1]': point C (capping) has force "
                "190000, below the yield force 200000 at B: the capping strength is the "
                "envelope's largest"},
        BadCase{"BackboneResidualAboveCapping",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 3e5], [0.05, 4e4]], rule = "
                "\"kinematic\" }",
                kOk, "",
                "46:49: error: key 'hinges[0].ry.backbone[2]': point D (residual) has force "
                "300000: the residual strength must lie between 0 and the capping strength "
                "220000 at C"},
        BadCase{"BackboneSteeperThanK",
                "{ backbone = [[0.002, 2e5], [0.003, 3.5e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\" }",
                kOk, "",
                "46:34: error: key 'hinges[0].ry.backbone[1]': the segment from B (yield) to C "
                "(capping) rises at 1.5e+08, not below the elastic stiffness k = 1e+08: a "
                "backbone hardens less steeply than it loads elastically"},
        BadCase{"BackboneThreePoints",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.05, 4e4]], rule = \"kinematic\" }",
                kOk, "",
                "46:19: error: key 'hinges[0].ry.backbone': expected the 4 points B, C, D, E "
                "of an ASCE 41 backbone as [deformation, force] pairs (A is the origin), got 3 "
                "points"},
        BadCase{"BackboneNegativeForce",
                "{ backbone = [[0.002, 2e5], [0.03, -2.2e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\" }",
                kOk, "",
                "46:41: error: key 'hinges[0].ry.backbone[1][1]': must not be negative (got "
                "-220000)"},
        BadCase{"BackboneWithoutRule",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]] }", kOk, "",
                "46:6: error: key 'hinges[0].ry.rule': missing required key 'rule'"},
        BadCase{"BackboneUnknownRule",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"isotropic\" }",
                kOk, "",
                "46:83: error: key 'hinges[0].ry.rule': must be one of \"kinematic\", "
                "\"peak_oriented\" (got \"isotropic\")"},
        BadCase{"BackboneDashpot",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\", dashpot = 10 }",
                kOk, "",
                "46:106: error: key 'hinges[0].ry.dashpot': a backbone direction takes no "
                "dashpot: its force must be able to drop to zero (damp the frame with "
                "[model.damping])"},
        BadCase{"BackboneCpBeyondE",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]], rule = "
                "\"kinematic\", io = 0.01, ls = 0.03, cp = 0.05 }",
                kOk, "",
                "46:123: error: key 'hinges[0].ry.cp': cp = 0.05 lies beyond the backbone's "
                "last point: the plastic deformation at E in the positive sense is d_E - f_E / "
                "k = 0.0496"},
        BadCase{"BackboneNegativeOffElastic",
                "{ backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]], "
                "backbone_negative = [[0.001, 2e5], [0.03, 2.2e5], [0.03, 4e4], [0.05, 4e4]], rule "
                "= \"kinematic\" }",
                kOk, "",
                "46:97: error: key 'hinges[0].ry.backbone_negative[0]': point B (yield) "
                "[0.001, 200000] is not on the elastic line of the positive sense (k = 1e+08): "
                "both senses unload at the same k; give its deformation as force / k = 0.002"},
        BadCase{"RuleWithoutBackbone", "{ plastic = 1e9, yield = 2e5, rule = \"kinematic\" }", kOk,
                "", "46:43: error: key 'hinges[0].ry.rule': only applies with 'backbone'"},
        BadCase{"RigidPlasticZero", "{ rigid_plastic = 0 }", kOk, "",
                "46:24: error: key 'hinges[0].ry.rigid_plastic': must be positive (got "
                "0)"},
        BadCase{"RigidPlasticDashpot", "{ rigid_plastic = 1e5, dashpot = 3 }", kOk, "",
                "46:39: error: key 'hinges[0].ry.dashpot': a rigid_plastic direction "
                "takes no dashpot: it is rigid while it sticks"},
        BadCase{"HardeningWithRigidPlastic", "{ rigid_plastic = 1e5, hardening = 0.1 }", kOk, "",

                "46:41: error: key 'hinges[0].ry.hardening': only applies with "
                "'plastic'"},
        BadCase{"FrictionNormalIsItself", "{ friction = 0.3, normal = \"ry\" }", kOk, "",
                "46:33: error: key 'hinges[0].ry.normal': the normal of a friction "
                "direction must be another direction of the hinge that does not slide "
                "itself and is not a stop (rigid, a spring or a curve without rigid branches): "
                "it is this direction"},
        BadCase{"FrictionNegativeMu", "{ friction = -0.3, normal = \"uz\" }", kOk, "",
                "46:19: error: key 'hinges[0].ry.friction': must not be negative (got "
                "-0.3)"},
        BadCase{"CohesionWithoutFriction", "{ rigid_plastic = 1e5, cohesion = 3 }", kOk, "",
                "46:40: error: key 'hinges[0].ry.cohesion': only applies with "
                "'friction'"},
        BadCase{"FixedIfControlSlides",
                "{ fixed_if = \"negative\", control = \"uz\" }\nuz = { rigid_plastic = 1e4 }", kOk,
                "",
                "46:41: error: key 'hinges[0].ry.control': the control of a fixed_if direction "
                "must be another direction of the hinge that does not slide itself and is not a "
                "stop (rigid, a spring or a curve without rigid branches): it slides"},
        BadCase{"FrictionNormalIsAStop",
                "{ friction = 0.3, normal = \"uz\" }\nuz = { fixed_if = \"negative\" }", kOk, "",
                "46:33: error: key 'hinges[0].ry.normal': the normal of a friction direction "
                "must be another direction of the hinge that does not slide itself and is not a "
                "stop (rigid, a spring or a curve without rigid branches): it is a stop, whose "
                "force comes after the slip stage"},
        BadCase{"FixedIfUnknownSign", "{ fixed_if = \"compression\" }", kOk, "",
                "46:19: error: key 'hinges[0].ry.fixed_if': must be one of \"negative\", "
                "\"positive\" (got \"compression\")"},
        BadCase{"ControlWithoutFixedIf", "{ rigid_plastic = 1e5, control = \"uz\" }", kOk, "",
                "46:39: error: key 'hinges[0].ry.control': only applies with 'fixed_if'"},
        BadCase{"HardeningStiffnessWithPlastic",
                "{ plastic = 1e9, yield = 2e5, hardening_stiffness = 1e3 }", kOk, "",
                "46:58: error: key 'hinges[0].ry.hardening_stiffness': only applies with "
                "'rigid_plastic'"},
        BadCase{"FailureSpringDashpot", "{ linear = 1e6, failure = 1e3, dashpot = 2 }", kOk, "",
                "46:47: error: key 'hinges[0].ry.dashpot': a failure direction takes no dashpot: "
                "its force must drop to zero when it breaks"},
        BadCase{"SlipStateOfAPlasticDirection", "{ plastic = 1e9, yield = 2e5 }", kOk,
                "\n[[outputs]]\nname = \"s\"\nkind = \"hinge_slip_state\"\nhinge = \"base\"\n"
                "direction = \"ry\"\n",
                "52:13: error: key 'outputs[0].direction': direction ry of hinge base does not "
                "stick or slip: a hinge_slip_state channel needs a rigid_plastic, friction, "
                "fixed_if or failure direction"},
        BadCase{"CircleIsItself", "{ friction = 0.3, normal = \"uz\", circle = \"ry\" }", kOk, "",
                "46:48: error: key 'hinges[0].ry.circle': the circle of a friction direction must "
                "be another friction direction of the hinge with the same friction, cohesion and "
                "normal (the two share one limit on their resultant): it is this direction"},
        BadCase{"CircleNotFriction", "{ friction = 0.3, normal = \"uz\", circle = \"rx\" }", kOk,
                "",
                "46:48: error: key 'hinges[0].ry.circle': the circle of a friction direction must "
                "be another friction direction of the hinge with the same friction, cohesion and "
                "normal (the two share one limit on their resultant): it is not a friction "
                "direction"},
        BadCase{"CircleOtherMu",
                "{ friction = 0.3, normal = \"uz\", circle = \"rx\" }\nrx = { friction = 0.4, "
                "normal = \"uz\" }",
                kOk, "",
                "46:48: error: key 'hinges[0].ry.circle': the circle of a friction direction must "
                "be another friction direction of the hinge with the same friction, cohesion and "
                "normal (the two share one limit on their resultant): its friction, cohesion or "
                "normal differ from this direction's"},
        BadCase{"CircleTranslationAndRotation",
                "{ friction = 0.3, normal = \"uz\", circle = \"ux\" }\nux = { friction = 0.3, "
                "normal = \"uz\" }",
                kOk, "",
                "46:48: error: key 'hinges[0].ry.circle': the circle of a friction direction must "
                "be another friction direction of the hinge with the same friction, cohesion and "
                "normal (the two share one limit on their resultant): it is a translation and "
                "this a rotation"},
        BadCase{"CircleWithoutFriction", "{ rigid_plastic = 1e5, circle = \"rx\" }", kOk, "",
                "46:38: error: key 'hinges[0].ry.circle': only applies with 'friction'"},
        BadCase{"BackboneAndPlastic",
                "{ plastic = 1e9, yield = 2e5, backbone = [[0.002, 2e5], [0.03, 2.2e5], [0.03, "
                "4e4], [0.05, 4e4]] }",
                kOk, "",
                "46:47: error: key 'hinges[0].ry.backbone': cannot be given together with "
                "'plastic'"}),
    [](const ::testing::TestParamInfo<BadCase>& i) { return std::string(i.param.name); });

}  // namespace modelc_plastic_test
