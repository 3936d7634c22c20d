// Modal analysis with hinges (DESIGN §7, §7.1): the library's
// constraint transformation u = T q against an independent exact condensation, rigid hinges
// against merged nodes, mechanisms and massless joints, curves linearized at the origin.
//
// The reference for hinged models is the tests' own: K and M assembled densely from the kernel's
// element functions, the supports as removed DOFs, the rigid hinge rows of B = T [-I -E I 0;
// 0 -I 0 I] written from DESIGN §7 in tests/support/assemble.hpp (not from the library or the
// kernel), and the eigenproblem solved on the null space of those rows (an SVD):
// ntn_test::constrained_modes, the condensation the hinge release tests use. The
// library instead eliminates the rigid directions tree by tree. Both are exact; they differ by
// rounding only.
//
// Tolerances. The issue's figure is 0.1 % (kIssueTolerance). Because both sides are exact, this
// file also holds them to 1e-8 relative (kExact): the SVD's null-space basis and the forest's T
// carry rounding of ~1e-15 into matrices whose eigenvalues span ~8 decades (bending rotations with
// ~1e-3 kg m^2 against translations), which leaves ~1e-10 on the lowest frequencies (measured:
// at most 4e-11 below). A wrong sign in an eccentric link, a lost free direction or a wrong
// effective mass shifts frequencies by 1e-3 to 1e-1.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/frame_models.hpp"
#include "modal_models.hpp"
#include "ntn/modal/constraints.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "support/assemble.hpp"
#include "support/builders.hpp"
#include "support/hinges.hpp"

