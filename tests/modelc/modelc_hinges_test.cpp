// The model compiler on models with hinges (DESIGN §7): every behaviour form, member-end releases
// (new node, hinge in the member's axes), frames, eccentricity, supports with axes, hinge
// outputs, curves, the penalty and limit stiffness defaults, mechanisms as notes, and the
// info report's ntn_exact / penalty ratio. Truth: the file's own numbers, the kernel's element
// rotation (bit for bit), closed forms (EA/l, 4EI/l), and the kernel's stable step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ntn/beam.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"

namespace modelc_hinges_test {

using ntn::HingeBehaviour;
using ntn::modelc::HingeOrigin;
using ntn::modelc::load_model_from_string;
using ntn::modelc::ModelDescription;

std::string config(const std::string& name) {
  return std::string(NTN_CONFIG_DIR) + "/" + name;
}

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
)";

std::string node(int id, const char* xyz) {
  return "\n[[nodes]]\nid = " + std::to_string(id) + "\nxyz = " + xyz + "\n";
}

std::string member(const char* id, int a, int b, const std::string& extra = "") {
  return std::string("\n[[members]]\nid = \"") + id + "\"\nnodes = [" + std::to_string(a) + ", " +
         std::to_string(b) + "]\nmaterial = \"S\"\nsection = \"H\"\n" + extra;
}

ModelDescription load_ok(const std::string& text) {
  const auto r = load_model_from_string(text, "test.toml");
  if (!r.ok()) {
    ADD_FAILURE() << ntn::modelc::format_all(r.errors);
    return {};
  }
  return *r.model;
}

std::array<double, 9> rotation(const ModelDescription& d, int e) {
  const auto& el = d.elements.at(static_cast<std::size_t>(e));
  return ntn::beam_geometry(d.nodes[static_cast<std::size_t>(el.node_i)],
                            d.nodes[static_cast<std::size_t>(el.node_j)], el)
      .rotation;
}

