// The model compiler on good models: meshing, orientation, materials, masses, time step,
// channels and the header text. Truth comes from closed forms (isotropic G, member length / N,
// rho A l), the kernel's own geometry, or the same model written another way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ntn/beam.hpp"
#include "ntn/modelc/emit_header.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_bytes.hpp"
#include "ntn/modelc/model_report.hpp"
#include "ntn/time_step.hpp"

namespace modelc_load_test {

using ntn::modelc::load_model;
using ntn::modelc::load_model_from_string;
using ntn::modelc::ModelDescription;

std::string config(const std::string& name) {
  return std::string(NTN_CONFIG_DIR) + "/" + name;
}

// A valid model with two nodes and one member; tests append tables or swap lines.
const std::string kHead = R"(
[model]
name = "m"

[[materials]]
id = "S"
E = 210e9
G = 81e9
rho = 7850.0

[[sections]]
id = "H"
A = 1.0e-2
Iy = 1.0e-4
Iz = 5.0e-5
J = 1.0e-6

[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [1.0, 0.0, 0.0]

[[supports]]
node = 1
fix = "all"
)";

const std::string kMember = R"(
[[members]]
id = "M1"
nodes = [1, 2]
material = "S"
section = "H"
)";

ModelDescription load_ok(const std::string& text) {
  const auto r = load_model_from_string(text, "test.toml");
  if (!r.ok()) {
    ADD_FAILURE() << ntn::modelc::format_all(r.errors);
    return {};
  }
  return *r.model;
}

// Rotation (rows local x, y, z) of element e, from the kernel's own geometry.
std::array<double, 9> rotation(const ModelDescription& d, std::size_t e) {
  const auto& el = d.elements.at(e);
  return ntn::beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                            d.nodes[static_cast<std::size_t>(el.node_j)], el)
      .rotation;
}

TEST(ModelLoad, DefaultModelsLoad) {
  const auto frame = load_model(config("frame3d.toml"));
  ASSERT_TRUE(frame.ok()) << ntn::modelc::format_all(frame.errors);
  const ModelDescription& f = *frame.model;
  // 3 levels x 6 grid points given; 26 members (12 columns, 14 beams) x 4 divisions each add
  // 3 interior nodes; the 8 beams along x are pinned at their exterior end: a node and a hinge
  // each.
  EXPECT_EQ(f.nodes.size(), 18U + 26U * 3U + 8U);
  EXPECT_EQ(f.elements.size(), 26U * 4U);
  EXPECT_EQ(f.members.size(), 26U);
  EXPECT_EQ(f.hinges.size(), 8U);
  EXPECT_EQ(f.hinge_count(ntn::modelc::HingeOrigin::kRelease), 8);
  EXPECT_TRUE(f.mechanisms.empty());  // every joint has columns: mass in all DOFs
  EXPECT_EQ(f.inputs.size(), 1U);
  EXPECT_EQ(f.outputs.size(), 9U);
  EXPECT_EQ(f.loads.size(), 0U);
  EXPECT_EQ(f.input_names.at(0), "ag_x");
  EXPECT_EQ(f.inputs[0].scale, 9.80665);  // in g
  EXPECT_TRUE(f.dt_auto);
  EXPECT_EQ(f.name, "frame3d");

  const auto cant = load_model(config("cantilever.toml"));
  ASSERT_TRUE(cant.ok()) << ntn::modelc::format_all(cant.errors);
  EXPECT_EQ(cant.model->nodes.size(), 21U);
  EXPECT_EQ(cant.model->elements.size(), 20U);
  EXPECT_EQ(cant.model->inputs.size(), 0U);
}

// Total translational mass of the default frame = point masses + sum of rho A l, computed here
// from the section areas and member lengths of the file's description (12 HEB 240 columns of
// 3.5 m, 8 IPE 330 beams of 5 m and 6 of 4 m). Tolerance 1e-12 relative: the same numbers
// summed in another order.
TEST(ModelLoad, FrameMassIsPointMassesPlusSteel) {
  const auto r = load_model(config("frame3d.toml"));
  ASSERT_TRUE(r.ok());
  const double rho = 7850.0;
  const double steel = rho * (12 * 3.5 * 106.0e-4 + (8 * 5.0 + 6 * 4.0) * 62.6e-4);
  const double points = 2 * (4 * 3750.0 + 2 * 7500.0) - 4 * 750.0 - 2 * 1500.0;  // 30 t + 24 t
  EXPECT_EQ(points, 54000.0);
  const auto m = ntn::modelc::mass_totals(*r.model);
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(m.all[static_cast<std::size_t>(d)], steel + points, 1e-12 * (steel + points));
  }
  EXPECT_NEAR(m.elements, steel, 1e-12 * steel);
  EXPECT_EQ(m.point_masses, points);
}