namespace modal_hinges_test {

using modal_test::B;
using ntn::modal::ModalOptions;
using ntn::modal::ModalResult;

constexpr double kIssueTolerance = 1e-3;
constexpr double kExact = 1e-8;
constexpr int kModes = 8;

ModalOptions options(int modes = kModes) {
  ModalOptions o;
  o.modes = modes;
  return o;
}

// ---- Released hinge (the models of tests/validation/hinge_release_test.cpp) ----

// Clamped-clamped beam, 4 m, 8 elements, cut at midspan (nodes 4 and 9), 100 x 150 mm.
constexpr int kN = 8, kMid = 4, kExtra = 9;
constexpr ntn::Sizes kBeam{.nodes = kN + 2, .elements = kN, .hinges = 1};
constexpr std::uint8_t kReleaseRy = 1U << ntn::kRy;

void build_beam(ntn::ModelSpec<kBeam>& s, const ntn_test::Mat3& frame, std::uint8_t release) {
  s = {};
  ntn_test::split_beam(s, 4.0, ntn_test::kSteel, ntn_test::rectangle(0.1, 0.15), kMid, kExtra,
                       ntn_test::kFixedAll, ntn_test::kFixedAll);
  s.hinges[0] = ntn_test::hinge(kExtra, kMid, frame, ntn_test::released(release));
}

// Plane portal: columns 3 m (3 elements each, clamped), beam 6 m (4 elements) pinned to the left
// column top through a hinge released about the beam's local y.
constexpr ntn::Sizes kPortal{.nodes = 12, .elements = 10, .hinges = 1};

void build_portal(ntn::ModelSpec<kPortal>& s, std::uint8_t release) {
  s = {};
  ntn_test::FrameBuilder<kPortal> f(s);
  const int base_l = f.add_node({0, 0, 0}, ntn_test::kFixedAll);
  const int base_r = f.add_node({6, 0, 0}, ntn_test::kFixedAll);
  const int top_l = f.add_node({0, 0, 3});
  const int top_r = f.add_node({6, 0, 3});
  const int beam_start = f.add_node({0, 0, 3});
  f.add_member(base_l, top_l, 3, ntn_test::kSteel, ntn_test::rectangle(0.2, 0.2), {1, 0, 0});
  f.add_member(base_r, top_r, 3, ntn_test::kSteel, ntn_test::rectangle(0.2, 0.2), {1, 0, 0});
  f.add_member(beam_start, top_r, 4, ntn_test::kSteel, ntn_test::rectangle(0.15, 0.3), {0, 0, 1});
  EXPECT_TRUE(f.complete());
  const ntn_test::Mat3 frame = ntn_test::member_frame({0, 0, 3}, {6, 0, 3}, {0, 0, 1});
  s.hinges[0] = ntn_test::hinge(beam_start, top_l, frame, ntn_test::released(release));
}

TEST(ModalHinges, ReleasedHingeEqualsExactCondensation) {
  static ntn::ModelSpec<kBeam> beam, rigid;
  const ntn_test::Mat3 member = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  const ntn_test::Mat3 turned =
      ntn_test::rotate_frame(member, ntn_test::rotation({1, 0, 0}, 30 * ntn_test::kDegree));
  for (const auto& [name, frame] :
       {std::pair{"beam, member frame", member}, std::pair{"beam, frame turned 30 deg", turned}}) {
    build_beam(beam, frame, kReleaseRy);
    build_beam(rigid, frame, 0);
    const ModalResult r = ntn::modal::modal_analysis(ntn::view(beam), options());
    const ntn_test::Modes ref = ntn_test::constrained_modes(ntn::view(beam));
    const double d = modal_test::compare_with_reference(name, r, ref, kModes);
    EXPECT_LT(d, kIssueTolerance);
    EXPECT_LT(d, kExact);
    // The release matters by far more than the tolerance, so the comparison can fail.
    const ModalResult rr = ntn::modal::modal_analysis(ntn::view(rigid), options());
    ASSERT_TRUE(rr.ok());
    const double effect = modal_test::max_relative_difference(r.omega, rr.omega, 4);
    std::printf("    the release changes the first 4 frequencies by up to %.1f %%\n", 100 * effect);
    EXPECT_GT(effect, 100 * kIssueTolerance);
  }
  static ntn::ModelSpec<kPortal> portal;
  build_portal(portal, kReleaseRy);
  const ModalResult r = ntn::modal::modal_analysis(ntn::view(portal), options());
  const double d = modal_test::compare_with_reference(
      "portal", r, ntn_test::constrained_modes(ntn::view(portal)), kModes);
  EXPECT_LT(d, kIssueTolerance);
  EXPECT_LT(d, kExact);
}

// Every joint kind of DESIGN §7.1: several hinges with different frames on one node, chains,
// eccentric hinges with released rotations whose child is node 2, hinges to the ground (inclined
// support) and to a supported node, linear springs.
TEST(ModalHinges, JointKindsEqualExactCondensation) {
  static ntn::ModelSpec<modal_test::kStar> star;
  static ntn::ModelSpec<modal_test::kChain> chain;
  static ntn::ModelSpec<modal_test::kEccentricChain> ecc;
  static ntn::ModelSpec<modal_test::kSupported> sup;
  modal_test::build_star(star);
  modal_test::build_chain(chain);
  modal_test::build_eccentric_chain(ecc);
  modal_test::build_supported(sup);
  struct Case {
    const char* name;
    ntn::SpecView v;
    int trees;
  };
  for (const Case& c : {Case{"star joint", ntn::view(star), 1}, Case{"chain", ntn::view(chain), 1},
                        Case{"eccentric chain", ntn::view(ecc), 1},
                        Case{"supports through hinges", ntn::view(sup), 3}}) {
    const ModalResult r = ntn::modal::modal_analysis(c.v, options());
    const double d =
        modal_test::compare_with_reference(c.name, r, ntn_test::constrained_modes(c.v), kModes);
    EXPECT_LT(d, kIssueTolerance) << c.name;
    EXPECT_LT(d, kExact) << c.name;
    EXPECT_EQ(r.trees, c.trees) << c.name;
    EXPECT_TRUE(r.mechanisms.empty()) << c.name;
  }
}

// The mode shapes satisfy the constraints: every rigid hinge row of B (written independently in
// tests/support) gives zero relative displacement, to rounding (1e-12 of the shape's largest
// translation: T's entries are exact up to one rounding of a 6x6 product).
TEST(ModalHinges, ShapesHoldTheRigidDirections) {
  static ntn::ModelSpec<modal_test::kEccentricChain> ecc;
  modal_test::build_eccentric_chain(ecc);
  const ntn::SpecView v = ntn::view(ecc);
  const ModalResult r = ntn::modal::modal_analysis(v, options());
  ASSERT_TRUE(r.ok()) << r.error;
  const Eigen::MatrixXd C = ntn_test::rigid_constraints(v);
  for (int i = 0; i < r.modes(); ++i) {
    const double top = r.shapes.col(i).cwiseAbs().maxCoeff();
    EXPECT_LT((C * r.shapes.col(i)).cwiseAbs().maxCoeff(), 1e-12 * top) << "mode " << i + 1;
  }
  // Mass-normalized: phi^T M phi = 1 with the kernel's lumped mass, to 1e-12.
  const Eigen::VectorXd m = ntn_test::lumped_mass(v);
  for (int i = 0; i < r.modes(); ++i)
    EXPECT_NEAR(r.shapes.col(i).dot(m.asDiagonal() * r.shapes.col(i)), 1.0, 1e-12);
}

// Rigid hinges are merged nodes: the benchmark frame with a node of its own and an NTN hinge at
// every beam end, all six directions rigid, against the same frame with beams and columns sharing
// nodes. The merged node's lumped mass is the sum of the tied nodes' (zero eccentricity), so the
// two eigenproblems are the same up to rounding. Tolerance 1e-9 relative (the issue's check
// list): measured ~1e-13.
TEST(ModalHinges, RigidHingesEqualMergedNodes) {
  constexpr ntn::bench::Grid kG{.nx = 2, .ny = 1, .storeys = 2, .col_div = 2, .beam_div = 2};
  auto& merged = ntn::bench::static_instance<ntn::ModelSpec<ntn::bench::sizes_of(kG)>>();
  auto& hinged = ntn::bench::static_instance<
      ntn::ModelSpec<ntn::bench::sizes_of(kG, ntn::bench::Joints::kPinned)>>();
  ntn::bench::build_frame<kG>(merged);
  ntn::bench::build_frame<kG, ntn::bench::Joints::kPinned>(hinged);
  for (ntn::HingeSpec& h : hinged.hinges)
    h.behaviour.fill(B::kRigid);
  const ModalResult a = ntn::modal::modal_analysis(ntn::view(merged), options(20));
  const ModalResult b = ntn::modal::modal_analysis(ntn::view(hinged), options(20));
  ASSERT_TRUE(a.ok()) << a.error;
  ASSERT_TRUE(b.ok()) << b.error;
  EXPECT_EQ(b.trees, ntn::bench::joints_per_level(kG) * kG.storeys);  // a joint and its beam ends
  EXPECT_EQ(a.coordinates, b.coordinates);
  const double d = modal_test::max_relative_difference(b.omega, a.omega, 20);
  std::printf("  frame, %zu hinges all rigid vs merged: f1 %.6f Hz, max |rel diff| %.2e\n",
              hinged.hinges.size(), a.frequency(0), d);
  EXPECT_LT(d, 1e-9);
  // Shapes: the hinged frame's joint nodes move as the merged frame's (MAC 1 to 1e-9).
  for (int i = 0; i < 20; ++i) {
    const double gap = std::min(i > 0 ? a.omega(i) / a.omega(i - 1) - 1 : 1.0,
                                i < 19 ? a.omega(i + 1) / a.omega(i) - 1 : 1.0);
    if (gap < 1e-6) continue;  // a (nearly) repeated frequency: the shape is not unique
    // The first nodes of both frames are the joints (frame_models.hpp numbers them first).
    const int nj = ntn::bench::joints_per_level(kG) * (kG.storeys + 1);
    EXPECT_GT(ntn::modal::mac(a.shapes.col(i).head(6 * nj), b.shapes.col(i).head(6 * nj)), 1 - 1e-9)
        << "mode " << i + 1;
  }
}

// config/frame3d.toml's member-end releases made rigid give the moment frame of the same file
// without the release lines (no hinges). As tests/modelc/modelc_frame3d_modes_test.cpp, now with
// the library on both.
TEST(ModalHinges, Frame3dRigidReleasesGiveTheMomentFrame) {
  std::string text;
  {
    std::FILE* f = std::fopen(NTN_CONFIG_DIR "/frame3d.toml", "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
      text.append(buf, n);
    std::fclose(f);
  }
  std::string moment = text;
  for (const char* line : {"release_start = [\"ry\", \"rz\"]  # pinned to the exterior column A: "
                           "bending released\n",
                           "release_end = [\"ry\", \"rz\"]  # pinned to the exterior column C: "
                           "bending released\n"}) {
    for (std::size_t p = moment.find(line); p != std::string::npos; p = moment.find(line))
      moment.erase(p, std::string(line).size());
  }
  moment.erase(moment.find("# Shear and axial force in the pinned connection"));
  const auto plain = ntn::modelc::load_model_from_string(moment, "moment.toml");
  auto hinged = ntn::modelc::load_model_from_string(text, "frame3d.toml");
  ASSERT_TRUE(plain.ok() && hinged.ok());
  ASSERT_TRUE(plain.model->hinges.empty());
  ASSERT_EQ(hinged.model->hinges.size(), 8U);
  for (ntn::HingeSpec& h : hinged.model->hinges)
    h.behaviour.fill(B::kRigid);
  const ModalResult a = ntn::modal::modal_analysis(plain.model->view(), options(12));
  const ModalResult b = ntn::modal::modal_analysis(hinged.model->view(), options(12));
  ASSERT_TRUE(a.ok() && b.ok());
  const double d = modal_test::max_relative_difference(b.omega, a.omega, 12);
  std::printf("  frame3d releases rigid vs no releases: max |rel diff| %.2e\n", d);
  EXPECT_LT(d, 1e-9);
}

// Mechanisms (DESIGN §7.1): tests/modelc/good/pinned_joint.toml's joint has no mass of its own
// and nothing holds its rotation about z. The library removes exactly the DOFs the model compiler
// reports, and what is left equals the reference with that DOF held by a support (the kernel
// holds it at zero).
TEST(ModalHinges, MechanismRemovedAsTheCompilerReports) {
  const auto loaded = ntn::modelc::load_model(NTN_MODELC_GOOD_DIR "/pinned_joint.toml");
  ASSERT_TRUE(loaded.ok());
  const ntn::modelc::ModelDescription& d = *loaded.model;
  ASSERT_EQ(d.mechanisms.size(), 1U);
  const ModalResult r = ntn::modal::modal_analysis(d.view(), options(6));
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.mechanisms.size(), d.mechanisms.size());
  EXPECT_EQ(r.mechanisms[0].node, d.mechanisms[0].node);
  EXPECT_EQ(r.mechanisms[0].dofs, d.mechanisms[0].dofs);
  EXPECT_EQ(r.mechanism_dofs, 1);
  ASSERT_FALSE(r.notes.empty());
  std::printf("  %s\n", r.notes.back().c_str());
  ntn::modelc::ModelDescription held = d;
  held.nodes[static_cast<std::size_t>(d.mechanisms[0].node)].fixed |= d.mechanisms[0].dofs;
  const double diff = modal_test::compare_with_reference(
      "pinned joint", r, ntn_test::constrained_modes(held.view()), 6);
  EXPECT_LT(diff, kExact);
}

// A massless joint with springs: the star joint with translational mass only, every rotation of
// its four hinges that was rigid made a rotational spring. The joint's rotations then have no
// mass but stiffness, and are condensed statically (exact for undamped modes: no inertia there).
// Truth: the reference with a joint inertia eps -> 0, whose lowest modes approach the condensed
// problem as eps -> 0: eps = 1e-7 kg m^2, against ~1e-2 kg m^2 of rotational mass at the member
// ends, may leave up to ~1e-5 (measured 2e-9); tolerance 1e-4, and the same reference at 1e3 eps
// must be farther off (measured 4e-7: the convergence is real).
TEST(ModalHinges, MasslessJointWithSpringsIsCondensed) {
  static ntn::ModelSpec<modal_test::kStar> s;
  auto build = [](ntn::ModelSpec<modal_test::kStar>& spec, double inertia) {
    modal_test::build_star(spec);
    spec.nodes[0].added = {20, 20, 20, inertia, inertia, inertia};
    for (ntn::HingeSpec& h : spec.hinges) {
      for (std::size_t k = 3; k < 6; ++k) {
        if (h.behaviour[k] != B::kRigid) continue;
        h.behaviour[k] = B::kLinear;
        h.stiffness[k] = 1e5 * static_cast<double>(1 + k);  // N m/rad
      }
    }
  };
  build(s, 0.0);
  const ModalResult r = ntn::modal::modal_analysis(ntn::view(s), options(6));
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.condensed, 3);  // the joint's three rotations
  EXPECT_TRUE(r.mechanisms.empty());
  build(s, 1e-7);
  const double near = modal_test::compare_with_reference(
      "massless joint vs eps", r, ntn_test::constrained_modes(ntn::view(s)), 6);
  build(s, 1e-4);
  const double far = modal_test::compare_with_reference(
      "massless joint vs 1e3 eps", r, ntn_test::constrained_modes(ntn::view(s)), 6);
  EXPECT_LT(near, 1e-4);
  EXPECT_GT(far, 10 * near);
}