// A released end gets its own node (coincident with the joint, bit for bit) that takes the end
// element; the hinge joins it (node 1) to the joint (node 2) in the member's local axes: exactly
// the end element's rotation. Unnamed directions are rigid. An inclined member with a roll
// makes the frame a full rotation.
TEST(Hinges, ReleaseMakesNodeAndHingeInMemberAxes) {
  const auto d =
      load_ok(kHead + node(1, "[0.0, 0.0, 0.0]") + node(2, "[1.0, 2.0, 3.0]") +
              member("M1", 1, 2,
                     "divisions = 3\nroll = 30.0\nrelease_start = [\"ry\", \"rz\"]\n"
                     "release_end = { rx = \"free\", rz = { linear = 5.0e6, dashpot = 10.0 }, "
                     "uy = \"rigid\" }\n") +
              "\n[[supports]]\nnode = 1\nfix = \"all\"\n" +
              // Node 2 keeps no element: without its own mass a spring on it would be an error.
              "\n[[point_masses]]\nnode = 2\nmass = 10.0\ninertia = [1.0, 1.0, 1.0]\n");
  // 2 given + 2 interior + 2 released ends; the released nodes follow the interior ones.
  ASSERT_EQ(d.nodes.size(), 6U);
  ASSERT_EQ(d.elements.size(), 3U);
  ASSERT_EQ(d.hinges.size(), 2U);
  const auto& mi = d.members.at(0);
  EXPECT_EQ(mi.first_interior_node, 2);
  EXPECT_EQ(mi.start_release_node, 4);
  EXPECT_EQ(mi.end_release_node, 5);
  EXPECT_EQ(mi.start_hinge, 0);
  EXPECT_EQ(mi.end_hinge, 1);
  EXPECT_EQ(mi.start_node, 0);  // the joints stay the member's ends
  EXPECT_EQ(mi.end_node, 1);
  EXPECT_EQ(d.elements[0].node_i, 4);
  EXPECT_EQ(d.elements[2].node_j, 5);
  EXPECT_EQ(d.elements[1].node_i, 2);  // interior elements untouched
  for (int k : {4, 5}) {
    const auto& joint = d.nodes[static_cast<std::size_t>(k == 4 ? 0 : 1)];
    const auto& rn = d.nodes[static_cast<std::size_t>(k)];
    EXPECT_EQ(rn.x, joint.x);
    EXPECT_EQ(rn.y, joint.y);
    EXPECT_EQ(rn.z, joint.z);
    EXPECT_EQ(rn.fixed, 0);
    EXPECT_EQ(d.node_ids[static_cast<std::size_t>(k)], ntn::modelc::kGeneratedNode);
  }
  EXPECT_EQ(d.describe_node(4), "start of member M1 (released, model node 4)");
  EXPECT_EQ(d.describe_node(5), "end of member M1 (released, model node 5)");

  const ntn::HingeSpec& s = d.hinges[0];
  const ntn::HingeSpec& e = d.hinges[1];
  EXPECT_EQ(s.node1, 4);
  EXPECT_EQ(s.node2, 0);
  EXPECT_EQ(e.node1, 5);
  EXPECT_EQ(e.node2, 1);
  EXPECT_EQ(s.frame, rotation(d, 0));  // bit for bit
  EXPECT_EQ(e.frame, rotation(d, 2));
  // Local x along the member, (1, 2, 3) / sqrt(14); tolerance 2 ulp of 1.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(s.frame[static_cast<std::size_t>(c)], (c + 1.0) / std::sqrt(14.0), 4.5e-16);
  EXPECT_EQ(s.eccentricity, (std::array<double, 3>{0, 0, 0}));
  const HingeBehaviour R = HingeBehaviour::kRigid, F = HingeBehaviour::kFree;
  EXPECT_EQ(s.behaviour, (std::array<HingeBehaviour, 6>{R, R, R, R, F, F}));
  EXPECT_EQ(e.behaviour, (std::array<HingeBehaviour, 6>{R, R, R, F, R, HingeBehaviour::kLinear}));
  EXPECT_EQ(e.stiffness[5], 5.0e6);
  EXPECT_EQ(e.dashpot[5], 10.0);
  EXPECT_EQ(d.hinge_info[0].name, "M1.start");
  EXPECT_EQ(d.hinge_info[1].name, "M1.end");
  EXPECT_EQ(d.hinge_info[1].origin, HingeOrigin::kRelease);
  EXPECT_EQ(d.hinge_info[1].member, 0);
  EXPECT_EQ(d.hinge_info[1].end, 1);
  EXPECT_EQ(d.describe_hinge(0), "member-end release M1.start");
}

// One element, both ends released: the element runs between the two new nodes, and its geometry
// (so its stiffness and mass) is that of the unreleased member, bit for bit.
TEST(Hinges, BothEndsOfOneElement) {
  const std::string nodes = node(1, "[0.0, 0.0, 0.0]") + node(2, "[0.0, 3.0, 0.0]") +
                            node(3, "[0.0, 0.0, 3.0]") + member("C1", 1, 3) + member("C2", 2, 3) +
                            "\n[[supports]]\nnode = 1\nfix = \"all\"\n" +
                            "\n[[supports]]\nnode = 2\nfix = \"all\"\n";
  const auto plain = load_ok(kHead + nodes + member("B", 1, 2));
  const auto pinned = load_ok(
      kHead + nodes + member("B", 1, 2, "release_start = [\"rz\"]\nrelease_end = [\"rz\"]\n"));
  ASSERT_EQ(pinned.nodes.size(), plain.nodes.size() + 2);
  const auto& el = pinned.elements[2];
  EXPECT_EQ(el.node_i, 3);
  EXPECT_EQ(el.node_j, 4);
  EXPECT_EQ(rotation(pinned, 2), rotation(plain, 2));
  const auto g = ntn::beam_geometry(pinned.nodes[3], pinned.nodes[4], el);
  const auto h = ntn::beam_geometry(plain.nodes[0], plain.nodes[1], plain.elements[2]);
  EXPECT_EQ(g.length, h.length);
}

