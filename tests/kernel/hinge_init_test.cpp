// Init errors with hinges (model checks): a cycle of rigid
// connections (two hinges between the same pair, a triangle, a tree reaching the ground twice)
// is refused as kRigidCycle, and a hinge with a bad frame, curve, node or stiffness as kBadHinge,
// each with `where` naming the offending hinge; the valid neighbours of each case are accepted.
// A `plastic` direction's law (yields > 0 and finite, hardening in [0, 1), one slot per
// direction, in range) is checked the same way.
#include <gtest/gtest.h>

#include <ostream>

#include <initializer_list>
#include <limits>

#include "ntn/kernel.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"
#include "support/init_model.hpp"
#include "support/no_heap.hpp"

namespace hinge_init_test {

using B = ntn::HingeBehaviour;

// Three one-element steel beams meeting at x = 1 m: beam 0 from the clamped n0 to n1, beam 1
// from n2 to the clamped n3, beam 2 from n4 to the clamped n5 (along y). Nodes 1, 2 and 4
// coincide. Valid hinges: h0 pins n2 to n1 (free about y), h1 joins n4 to n1 rigidly, h2 (the
// slot the cases edit) joins n4 to n2 with every direction free (no rigid connection).
constexpr ntn::Sizes kS{.nodes = 6,
                        .elements = 3,
                        .outputs = 1,
                        .hinges = 3,
                        .curves = 2,
                        .curve_points = 6,
                        .hystereses = 3};
ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;

void base(ntn::HingeMethod method = ntn::HingeMethod::kNtnExact) {
  spec = {};
  const ntn_test::Section sec = ntn_test::rectangle(0.05, 0.08);
  spec.nodes[0] = {0, 0, 0, ntn_test::kFixedAll, {}};
  spec.nodes[1] = {1, 0, 0, 0, {}};
  spec.nodes[2] = {1, 0, 0, 0, {}};
  spec.nodes[3] = {2, 0, 0, ntn_test::kFixedAll, {}};
  spec.nodes[4] = {1, 0, 0, 0, {}};
  spec.nodes[5] = {1, 1, 0, ntn_test::kFixedAll, {}};
  spec.elements[0] = ntn_test::element(0, 1, ntn_test::kSteel, sec, {0, 0, 1});
  spec.elements[1] = ntn_test::element(2, 3, ntn_test::kSteel, sec, {0, 0, 1});
  spec.elements[2] = ntn_test::element(4, 5, ntn_test::kSteel, sec, {0, 0, 1});
  spec.hinges[0] = ntn_test::hinge(2, 1, ntn_test::kIdentity3, ntn_test::released(1U << ntn::kRy));
  spec.hinges[1] = ntn_test::hinge(4, 1, ntn_test::kIdentity3);
  spec.hinges[2] = ntn_test::hinge(4, 2, ntn_test::kIdentity3, ntn_test::released(0x3f));
  // Curve 0: a valid gap; curve 1: a plain valid spring (used by the curve cases).
  spec.curve_points = {
      {{-1.1e-3, -1e9}, {-1e-3, 0}, {1e-3, 0}, {1.1e-3, 1e9}, {-1, -1e6}, {1, 1e6}}};
  spec.curves[0] = {0, 4};
  spec.curves[1] = {4, 2};
  spec.settings.limit_stiffness = 1e12;
  spec.settings.limit_rotational_stiffness = 1e12;
  spec.settings.hinge_method = method;
  spec.settings.penalty_stiffness = 1e10;
  spec.settings.penalty_rotational_stiffness = 1e8;
  spec.outputs[0].kind = ntn::OutputKind::kHingeForce;
  spec.outputs[0].hinge = 2;
  spec.settings.dt = 1e-7;  // below every step these variants can have
}

ntn::InitStatus init() {
  const ntn_test::EigenNoMalloc guard;
  return ntn_test::init_model(spec, model);
}

void expect_error(ntn::InitError error, std::initializer_list<int> where, const char* what) {
  const ntn::InitStatus st = init();
  EXPECT_EQ(st.error, error) << what << ": got " << ntn::to_string(st.error) << " at " << st.where;
  bool named = false;
  for (const int w : where)
    named |= st.where == w;
  EXPECT_TRUE(named) << what << ": where = " << st.where;
}

TEST(HingeInit, TheBaseModelIsValidUnderEveryMethod) {
  for (const ntn::HingeMethod m :
       {ntn::HingeMethod::kNtnExact, ntn::HingeMethod::kNtnPaper, ntn::HingeMethod::kPenalty}) {
    base(m);
    const ntn::InitStatus st = init();
    EXPECT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  }
  base();
  ASSERT_TRUE(init().ok());
  EXPECT_EQ(model.num_edges, 2);  // h0 and h1; h2 has no rigid direction
  EXPECT_EQ(model.num_roots, 1);
  EXPECT_EQ(model.hinge_edge[2], -1);
}

TEST(HingeInit, RigidCyclesAreRefused) {
  // Two hinges between the same pair, both rigid somewhere: h2 duplicates h0 (n2 - n1).
  base();
  spec.hinges[2] = ntn_test::hinge(2, 1, ntn_test::kIdentity3, ntn_test::released(0x38));
  expect_error(ntn::InitError::kRigidCycle, {0, 2}, "two hinges between one pair");
  // A triangle n1 - n2 - n4 - n1.
  base();
  spec.hinges[2].behaviour = ntn_test::kAllRigid;
  expect_error(ntn::InitError::kRigidCycle, {0, 1, 2}, "triangle");
  // A tree with two supports: n1 - n2 - n3 (clamped) and n1 - n5 (clamped) through hinges.
  base();
  spec.hinges[1] = ntn_test::hinge(5, 1, ntn_test::kIdentity3);
  spec.hinges[2] = ntn_test::hinge(3, 2, ntn_test::kIdentity3);
  expect_error(ntn::InitError::kRigidCycle, {0, 1, 2}, "tree with two supports");
  // A supported node that also has a hinge to the ground: two ways to the ground.
  base();
  spec.hinges[2] = ntn_test::hinge(3, ntn::kGround, ntn_test::kIdentity3);
  expect_error(ntn::InitError::kRigidCycle, {2}, "support and ground hinge");
  // Two hinges to the ground in one tree (n1 via h1's tree: n4 - n1, n1 - n2).
  base();
  spec.hinges[0] = ntn_test::hinge(1, ntn::kGround, ntn_test::kIdentity3);
  spec.hinges[2] = ntn_test::hinge(4, ntn::kGround, ntn_test::kIdentity3);
  expect_error(ntn::InitError::kRigidCycle, {0, 1, 2}, "two ground hinges in one tree");
}

TEST(HingeInit, ValidNeighboursOfTheCyclesAreAccepted) {
  // A second hinge on the same pair with every direction free is no connection.
  base();
  spec.hinges[2] = ntn_test::hinge(2, 1, ntn_test::kIdentity3, ntn_test::released(0x3f));
  EXPECT_TRUE(init().ok());
  // One support in a tree is its root, not a cycle.
  base();
  spec.hinges[2] = ntn_test::hinge(3, 2, ntn_test::kIdentity3);
  EXPECT_TRUE(init().ok());
  // Penalty has no forest: redundant stiff springs are a valid (if stiff) model.
  base(ntn::HingeMethod::kPenalty);
  spec.hinges[2].behaviour = ntn_test::kAllRigid;
  EXPECT_TRUE(init().ok());
}

TEST(HingeInit, BadFramesAreRefused) {
  base();
  spec.hinges[1].frame = {1, 0, 0, 0, 1.01, 0, 0, 0, 1};  // a row not of unit length
  expect_error(ntn::InitError::kBadHinge, {1}, "row of length 1.01");
  base();
  spec.hinges[1].frame = {1, 0, 0, 0, 1, 0, 0, 0, -1};  // left-handed
  expect_error(ntn::InitError::kBadHinge, {1}, "left-handed frame");
  base();
  spec.hinges[1].frame = {1, 0, 0, 0.1, 1, 0, 0, 0, 1};  // rows not orthogonal
  expect_error(ntn::InitError::kBadHinge, {1}, "rows not orthogonal");
  base();
  spec.hinges[1].frame = {1, 0, 0, 0, 1, 1e-8, 0, 0, 1};  // off by 1e-8 (the limit is 1e-9)
  expect_error(ntn::InitError::kBadHinge, {1}, "orthogonal only to 1e-8");
  // A frame built in floating point (orthonormal to rounding) is accepted.
  base();
  spec.hinges[1].frame =
      ntn_test::skewed_frame(ntn_test::member_frame({0, 0, 0}, {1, 2, 2}, {0, 0, 1}));
  EXPECT_TRUE(init().ok());
}

TEST(HingeInit, BadCurvesAreRefused) {
  auto with_curve = [](int curve) {
    base();
    spec.hinges[1].behaviour[ntn::kUz] = B::kCurve;
    spec.hinges[1].curve[ntn::kUz] = curve;
  };
  with_curve(0);
  EXPECT_TRUE(init().ok());  // the gap
  with_curve(1);
  EXPECT_TRUE(init().ok());  // a plain spring
  with_curve(2);
  expect_error(ntn::InitError::kBadHinge, {1}, "curve index out of range");
  with_curve(-1);
  expect_error(ntn::InitError::kBadHinge, {1}, "negative curve index");
  with_curve(1);
  spec.curves[1] = {4, 1};
  expect_error(ntn::InitError::kBadHinge, {1}, "one point");
  with_curve(1);
  spec.curves[1] = {4, 3};
  expect_error(ntn::InitError::kBadHinge, {1}, "points past the end");
  with_curve(0);
  spec.curve_points[2].d = -1e-3;  // two points at the same deformation
  expect_error(ntn::InitError::kBadHinge, {1}, "deformation not increasing");
  with_curve(0);
  spec.settings.limit_stiffness = 1e14;  // no segment is rigid: the curve is all spring
  EXPECT_TRUE(init().ok());
  with_curve(0);  // spring, rigid, spring: a rigid segment between spring ones
  spec.curve_points[0] = {-1e-3, 0};
  spec.curve_points[1] = {0, 0};
  spec.curve_points[2] = {1e-4, 1e9};
  spec.curve_points[3] = {1e-3, 1e9};
  expect_error(ntn::InitError::kBadHinge, {1}, "rigid segment inside the curve");
  with_curve(1);
  spec.curve_points[4].force = 1e6;  // a curve that is all rigid branch
  spec.curve_points[5].force = 1e13;
  expect_error(ntn::InitError::kBadHinge, {1}, "no spring segment");
}

TEST(HingeInit, OtherBadHingesAreRefused) {
  base();
  spec.hinges[1].node1 = kS.nodes;
  expect_error(ntn::InitError::kBadHinge, {1}, "node 1 out of range");
  base();
  spec.hinges[1].node2 = -2;
  expect_error(ntn::InitError::kBadHinge, {1}, "node 2 out of range");
  base();
  spec.hinges[1].node2 = spec.hinges[1].node1;
  expect_error(ntn::InitError::kBadHinge, {1}, "a node joined to itself");
  base();
  spec.hinges[1] =
      ntn_test::hinge(4, ntn::kGround, ntn_test::kIdentity3, ntn_test::kAllRigid, {0, 0, 0.1});
  expect_error(ntn::InitError::kBadHinge, {1}, "eccentric ground hinge");
  base();
  spec.hinges[1].behaviour[ntn::kRx] = B::kLinear;
  spec.hinges[1].stiffness[ntn::kRx] = -1;
  expect_error(ntn::InitError::kBadHinge, {1}, "negative stiffness");
  base();
  spec.hinges[1].behaviour[ntn::kRx] = B::kLinear;
  spec.hinges[1].stiffness[ntn::kRx] = 1e4;
  spec.hinges[1].dashpot[ntn::kRx] = -1;
  expect_error(ntn::InitError::kBadHinge, {1}, "negative dashpot");
  base(ntn::HingeMethod::kPenalty);
  spec.settings.penalty_rotational_stiffness = 0;  // rigid rotations need a penalty spring
  expect_error(ntn::InitError::kBadHinge, {0}, "penalty without a rotational stiffness");
  base();
  spec.outputs[0].hinge = 3;
  expect_error(ntn::InitError::kBadOutput, {0}, "hinge channel out of range");
  base();
  spec.outputs[0].kind = ntn::OutputKind::kHingeDisplacement;
  spec.outputs[0].dof = 6;
  expect_error(ntn::InitError::kBadOutput, {0}, "hinge channel direction out of range");
}

// `plastic` directions: hinge 2 (free, n4 to n2) gets rx in slot 0 and ry in slot 1,
// laws valid at their edges (hardening 0 and just below 1, tiny and large yields), then one thing
// made bad at a time: a yield not > 0 or not finite, a hardening outside [0, 1), a slot out of
// range or negative, a slot taken by two directions (of one hinge, or of two: the second one
// named), a plastic direction without a positive elastic stiffness or with a negative dashpot.
void plastic_base() {
  base();
  ntn::HingeSpec& h = spec.hinges[2];
  for (const int d : {ntn::kRx, ntn::kRy}) {
    const auto k = static_cast<std::size_t>(d);
    h.behaviour[k] = B::kPlastic;
    h.stiffness[k] = 1e4;
    h.dashpot[k] = 1.0;
    h.hysteresis[k] = d - ntn::kRx;
  }
  spec.hystereses[0] = {1e-12, 5e3, 0.0};
  spec.hystereses[1] = {2e3, 1e250, 0.999999};
  // slot 2 unused: its (all-zero, invalid) law is never read
}

TEST(HingeInit, PlasticLawsAreChecked) {
  plastic_base();
  {
    const ntn::InitStatus st = init();
    EXPECT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  }
  struct Law {
    ntn::HysteresisSpec law;
    const char* what;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Law& c :
       {Law{{0.0, 5e3, 0.0}, "yield 0"}, Law{{-1.0, 5e3, 0.0}, "negative yield"},
        Law{{1e3, 0.0, 0.0}, "yield_negative 0"}, Law{{1e3, -5e3, 0.0}, "negative yield_negative"},
        Law{{nan, 5e3, 0.0}, "NaN yield"}, Law{{1e3, inf, 0.0}, "infinite yield_negative"},
        Law{{1e3, 5e3, 1.0}, "hardening 1"}, Law{{1e3, 5e3, -0.01}, "negative hardening"},
        Law{{1e3, 5e3, nan}, "NaN hardening"}}) {
    plastic_base();
    spec.hystereses[1] = c.law;
    expect_error(ntn::InitError::kBadHinge, {2}, c.what);
  }
  plastic_base();
  spec.hinges[2].hysteresis[ntn::kRy] = 3;
  expect_error(ntn::InitError::kBadHinge, {2}, "slot out of range");
  plastic_base();
  spec.hinges[2].hysteresis[ntn::kRy] = -1;
  expect_error(ntn::InitError::kBadHinge, {2}, "negative slot");
  plastic_base();
  spec.hinges[2].hysteresis[ntn::kRy] = 0;
  expect_error(ntn::InitError::kBadHinge, {2}, "one slot, two directions of a hinge");
  plastic_base();
  spec.hinges[0].behaviour[ntn::kRy] = B::kPlastic;  // the pin's free direction
  spec.hinges[0].stiffness[ntn::kRy] = 1e4;
  spec.hinges[0].hysteresis[ntn::kRy] = 1;
  expect_error(ntn::InitError::kBadHinge, {2}, "one slot, directions of two hinges");
  spec.hinges[0].hysteresis[ntn::kRy] = 2;  // its own slot, with a valid law: accepted
  spec.hystereses[2] = {1e3, 1e3, 0.5};
  {
    const ntn::InitStatus st = init();
    EXPECT_TRUE(st.ok()) << ntn::to_string(st.error) << " at " << st.where;
  }
  plastic_base();
  spec.hinges[2].stiffness[ntn::kRx] = 0;
  expect_error(ntn::InitError::kBadHinge, {2}, "plastic without elastic stiffness");
  plastic_base();
  spec.hinges[2].dashpot[ntn::kRx] = -1;
  expect_error(ntn::InitError::kBadHinge, {2}, "plastic with a negative dashpot");
}

}  // namespace hinge_init_test