// A roll angle and the orientation vector it stands for give the same element frame.
// Expected vectors by hand: default reference Z for non-vertical members, X for vertical ones;
// roll turns local z towards -y: z' = cos(roll) z0 - sin(roll) y0, y0 = z0 x x.
// Tolerance 4e-16: cos and sin of the roll angle round differently from the literals.
TEST(ModelLoad, RollEqualsOrientation) {
  struct Case {
    const char* end;          // xyz of node 2
    const char* roll;         // roll in degrees
    const char* orientation;  // the same as a vector
  };
  const double s30 = 0.5, c30 = std::sqrt(3.0) / 2.0;
  char o30s[128];
  std::snprintf(o30s, sizeof o30s, "[0.0, %.17g, %.17g]", -s30, c30);
  // Inclined member along (1, 0, 1)/sqrt2: z0 = (-1, 0, 1)/sqrt2, y0 = z0 x x = (0, 1, 0);
  // roll 45: z' = cos45 z0 - sin45 (0, 1, 0) = (-0.5, -0.70710678, 0.5).
  char o45[128];
  std::snprintf(o45, sizeof o45, "[%.17g, %.17g, %.17g]", -0.5, -std::sqrt(0.5), 0.5);
  const Case cases[] = {
      {"[1.0, 0.0, 0.0]", "30.0", o30s},               // horizontal along x
      {"[0.0, 0.0, 1.0]", "90.0", "[0.0, 1.0, 0.0]"},  // vertical: z0 = X, y0 = X x Z = -Y
      {"[0.0, 0.0, 1.0]", "0.0", "[1.0, 0.0, 0.0]"},   // vertical default
      {"[0.0, 2.0, 0.0]", "0.0", "[0.0, 0.0, 1.0]"},   // horizontal default
      {"[1.0, 0.0, 1.0]", "45.0", o45},                // inclined
  };
  for (const Case& c : cases) {
    std::string base = kHead;
    base.replace(base.find("[1.0, 0.0, 0.0]"), 15, c.end);
    const auto rolled = load_ok(base + kMember + "roll = " + c.roll + "\n");
    const auto oriented = load_ok(base + kMember + "orientation = " + c.orientation + "\n");
    const auto ra = rotation(rolled, 0), rb = rotation(oriented, 0);
    for (std::size_t k = 0; k < 9; ++k) {
      EXPECT_NEAR(ra[k], rb[k], 4e-16) << "end " << c.end << " roll " << c.roll << " entry " << k;
    }
  }
  // Without roll or orientation a member takes roll = 0, bit for bit.
  const auto none = load_ok(kHead + kMember);
  const auto zero = load_ok(kHead + kMember + "roll = 0.0\n");
  EXPECT_EQ(rotation(none, 0), rotation(zero, 0));
}

// Isotropic elasticity: G = E / (2 (1 + nu)); 210 GPa, nu = 0.3 -> 80.769230769... GPa.
TEST(ModelLoad, PoissonRatioGivesShearModulus) {
  std::string text = kHead + kMember;
  text.replace(text.find("G = 81e9"), 8, "nu = 0.3");
  const auto d = load_ok(text);
  ASSERT_EQ(d.elements.size(), 1U);
  EXPECT_NEAR(d.elements[0].G, 210e9 / 2.6, 1e-15 * 210e9 / 2.6);
  EXPECT_NEAR(d.elements[0].G, 80.769230769230769e9, 1e3);
}