// Every behaviour form of an explicit hinge, the three frame forms, and eccentricity e = x2 - x1.
// Each hinge joins its own pair of nodes: two hinges with rigid directions between the same
// nodes would close a cycle.
TEST(Hinges, BehaviourAndFrameForms) {
  const std::string text =
      kHead + node(1, "[0.0, 0.0, 0.0]") + node(2, "[2.0, 0.0, 0.0]") + node(3, "[2.0, 0.0, 0.0]") +
      node(4, "[4.0, 1.0, 0.0]") + node(5, "[2.0, 0.5, -0.25]") + node(6, "[4.0, 1.0, 0.0]") +
      node(7, "[6.0, 1.0, 0.0]") + node(8, "[6.0, 1.0, 0.0]") + node(9, "[8.0, 1.0, 0.0]") +
      member("B1", 1, 2) + member("B2", 3, 4, "roll = 15.0\n") + member("B3", 5, 4) +
      member("B4", 6, 7) + member("B5", 8, 9) + "\n[[supports]]\nnode = 1\nfix = \"all\"\n" + R"(
[[curves]]
id = "unused"
points = [[0.0, 0.0], [1.0, 1.0], [2.0, 3.0]]

[[curves]]
id = "soft"
points = [[-0.01, -100.0], [0.01, 100.0]]

[[hinges]]
id = "H1"
nodes = [2, 3]
ux = "rigid"
uy = "free"
uz = { linear = 1.0e6 }
rx = { linear = 0.0, dashpot = 3.0 }
ry = { curve = "soft" }

[[hinges]]
id = "H2"
nodes = [6, 4]
frame = { member = "B2" }
rz = "free"

[[hinges]]
id = "H3"
nodes = [8, 7]
frame = "global"
axes = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
)";
  // frame and axes exclude each other: H3 is an error; without `frame` it loads.
  ASSERT_FALSE(load_model_from_string(text, "t.toml").ok());
  std::string fixed = text;
  fixed.erase(fixed.rfind("frame = \"global\"\n"), 17);
  const auto d = load_ok(fixed + R"(
[[hinges]]
id = "H4"
nodes = [5, 2]
eccentric = true
rz = "free"
)");
  ASSERT_EQ(d.hinges.size(), 4U);
  const auto& h1 = d.hinges[0];
  using B = HingeBehaviour;
  EXPECT_EQ(h1.behaviour,
            (std::array<B, 6>{B::kRigid, B::kFree, B::kLinear, B::kLinear, B::kCurve, B::kRigid}));
  EXPECT_EQ(h1.stiffness[2], 1.0e6);
  EXPECT_EQ(h1.dashpot[2], 0.0);  // no dashpot given
  EXPECT_EQ(h1.stiffness[3], 0.0);
  EXPECT_EQ(h1.dashpot[3], 3.0);
  EXPECT_EQ(h1.curve[4], 1);  // "soft" is the second curve
  EXPECT_EQ(h1.frame, (std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));  // default: global
  EXPECT_EQ(h1.node1, 1);
  EXPECT_EQ(h1.node2, 2);
  // Curves concatenated in file order, used or not.
  ASSERT_EQ(d.curves.size(), 2U);
  EXPECT_EQ(d.curves[1].first, 3);
  EXPECT_EQ(d.curves[1].count, 2);
  EXPECT_EQ(d.curve_points[3].d, -0.01);
  EXPECT_EQ(d.curve_points[4].force, 100.0);
  EXPECT_EQ(d.curve_ids[1], "soft");
  EXPECT_EQ(d.hinges[1].frame, rotation(d, 1));  // B2's (first) element
  EXPECT_EQ(d.hinges[2].frame, (std::array<double, 9>{0, 1, 0, -1, 0, 0, 0, 0, 1}));
  // H4: node 5 at (2, 0.5, -0.25), node 2 at (2, 0, 0): e = x2 - x1 = (0, -0.5, 0.25).
  EXPECT_EQ(d.hinges[3].eccentricity, (std::array<double, 3>{0.0, -0.5, 0.25}));
  EXPECT_EQ(d.hinges[0].eccentricity, (std::array<double, 3>{0, 0, 0}));
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_EQ(d.hinge_info[i].origin, HingeOrigin::kExplicit);
}