// Curves linearized at the origin (constraints.hpp): the origin on a rigid branch ties the
// direction (frequencies of the rigid hinge), inside the spring part it is a spring with the
// slope there (frequencies of the linear hinge). Both references are models validated above.
TEST(ModalHinges, CurvesAreLinearizedAtTheOrigin) {
  constexpr ntn::Sizes kCurveBeam{
      .nodes = kN + 2, .elements = kN, .hinges = 1, .curves = 2, .curve_points = 7};
  static ntn::ModelSpec<kCurveBeam> c;
  static ntn::ModelSpec<kBeam> rigid, linear;
  const ntn_test::Mat3 member = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  c = {};
  ntn_test::split_beam(c, 4.0, ntn_test::kSteel, ntn_test::rectangle(0.1, 0.15), kMid, kExtra,
                       ntn_test::kFixedAll, ntn_test::kFixedAll);
  c.hinges[0] =
      ntn_test::hinge(kExtra, kMid, member, ntn_test::released(kReleaseRy | 1U << ntn::kRz));
  c.settings.limit_rotational_stiffness = 1e9;
  // Curve 0: a gap of +-1 mrad with a 2e5 N m/rad spring inside and rigid stops (slope 1e10)
  // outside; the origin is inside the spring part.
  // Curve 1: rigid (slope 1e10) up to 1 mrad, then a soft spring: the origin is on the rigid
  // branch.
  c.curve_points = {ntn::CurvePoint{-2e-3, -1e7 - 200},
                    {-1e-3, -200},
                    {1e-3, 200},
                    {2e-3, 1e7 + 200},
                    {-1e-3, -1e7},
                    {1e-3, 1e7},
                    {2e-3, 1e7 + 1e3}};
  c.curves[0] = {0, 4};
  c.curves[1] = {4, 3};
  c.hinges[0].behaviour[ntn::kRy] = B::kCurve, c.hinges[0].curve[ntn::kRy] = 0;
  c.hinges[0].behaviour[ntn::kRz] = B::kCurve, c.hinges[0].curve[ntn::kRz] = 1;
  build_beam(linear, member, kReleaseRy);  // rz rigid, ry a 2e5 N m/rad spring
  linear.hinges[0].behaviour[ntn::kRy] = B::kLinear;
  linear.hinges[0].stiffness[ntn::kRy] = 2e5;
  const ModalResult r = ntn::modal::modal_analysis(ntn::view(c), options());
  const ModalResult l = ntn::modal::modal_analysis(ntn::view(linear), options());
  ASSERT_TRUE(r.ok() && l.ok()) << r.error << l.error;
  const double d = modal_test::max_relative_difference(r.omega, l.omega, kModes);
  std::printf("  curves: max |rel diff| to the linear / rigid hinge %.2e; notes:\n", d);
  for (const std::string& n : r.notes)
    std::printf("    %s\n", n.c_str());
  EXPECT_LT(d, 1e-12);  // the same matrices, assembled in the same order
  build_beam(rigid, member, kReleaseRy);
  const ModalResult rr = ntn::modal::modal_analysis(ntn::view(rigid), options());
  EXPECT_GT(modal_test::max_relative_difference(r.omega, rr.omega, 4), 1e-3);  // the spring acts
}