// divisions = N makes N elements of length L / N and N - 1 interior nodes on the member,
// chained start to end. Tolerance 4 ulp of L: node coordinates are rounded once each.
TEST(ModelLoad, DivisionsMeshEqualElements) {
  std::string base = kHead;
  base.replace(base.find("[1.0, 0.0, 0.0]"), 15, "[1.0, 2.0, 3.0]");
  const auto d = load_ok(base + kMember + "divisions = 7\n");
  ASSERT_EQ(d.nodes.size(), 2U + 6U);
  ASSERT_EQ(d.elements.size(), 7U);
  const double L = std::sqrt(14.0);
  for (std::size_t e = 0; e < 7; ++e) {
    const auto& el = d.elements[e];
    const auto g = ntn::beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                                      d.nodes[static_cast<std::size_t>(el.node_j)], el);
    EXPECT_NEAR(g.length, L / 7.0, 4 * std::numeric_limits<double>::epsilon() * L) << e;
    EXPECT_EQ(d.element_member[e], 0);
    if (e > 0) {
      EXPECT_EQ(el.node_i, d.elements[e - 1].node_j);
    }
  }
  EXPECT_EQ(d.elements.front().node_i, 0);
  EXPECT_EQ(d.elements.back().node_j, 1);
  const auto& m = d.members.at(0);
  EXPECT_EQ(m.first_element, 0);
  EXPECT_EQ(m.element_count, 7);
  EXPECT_EQ(m.first_interior_node, 2);
  EXPECT_EQ(m.interior_node_count, 6);
  EXPECT_EQ(d.node_ids[2], ntn::modelc::kGeneratedNode);
  EXPECT_EQ(d.describe_node(4), "interior node 3 of member M1 (model node 4)");
  EXPECT_EQ(d.describe_node(1), "node 2");
  EXPECT_EQ(d.describe_element(3), "member M1, element 4 of 7 (model element 3)");
}

// dt = "auto" (DESIGN §6): a whole number n of substeps per frame, dt <= 0.9 dt_stable, and the
// largest such dt (n - 1 substeps would exceed 0.9 dt_stable).
TEST(ModelLoad, AutoTimeStepFillsFrameBelowStable) {
  for (const char* file : {"frame3d.toml", "cantilever.toml"}) {
    const auto r = load_model(config(file));
    ASSERT_TRUE(r.ok());
    const auto& d = *r.model;
    // N by the kernel's frame rule; dt is derived from it, period / N, to the bit.
    const ntn::Substeps n = ntn::frame_substeps(d.settings.dt, d.settings.frame_period);
    ASSERT_TRUE(n.ok()) << file;
    EXPECT_EQ(d.settings.dt, d.settings.frame_period / static_cast<double>(n.count)) << file;
    EXPECT_LE(d.settings.dt, 0.9 * d.stable.dt_stable) << file;
    if (n.count > 1) {
      EXPECT_GT(d.settings.frame_period / static_cast<double>(n.count - 1),
                0.9 * d.stable.dt_stable)
          << file;
    }
    EXPECT_EQ(d.settings.frame_period, 1.0 / d.frame_rate);
  }
  // The same at other frame rates.
  for (const char* rate : {"200.0", "2000.0", "5000.0"}) {
    std::string text = kHead + kMember;
    text.replace(text.find("name = \"m\""), 10, std::string("name = \"m\"\nframe_rate = ") + rate);
    const auto d = load_ok(text);
    const ntn::Substeps n = ntn::frame_substeps(d.settings.dt, d.settings.frame_period);
    ASSERT_TRUE(n.ok()) << rate;
    EXPECT_EQ(d.settings.dt, d.settings.frame_period / static_cast<double>(n.count)) << rate;
    EXPECT_LE(d.settings.dt, 0.9 * d.stable.dt_stable) << rate;
  }
}

// Point masses add to the lumped mass exactly as given: per node added = sum of its point
// masses, and the totals differ by their sum. Tolerance 4 ulp of the total: the totals are
// sums in node order of element + point masses, rounded at each addition.
TEST(ModelLoad, PointMassesChangeTotalMass) {
  const auto bare = load_ok(kHead + kMember);
  const auto loaded = load_ok(kHead + kMember + R"(
[[point_masses]]
node = 2
mass = 1234.5
inertia = [10.0, 20.0, 30.0]

[[point_masses]]
node = 2
mass = 765.5

[[point_masses]]
node = 1
mass = 99.0
)");
  EXPECT_EQ(loaded.nodes[1].added[0], 2000.0);
  EXPECT_EQ(loaded.nodes[1].added[5], 30.0);
  EXPECT_EQ(loaded.nodes[0].added[2], 99.0);
  const auto a = ntn::modelc::mass_totals(bare), b = ntn::modelc::mass_totals(loaded);
  for (std::size_t d = 0; d < 3; ++d) {
    EXPECT_NEAR(b.all[d] - a.all[d], 2099.0, 4 * std::numeric_limits<double>::epsilon() * b.all[d]);
    // Node 1 is fully supported: its point mass is not on a free DOF.
    EXPECT_NEAR(b.free[d] - a.free[d], 2000.0,
                4 * std::numeric_limits<double>::epsilon() * b.all[d]);
  }
  EXPECT_NEAR(b.all[3] - a.all[3], 10.0, 1e-12);
  EXPECT_EQ(b.point_masses, 2099.0);
}