// A support with axes is a hinge to the ground in those axes: rigid in the fixed local
// directions, free in the others; the node's own support bits stay 0. A support without axes
// is unchanged. Its hinge is named support.<node id>.
TEST(Hinges, SupportWithAxesIsAGroundHinge) {
  const auto d = load_ok(kHead + node(1, "[0.0, 0.0, 0.0]") + node(7, "[3.0, 0.0, 0.0]") +
                         member("B", 1, 7) + R"(
[[supports]]
node = 1
fix = "pinned"

[[supports]]
node = 7
axes = [[0.8660254037844386, 0.0, -0.5], [0.0, 1.0, 0.0], [0.5, 0.0, 0.8660254037844386]]
fix = ["uz", "rx"]

[[outputs]]
name = "R"
kind = "hinge_force"
hinge = "support.7"
direction = "uz"

[[outputs]]
name = "slide"
kind = "hinge_displacement"
hinge = "support.7"
direction = "ux"

[[outputs]]
name = "tilt"
kind = "hinge_displacement"
hinge = "support.7"
direction = "ry"

[[outputs]]
name = "M"
kind = "hinge_force"
hinge = "support.7"
direction = "rx"
)");
  EXPECT_EQ(d.nodes[0].fixed, 0x07);
  EXPECT_EQ(d.nodes[1].fixed, 0);
  ASSERT_EQ(d.hinges.size(), 1U);
  const auto& h = d.hinges[0];
  EXPECT_EQ(h.node1, 1);
  EXPECT_EQ(h.node2, ntn::kGround);
  EXPECT_EQ(h.frame, (std::array<double, 9>{0.8660254037844386, 0.0, -0.5, 0.0, 1.0, 0.0, 0.5, 0.0,
                                            0.8660254037844386}));
  using B = HingeBehaviour;
  EXPECT_EQ(h.behaviour,
            (std::array<B, 6>{B::kFree, B::kFree, B::kRigid, B::kRigid, B::kFree, B::kFree}));
  EXPECT_EQ(d.hinge_info[0].name, "support.7");
  EXPECT_EQ(d.hinge_info[0].origin, HingeOrigin::kSupport);
  ASSERT_EQ(d.outputs.size(), 4U);
  EXPECT_EQ(d.outputs[0].kind, ntn::OutputKind::kHingeForce);
  EXPECT_EQ(d.outputs[0].hinge, 0);
  EXPECT_EQ(d.outputs[0].dof, 2);
  EXPECT_EQ(d.outputs[1].kind, ntn::OutputKind::kHingeDisplacement);
  EXPECT_EQ(d.output_units, (std::vector<std::string>{"N", "m", "rad", "N m"}));
}