// Penalty springs in the rigid directions converge to the exact ties at first order in 1 / k_p:
// the frequency differences at k_p and 10 k_p are in the ratio 10 (within 20 %).
TEST(ModalHinges, PenaltySpringsConvergeToTheExactTies) {
  static ntn::ModelSpec<kBeam> s;
  const ntn_test::Mat3 member = ntn_test::member_frame({0, 0, 0}, {1, 0, 0}, {0, 0, 1});
  build_beam(s, member, kReleaseRy);
  const ModalResult exact = ntn::modal::modal_analysis(ntn::view(s), options());
  double diff[2];
  for (int i = 0; i < 2; ++i) {
    const double k = 1e11 * std::pow(10.0, i);
    s.settings.penalty_stiffness = k, s.settings.penalty_rotational_stiffness = k / 10;
    ModalOptions o = options();
    o.penalty_as_springs = true;
    const ModalResult p = ntn::modal::modal_analysis(ntn::view(s), o);
    ASSERT_TRUE(p.ok()) << p.error;
    diff[i] = modal_test::max_relative_difference(p.omega, exact.omega, 4);
    std::printf("  penalty k_p %.0e: max |rel diff| to exact ties %.3e\n", k, diff[i]);
  }
  EXPECT_NEAR(diff[0] / diff[1], 10.0, 2.0);
  EXPECT_LT(diff[1], 1e-3);
}

// What the kernel and the model compiler refuse is refused here too, with a message.
TEST(ModalHinges, CyclesAndBadHingesAreRefused) {
  static ntn::ModelSpec<modal_test::kChain> s;
  modal_test::build_chain(s);
  s.hinges[2].node1 = 1;  // D-C becomes A-C: A-B-C-A is a cycle of rigid connections
  ModalResult r = ntn::modal::modal_analysis(ntn::view(s), options());
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.error.find("cycle"), std::string::npos) << r.error;
  modal_test::build_chain(s);
  s.hinges[0].frame[0] = 2.0;  // not orthonormal
  r = ntn::modal::modal_analysis(ntn::view(s), options());
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.error.find("hinge 0"), std::string::npos) << r.error;
}

}  // namespace modal_hinges_test