// Mass-proportional damping C = alpha M has the fraction alpha / (2 omega) in a mode at omega,
// so ratio 0.02 at 2 Hz is alpha = 2 * 0.02 * 2 pi * 2.
TEST(ModelLoad, DampingRatioAtFrequency) {
  std::string text = kHead + kMember;
  text.replace(text.find("name = \"m\""), 10,
               "name = \"m\"\n[model.damping]\nratio = 0.02\nfrequency = 2.0\n");
  const auto d = load_ok(text);
  const double omega = 2.0 * std::numbers::pi * 2.0;
  EXPECT_NEAR(d.settings.alpha / (2.0 * omega), 0.02, 1e-15);
  std::string alpha = kHead + kMember;
  alpha.replace(alpha.find("name = \"m\""), 10, "name = \"m\"\n[model.damping]\nalpha = 0.5\n");
  EXPECT_EQ(load_ok(alpha).settings.alpha, 0.5);
  EXPECT_EQ(load_ok(alpha).settings.beta, 0.0);
}

// [model.damping] with Rayleigh damping C = alpha M + beta K_el. A mode at omega has the ratio
// alpha / (2 omega) + beta omega / 2 (config/README.md):
//  - alpha and beta as given (either alone: the other 0);
//  - ratio with frequencies = [f1, f2]: that ratio at both (1e-15: the formula's rounding);
//  - ratio with modes = [i, j]: the frequencies of the model's modes i and j (the compiler's
//    modal analysis; tests/modal/modal_damping_test.cpp checks them against ntn::modal and the
//    kernel's free decay), the ratio there.
std::string with_damping(const std::string& table) {
  std::string t = kHead + kMember;
  t.replace(t.find("name = \"m\""), 10, "name = \"m\"\n[model.damping]\n" + table);
  return t;
}

TEST(ModelLoad, DampingAlphaAndBeta) {
  const auto both = load_ok(with_damping("alpha = 0.5\nbeta = 2.0e-5\n"));
  EXPECT_EQ(both.settings.alpha, 0.5);
  EXPECT_EQ(both.settings.beta, 2.0e-5);
  const auto beta = load_ok(with_damping("beta = 2.0e-5\n"));
  EXPECT_EQ(beta.settings.alpha, 0.0);
  EXPECT_EQ(beta.settings.beta, 2.0e-5);
  // beta lowers the stable step: the kernel's bound with alpha + beta omega_max^2.
  const auto none = load_ok(kHead + kMember);
  EXPECT_LT(beta.stable.dt_stable, none.stable.dt_stable);
  EXPECT_EQ(beta.stable.dt_stable, ntn::damped_stable_step(none.stable.omega_max, 0.0, 2.0e-5));
}

TEST(ModelLoad, DampingRatioAtTwoFrequencies) {
  const auto d = load_ok(with_damping("ratio = 0.03\nfrequencies = [2.0, 15.0]\n"));
  const auto ratio = [&d](double hz) {
    const double w = 2.0 * std::numbers::pi * hz;
    return d.settings.alpha / (2.0 * w) + d.settings.beta * w / 2.0;
  };
  EXPECT_NEAR(ratio(2.0), 0.03, 1e-15);
  EXPECT_NEAR(ratio(15.0), 0.03, 1e-15);
  EXPECT_LT(ratio(6.0), 0.03);   // below between them
  EXPECT_GT(ratio(40.0), 0.03);  // above outside
  EXPECT_EQ(d.damping_frequencies[0], 2.0);
  EXPECT_EQ(d.damping_frequencies[1], 15.0);
  EXPECT_EQ(d.damping_ratio, 0.03);
}