// Defaults (config/README.md): penalty and limit stiffness 1e4 x the largest element EA/l
// (translations) and 4EI/l with the larger I (rotations); a given penalty stiffness does not move
// the limit. Here E = 210 GPa, A = 1e-2 m^2, Iy = 1e-4 m^4 > Iz, and the shortest element is
// 0.5 m (2 divisions of 1 m): EA/l = 4.2e9 N/m, 4EI/l = 1.68e8 N m/rad.
TEST(Hinges, PenaltyAndLimitDefaults) {
  const std::string base = kHead + node(1, "[0.0, 0.0, 0.0]") + node(2, "[1.0, 0.0, 0.0]") +
                           node(3, "[3.0, 0.0, 0.0]") + member("M1", 1, 2, "divisions = 2\n") +
                           member("M2", 2, 3) + "\n[[supports]]\nnode = 1\nfix = \"all\"\n";
  const auto d = load_ok(base);
  const double EA_l = 210e9 * 1.0e-2 / 0.5, EI4_l = 4.0 * 210e9 * 1.0e-4 / 0.5;
  // Tolerance 1 ulp: the compiler multiplies in another order.
  EXPECT_NEAR(d.settings.penalty_stiffness, 1e4 * EA_l, 1e-16 * 1e4 * EA_l);
  EXPECT_NEAR(d.settings.penalty_rotational_stiffness, 1e4 * EI4_l, 1e-16 * 1e4 * EI4_l);
  EXPECT_EQ(d.settings.limit_stiffness, d.settings.penalty_stiffness);
  EXPECT_EQ(d.settings.limit_rotational_stiffness, d.settings.penalty_rotational_stiffness);
  EXPECT_FALSE(d.penalty_stiffness_given);
  std::string given = base;
  given.replace(given.find("name = \"m\""), 10,
                "name = \"m\"\npenalty_stiffness = 5.0e12\nlimit_rotational_stiffness = 7.0e9\n"
                "hinge_method = \"penalty\"\nclamp = \"paper\"");
  const auto g = load_ok(given);
  EXPECT_EQ(g.settings.penalty_stiffness, 5.0e12);
  EXPECT_EQ(g.settings.limit_stiffness, d.settings.limit_stiffness);
  EXPECT_EQ(g.settings.limit_rotational_stiffness, 7.0e9);
  EXPECT_EQ(g.settings.penalty_rotational_stiffness, d.settings.penalty_rotational_stiffness);
  EXPECT_EQ(g.settings.hinge_method, ntn::HingeMethod::kPenalty);
  EXPECT_EQ(g.settings.clamp, ntn::ClampRule::kPaper);
  EXPECT_TRUE(g.penalty_stiffness_given);
  EXPECT_TRUE(g.limit_rotational_stiffness_given);
  EXPECT_EQ(d.settings.hinge_method, ntn::HingeMethod::kNtnExact);  // the defaults
  EXPECT_EQ(d.settings.clamp, ntn::ClampRule::kMomentum);
}

// tests/modelc/good/pinned_joint.toml: a joint whose member ends are all pinned has its
// translations (and the rotations the beams' torsion ties) through the rigid directions, but
// not its rotation about z: a mechanism, reported as a note at the node's id, not an error.
TEST(Hinges, PinnedJointRotationIsAMechanismNote) {
  const std::string file = std::string(NTN_MODELC_GOOD_DIR) + "/pinned_joint.toml";
  const auto r = ntn::modelc::load_model(file);
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  ASSERT_EQ(r.model->mechanisms.size(), 1U);
  EXPECT_EQ(r.model->mechanisms[0].node, 0);
  EXPECT_EQ(r.model->mechanisms[0].dofs, 1U << ntn::kRz);
  ASSERT_EQ(r.notes.size(), 1U);
  const auto& n = r.notes[0];
  EXPECT_EQ(n.severity, ntn::modelc::Severity::kNote);
  EXPECT_EQ(n.line, 23);
  EXPECT_EQ(n.column, 6);
  EXPECT_EQ(n.key, "nodes[0].id");
  EXPECT_NE(n.message.find("node 1 has no effective mass and no stiffness in rz"),
            std::string::npos)
      << n.message;
  EXPECT_NE(n.format().find("pinned_joint.toml:23:6: note: key 'nodes[0].id': node 1"),
            std::string::npos);
  EXPECT_NE(ntn::modelc::info_text(*r.model).find("mechanisms   node 1: rz"), std::string::npos);

  // Releasing the torsion of both beams too leaves all three rotations of the joint free; the
  // translations still move with the beams. A spring on the rotation about z instead makes it
  // an error (a spring on a DOF without mass).
  std::string text;
  {
    std::FILE* f = std::fopen(file.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t k;
    while ((k = std::fread(buf, 1, sizeof buf, f)) > 0)
      text.append(buf, k);
    std::fclose(f);
  }
  std::string all = text;
  for (std::size_t p = all.find("[\"ry\", \"rz\"]"); p != std::string::npos;
       p = all.find("[\"ry\", \"rz\"]", p + 1))
    all.replace(p, 12, "[\"rx\", \"ry\", \"rz\"]");
  const auto a = load_ok(all);
  ASSERT_EQ(a.mechanisms.size(), 1U);
  EXPECT_EQ(a.mechanisms[0].dofs, (1U << ntn::kRx) | (1U << ntn::kRy) | (1U << ntn::kRz));
  std::string spring = text;
  const std::size_t p = spring.find("release_start = [\"ry\", \"rz\"]");
  spring.replace(p, 28, "release_start = { ry = \"free\", rz = { linear = 1.0e3 } }");
  const auto s = load_model_from_string(spring, "spring.toml");
  ASSERT_FALSE(s.ok());
  ASSERT_EQ(s.errors.size(), 1U);
  EXPECT_NE(s.errors[0].message.find("node 1 has no effective mass in rz (global axes), but a "
                                     "hinge spring"),
            std::string::npos)
      << s.errors[0].message;
}

// A model whose nodes all have mass has no notes; frame3d's joints all have columns.
TEST(Hinges, NoNotesWithoutMechanisms) {
  const auto r = ntn::modelc::load_model(config("frame3d.toml"));
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r.notes.empty());
  const auto h = ntn::modelc::load_model(config("hinged_beam.toml"));
  ASSERT_TRUE(h.ok()) << ntn::modelc::format_all(h.errors);
  EXPECT_TRUE(h.notes.empty());
}

// hinged_beam.toml's comment: its bearing plate (node 7, no member) needs its point mass only for
// penalty. Without it, ntn_exact moves node 7 with node 6 through H_ecc's six rigid directions
// (no mechanism, no note), while penalty puts stiff springs on a node without mass: an error.
TEST(Hinges, BearingMassOnlyPenaltyNeedsIt) {
  std::FILE* f = std::fopen(config("hinged_beam.toml").c_str(), "rb");
  ASSERT_NE(f, nullptr);
  std::string text;
  char buf[4096];
  std::size_t k;
  while ((k = std::fread(buf, 1, sizeof buf, f)) > 0)
    text.append(buf, k);
  std::fclose(f);
  const std::size_t at = text.find("[[point_masses]]\nnode = 7");
  ASSERT_NE(at, std::string::npos);
  text.erase(at, text.find("[[time_functions]]") - at);
  const auto exact = load_model_from_string(text, "hb.toml");
  ASSERT_TRUE(exact.ok()) << ntn::modelc::format_all(exact.errors);
  EXPECT_TRUE(exact.notes.empty());
  text.replace(text.find("hinge_method = \"ntn_exact\""), 26, "hinge_method = \"penalty\"");
  const auto pen = load_model_from_string(text, "hb.toml");
  ASSERT_EQ(pen.errors.size(), 1U) << ntn::modelc::format_all(pen.errors);
  EXPECT_EQ(pen.errors[0].key, "nodes[6].id");
  EXPECT_NE(pen.errors[0].message.find("penalty needs mass on both nodes"), std::string::npos);
}

// ntn-model info prints the stable step with the model's method and with penalty, and their
// ratio: the same numbers as the kernel's stable_time_step on the same model with
// hinge_method switched.
TEST(Hinges, InfoPrintsPenaltyRatio) {
  const auto r = ntn::modelc::load_model(config("hinged_beam.toml"));
  ASSERT_TRUE(r.ok());
  const auto& d = *r.model;
  const auto exact = ntn::modelc::stable_step_with(d, ntn::HingeMethod::kNtnExact);
  const auto pen = ntn::modelc::stable_step_with(d, ntn::HingeMethod::kPenalty);
  EXPECT_EQ(exact.dt_stable, d.stable.dt_stable);  // the model's own method is ntn_exact
  ASSERT_GT(pen.dt_stable, 0.0);
  EXPECT_LT(pen.dt_stable, exact.dt_stable);  // penalty springs are stiffer than any element
  EXPECT_GE(pen.governing_hinge, 0);
  char ratio[64];
  std::snprintf(ratio, sizeof ratio, "ntn_exact / penalty = %.4g", exact.dt_stable / pen.dt_stable);
  const std::string t = ntn::modelc::info_text(d);
  for (const std::string& s :
       {std::string(ratio),
        std::string("hinges       5: 3 explicit, 1 member-end releases, 1 supports with axes; 1 "
                    "curves (4 points)"),
        std::string("method       ntn_exact"), std::string("penalty dt"),
        std::string("per hinge ")}) {
    EXPECT_NE(t.find(s), std::string::npos) << s << "\n" << t;
  }
}

}  // namespace modelc_hinges_test