TEST(ModelLoad, DampingRatioAtTwoModes) {
  const auto d = load_ok(with_damping("ratio = 0.05\nmodes = [1, 3]\n"));
  EXPECT_EQ(d.damping_modes[0], 1);
  EXPECT_EQ(d.damping_modes[1], 3);
  ASSERT_GT(d.damping_frequencies[0], 0.0);
  EXPECT_LT(d.damping_frequencies[0], d.damping_frequencies[1]);
  for (const double hz : d.damping_frequencies) {
    const double w = 2.0 * std::numbers::pi * hz;
    EXPECT_NEAR(d.settings.alpha / (2.0 * w) + d.settings.beta * w / 2.0, 0.05, 1e-15);
  }
}

// Timoshenko: shear areas kappa A, default kappa 5/6; Euler-Bernoulli leaves them 0.
TEST(ModelLoad, ShearAreas) {
  EXPECT_EQ(load_ok(kHead + kMember).elements[0].shear_area_y, 0.0);
  std::string t = kHead + kMember;
  t.replace(t.find("J = 1.0e-6"), 10, "J = 1.0e-6\nshear = \"timoshenko\"\nkappa_z = 0.5");
  const auto d = load_ok(t);
  EXPECT_EQ(d.elements[0].shear_area_y, 5.0 / 6.0 * 1.0e-2);
  EXPECT_EQ(d.elements[0].shear_area_z, 0.5 * 1.0e-2);
}

TEST(ModelLoad, ChannelsLoadsAndSupports) {
  const auto d = load_ok(kHead + R"(
[[nodes]]
id = 3
xyz = [1.0, 0.0, 3.0]

[[members]]
id = "B"
nodes = [1, 2]
material = "S"
section = "H"
divisions = 3

[[members]]
id = "C"
nodes = [2, 3]
material = "S"
section = "H"
divisions = 2

[[supports]]
node = 3
fix = ["ux", "rz"]

[[time_functions]]
id = "ramp"
points = [[0.0, 0.0], [1.0, 1.0]]

[[loads]]
node = 2
force = [0.0, 5.0, 0.0, 0.0, 0.0, -7.0]
function = "ramp"

[[inputs]]
name = "ag"
kind = "ground_acceleration"
direction = "y"

[[inputs]]
name = "push"
kind = "nodal_force"
node = 3
dof = "uy"
scale = 1000.0

[[outputs]]
name = "end_T"
kind = "element_force"
member = "B"
end = "end"
component = "T"

[[outputs]]
name = "drift"
kind = "drift"
nodes = [2, 3]
direction = "y"

[[outputs]]
name = "rz"
kind = "reaction"
direction = "rz"

[[outputs]]
name = "v"
kind = "velocity"
node = 3
dof = "rx"
)");
  ASSERT_EQ(d.loads.size(), 2U);  // nonzero components only
  EXPECT_EQ(d.loads[0].dof, 1);
  EXPECT_EQ(d.loads[0].value, 5.0);
  EXPECT_EQ(d.loads[1].dof, 5);
  EXPECT_EQ(d.loads[1].time_function, 0);
  EXPECT_EQ(d.nodes[2].fixed, (1U << 0) | (1U << 5));
  EXPECT_EQ(d.nodes[0].fixed, 0x3F);
  EXPECT_EQ(d.inputs[0].scale, 1.0);  // m/s2 by default
  EXPECT_EQ(d.inputs[0].dof, 1);
  EXPECT_EQ(d.inputs[1].node, 2);
  EXPECT_EQ(d.inputs[1].scale, 1000.0);
  // element_force at "end" of B: B's last element (index 2), its end j.
  EXPECT_EQ(d.outputs[0].element, 2);
  EXPECT_EQ(d.outputs[0].end, 1);
  EXPECT_EQ(d.outputs[0].dof, 3);
  EXPECT_EQ(d.output_units[0], "N m");
  EXPECT_EQ(d.outputs[1].scale, 1.0 / 3.0);  // storey height 3 m
  EXPECT_EQ(d.output_units[1], "-");
  EXPECT_EQ(d.outputs[2].kind, ntn::OutputKind::kReaction);
  EXPECT_EQ(d.output_units[2], "N m");
  EXPECT_EQ(d.output_units[3], "rad/s");
}

// Output alarms: per output, in file order; the hysteresis defaults to 0; no alarm is limit 0;
// the header carries them as kAlarmLimits / kAlarmHysteresis with the values' own literals.
TEST(ModelLoad, OutputAlarms) {
  const auto d = load_ok(kHead + kMember + R"(
[[outputs]]
name = "tip"
kind = "displacement"
node = 2
dof = "uz"
alarm = 0.02
alarm_hysteresis = 0.005

[[outputs]]
name = "plain"
kind = "velocity"
node = 2
dof = "uz"

[[outputs]]
name = "moment"
kind = "element_force"
member = "M1"
end = "start"
component = "My"
alarm = 1.5e4
)");
  ASSERT_EQ(d.output_alarms.size(), 3U);
  EXPECT_EQ(d.output_alarms[0].limit, 0.02);
  EXPECT_EQ(d.output_alarms[0].hysteresis, 0.005);
  EXPECT_EQ(d.output_alarms[1].limit, 0.0);
  EXPECT_EQ(d.output_alarms[1].hysteresis, 0.0);
  EXPECT_EQ(d.output_alarms[2].limit, 1.5e4);
  EXPECT_EQ(d.output_alarms[2].hysteresis, 0.0);
  const std::string h = ntn::modelc::emit_header(d);
  EXPECT_NE(h.find("kAlarmLimits{{0.02, 0.0, 15000.0}}"), std::string::npos) << h;
  EXPECT_NE(h.find("kAlarmHysteresis{{0.0050000000000000001, 0.0, 0.0}}"), std::string::npos) << h;
}

// (A dt longer than the frame is refused whatever allow_unstable says: frame_rate 50 Hz here.)
TEST(ModelLoad, AllowUnstableAcceptsLargeDt) {
  std::string text = kHead + kMember;
  text.replace(text.find("name = \"m\""), 10,
               "name = \"m\"\ndt = 1.0e-2\nframe_rate = 50.0\nallow_unstable = true");
  const auto d = load_ok(text);
  EXPECT_EQ(d.settings.dt, 1.0e-2);
  EXPECT_GT(d.settings.dt, d.stable.dt_stable);
  EXPECT_TRUE(d.settings.allow_unstable);
}

// A ground acceleration's `scale` multiplies the motion: it is InputSpec::factor, while the
// input's unit (scale), range and kind stay the channel's; a negative factor is allowed (the
// motion reversed). The header carries it.
TEST(ModelLoad, GroundAccelerationScaleIsAFactorOnTheMotion) {
  const auto d = load_ok(kHead + kMember + R"(
[[inputs]]
name = "ag"
kind = "ground_acceleration"
direction = "y"
units = "g"
scale = -1.5
min = -2.0
max = 2.0

[[inputs]]
name = "ag_z"
kind = "ground_acceleration"
direction = "z"
)");
  ASSERT_EQ(d.inputs.size(), 2U);
  EXPECT_EQ(d.inputs[0].scale, 9.80665);  // the unit: g
  EXPECT_EQ(d.inputs[0].factor, -1.5);
  EXPECT_EQ(d.inputs[0].min, -2.0);  // of the raw value, as it arrives
  EXPECT_EQ(d.inputs[0].max, 2.0);
  EXPECT_EQ(d.inputs[1].scale, 1.0);
  EXPECT_EQ(d.inputs[1].factor, 1.0);  // by default
  const std::string h = ntn::modelc::emit_header(d);
  EXPECT_NE(h.find(".scale = 9.8066499999999994, .min = -2.0, .max = 2.0, .factor = -1.5}"),
            std::string::npos)
      << h;
}

// Every double in the header reads back to the same bits: parse the literals of the element
// lines with strtod and compare with the description.
TEST(EmitHeader, DoublesRoundTripAndZeroSizeArrays) {
  const auto r = load_model(config("cantilever.toml"));
  ASSERT_TRUE(r.ok());
  const std::string h = ntn::modelc::emit_header(*r.model);
  EXPECT_NE(h.find("#pragma once"), std::string::npos);
  EXPECT_NE(h.find("namespace ntn::models::cantilever {"), std::string::npos);
  EXPECT_NE(h.find("inline constexpr ntn::ModelSpec<kSizes> kSpec{"), std::string::npos);
  EXPECT_NE(h.find("    .inputs = {},\n"), std::string::npos);  // no inputs
  EXPECT_EQ(h.find("inf"), std::string::npos);
  EXPECT_EQ(h.find("nan"), std::string::npos);
  std::size_t pos = 0;
  int checked = 0;
  for (const auto& e : r.model->elements) {
    pos = h.find(".E = ", pos);
    ASSERT_NE(pos, std::string::npos);
    const double E = std::strtod(h.c_str() + pos + 5, nullptr);
    const std::size_t iz = h.find(".Iz = ", pos);
    const double Iz = std::strtod(h.c_str() + iz + 6, nullptr);
    const std::size_t rz = h.find(".ref_z = ", pos);
    const double ref_z = std::strtod(h.c_str() + rz + 9, nullptr);
    EXPECT_EQ(std::memcmp(&E, &e.E, sizeof E), 0);
    EXPECT_EQ(std::memcmp(&Iz, &e.Iz, sizeof Iz), 0);
    EXPECT_EQ(std::memcmp(&ref_z, &e.ref_z, sizeof ref_z), 0);
    ++pos;
    ++checked;
  }
  EXPECT_EQ(checked, 20);
  const std::size_t g = h.find(".G = ");
  EXPECT_EQ(std::strtod(h.c_str() + g + 5, nullptr), 210e9 / 2.6);
}

TEST(EmitHeader, RefusesNonFiniteAndBadNames) {
  auto d = load_ok(kHead + kMember);
  EXPECT_THROW((void)ntn::modelc::emit_header(d, "3d"), std::invalid_argument);
  d.elements[0].E = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)ntn::modelc::emit_header(d), std::invalid_argument);
  EXPECT_TRUE(ntn::modelc::is_cpp_identifier("frame3d"));
  EXPECT_TRUE(ntn::modelc::is_cpp_identifier("_x1"));
  EXPECT_FALSE(ntn::modelc::is_cpp_identifier("int"));
  EXPECT_FALSE(ntn::modelc::is_cpp_identifier("a-b"));
  EXPECT_FALSE(ntn::modelc::is_cpp_identifier("_Big"));
  EXPECT_FALSE(ntn::modelc::is_cpp_identifier("a__b"));
  EXPECT_FALSE(ntn::modelc::is_cpp_identifier(""));
}

// The damping line: alpha and beta, and the ratio at the two frequencies Rayleigh damping was
// set at (to the printed three digits: 3 %).
TEST(ModelInfo, ReportsRayleighDamping) {
  const std::string t =
      ntn::modelc::info_text(load_ok(with_damping("ratio = 0.03\nfrequencies = [2.0, 15.0]\n")));
  for (const std::string& s : {std::string("C = alpha M + beta K_el, alpha = "),
                               std::string(" s: 3 % at 2 Hz, 3 % at 15 Hz")}) {
    EXPECT_NE(t.find(s), std::string::npos) << s << "\n" << t;
  }
}

TEST(ModelInfo, ReportsFigures) {
  const auto r = load_model(config("frame3d.toml"));
  ASSERT_TRUE(r.ok());
  const std::string t = ntn::modelc::info_text(*r.model);
  // Per node: 6 DOFs x 9 double arrays (mass, inv_mass, damping, u0, v0, u, v, f, a) + 1 + 4.
  // Plus a quarter of a mass-table entry (384 bytes) and of its index (4 bytes), and a
  // sixteenth of a book group's sums (32 bytes).
  const std::string per_node = "per node " + std::to_string(6 * 9 * 8 + 1 + 4 + 97 + 2) + " B";
  const std::string per_element =
      "per element " + std::to_string(ntn::modelc::memory_footprint(r.model->sizes()).per_element) +
      " B";
  for (const std::string& s :
       {std::string("nodes        104"), std::string("elements     104 in 26 members"),
        std::string("order        26 blocks of 4, "),
        std::string("hinges       8: 0 explicit, 8 member-end releases, 0 supports with axes"),
        std::string("ntn_exact / penalty = "), std::string("stable dt"),
        std::string("set by member"), std::string("CFL (seed)"), std::string("substeps"),
        per_element, per_node}) {
    EXPECT_NE(t.find(s), std::string::npos) << s << "\n" << t;
  }
}

}  // namespace modelc_load_test
