// Nodes and frames, against truth nobody here chose:
// - plane = "xz": good/portal_xz.toml and its 3D twin good/portal_xz_3d.toml (a user node at every
//   mesh point, uy, rx, rz held by supports on every user node) are one structure; the compiler
//   must make the same spec of both, so modal analysis (tools/modal) gives the same frequencies
//   and the kernel the same u and v, bit for bit, over 4000 steps of the same ground motion.
// - point masses on an offset: the mass the model carries through the rigid offset, seen at the
//   node (T^T M T over tools/modal's exact constraint map, which is built on the kernel's forest),
//   is the rigid body's closed form [m I, -m [e]x; m [e]x, I_c - m [e]x [e]x]; and a cantilever
//   with its tip mass on a rigid arm along its axis vibrates at omega^2 = 1 / (m f_C), f_C the
//   beam-theory flexibility at the mass centre; the kernel, started in the first mode of
//   good/tip_mass_arm.toml, vibrates at that mode's frequency (central difference's discrete one).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "ntn/kernel.hpp"
#include "ntn/modal/constraints.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "portal_xz_3d_model.hpp"
#include "portal_xz_model.hpp"
#include "support/init_model.hpp"
#include "support/zero_crossings.hpp"
#include "tip_mass_arm_model.hpp"

namespace modelc_nodes_physics_test {

using ntn::modelc::ModelDescription;

ModelDescription load(const std::string& file) {
  const auto r = ntn::modelc::load_model(std::string(NTN_MODELC_GOOD_DIR) + "/" + file);
  EXPECT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  return r.ok() ? *r.model : ModelDescription{};
}

ModelDescription load_text(const std::string& text) {
  const auto r = ntn::modelc::load_model_from_string(text, "m.toml");
  EXPECT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  return r.ok() ? *r.model : ModelDescription{};
}

// ---- plane -----------------------------------------------------------------------------------

TEST(ModelcPlanePhysics, PortalInPlaneIsItsThreeDimensionalTwin) {
  const ModelDescription a = load("portal_xz.toml");
  const ModelDescription b = load("portal_xz_3d.toml");
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].x, b.nodes[i].x) << i;
    EXPECT_EQ(a.nodes[i].z, b.nodes[i].z) << i;
    EXPECT_EQ(a.nodes[i].fixed, b.nodes[i].fixed) << i;
  }
  ASSERT_EQ(a.hinges.size(), 1U);
  ASSERT_EQ(b.hinges.size(), 1U);
  EXPECT_EQ(a.hinges[0].behaviour, b.hinges[0].behaviour);
  EXPECT_EQ(a.hinges[0].frame, b.hinges[0].frame);
  EXPECT_EQ(a.settings.dt, b.settings.dt);

  // Modal analysis: the same frequencies to the last bit, and no mass moves out of plane.
  ntn::modal::ModalOptions o;
  o.modes = 10;
  const ntn::modal::ModalResult ma = ntn::modal::modal_analysis(a.view(), o);
  const ntn::modal::ModalResult mb = ntn::modal::modal_analysis(b.view(), o);
  ASSERT_TRUE(ma.ok()) << ma.error;
  ASSERT_TRUE(mb.ok()) << mb.error;
  ASSERT_EQ(ma.modes(), mb.modes());
  for (int i = 0; i < ma.modes(); ++i) {
    EXPECT_EQ(ma.frequency(i), mb.frequency(i)) << "mode " << i + 1;
    EXPECT_EQ(ma.effective_mass(i, 1), 0.0) << "mode " << i + 1;
  }
  std::printf("  portal_xz: f1..f3 = %.6f %.6f %.6f Hz (plane) = %.6f %.6f %.6f Hz (3D twin)\n",
              ma.frequency(0), ma.frequency(1), ma.frequency(2), mb.frequency(0), mb.frequency(1),
              mb.frequency(2));
}

namespace p2 = ntn::models::portal_xz;
namespace p3 = ntn::models::portal_xz_3d;
static_assert(p2::kSizes.nodes == p3::kSizes.nodes && p2::kSizes.hinges == p3::kSizes.hinges);

ntn::Model<p2::kSizes> g_m2;
ntn::State<p2::kSizes> g_s2;
ntn::Scratch<p2::kSizes> g_w2;
ntn::Model<p3::kSizes> g_m3;
ntn::State<p3::kSizes> g_s3;
ntn::Scratch<p3::kSizes> g_w3;

TEST(ModelcPlanePhysics, KernelGivesTheSameBitsAsTheThreeDimensionalTwin) {
  ASSERT_TRUE(ntn_test::init_model(p2::kSpec, g_m2).ok());
  ASSERT_TRUE(ntn_test::init_model(p3::kSpec, g_m3).ok());
  ASSERT_EQ(g_m2.dt, g_m3.dt);
  // 4000 steps (1 s at dt = 0.25 ms) of a 0.3 g, 1.7 Hz ground acceleration along x.
  auto ag = [](long n, double dt) {
    return 0.3 * std::sin(2.0 * std::numbers::pi * 1.7 * static_cast<double>(n) * dt);
  };
  ASSERT_EQ(ntn::start(g_m2, g_s2, g_w2, {ag(0, g_m2.dt)}), ntn::StepStatus::kOk);
  ASSERT_EQ(ntn::start(g_m3, g_s3, g_w3, {ag(0, g_m3.dt)}), ntn::StepStatus::kOk);
  long differing = 0;
  double top = 0, out_of_plane = 0;
  for (long n = 0; n < 4000; ++n) {
    ASSERT_EQ(ntn::step(g_m2, g_s2, g_w2, {ag(n, g_m2.dt)}), ntn::StepStatus::kOk);
    ASSERT_EQ(ntn::step(g_m3, g_s3, g_w3, {ag(n, g_m3.dt)}), ntn::StepStatus::kOk);
    differing += g_s2.u == g_s3.u && g_s2.v == g_s3.v ? 0 : 1;
    for (std::size_t j = 0; j < g_s2.u.size(); ++j) {
      const std::size_t d = j % 6;
      if (d == ntn::kUy || d == ntn::kRx || d == ntn::kRz) {
        out_of_plane = std::max(out_of_plane, std::abs(g_s2.u[j]));
      } else {
        top = std::max(top, std::abs(g_s2.u[j]));
      }
    }
  }
  EXPECT_EQ(differing, 0);  // steps at which u or v differ in any bit
  EXPECT_EQ(out_of_plane, 0.0);
  EXPECT_GT(top, 1e-4);  // the frame did move: a comparison of two rests would prove nothing
  std::printf("  portal_xz: 4000 steps, largest in-plane |u| %.3e, out of plane %.1e\n", top,
              out_of_plane);
}

// ---- point masses on an offset -----------------------------------------------------------------

// A cantilever of 2 m along x (node 1 fixed, node 2 the tip) with a point mass on an offset.
std::string cantilever(const std::string& rho, const std::string& divisions,
                       const std::string& point_mass) {
  return R"([model]
name = "m"

[[materials]]
id = "steel"
E = 2.1e11
G = 8.1e10
rho = )" +
         rho +
         R"(

[[sections]]
id = "s"
A = 1e-2
Iy = 2e-5
Iz = 8e-6
J = 1e-5

[[nodes]]
id = 1
xyz = [0, 0, 0]

[[nodes]]
id = 2
xyz = [2, 0, 0]

[[members]]
id = "M"
nodes = [1, 2]
material = "steel"
section = "s"
divisions = )" +
         divisions + R"(

[[supports]]
node = 1
fix = "all"

[[point_masses]]
node = 2
)" + point_mass;
}

Eigen::Matrix3d cross(const Eigen::Vector3d& e) {  // [e]x a = e x a
  Eigen::Matrix3d X;
  X << 0, -e(2), e(1), e(2), 0, -e(0), -e(1), e(0), 0;
  return X;
}

TEST(ModelcPointMassOffsetPhysics, RigidBodyMassSeenAtTheNodeIsTheClosedForm) {
  const double m = 500;
  const Eigen::Vector3d e(0.3, -0.2, 0.5);
  const Eigen::Vector3d Ic(10, 20, 30);
  const ModelDescription d = load_text(
      cantilever("7850", "4", "mass = 500\ninertia = [10, 20, 30]\noffset = [0.3, -0.2, 0.5]\n"));
  ASSERT_EQ(d.hinges.size(), 1U);
  const int tip = 1;
  const int centre = d.hinges[0].node2;
  const ntn::SpecView v = d.view();
  const auto lin = ntn::modal::linearize_hinges(v);
  ASSERT_TRUE(lin.error.empty()) << lin.error;
  const ntn::modal::ConstraintMap cm = ntn::modal::build_constraints(v, lin.hinges);
  ASSERT_TRUE(cm.error.empty()) << cm.error;
  // The tree {tip, centre}: its 6 coordinates. S and C map them to the two nodes' DOFs; the
  // point mass seen through the node's DOFs is (C S^-1)^T M_c (C S^-1), whichever node is root.
  const ntn::modal::ConstraintGroup* g = nullptr;
  for (const auto& grp : cm.groups)
    if (std::find(grp.nodes.begin(), grp.nodes.end(), centre) != grp.nodes.end()) g = &grp;
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(g->columns, 6);
  const Eigen::MatrixXd T(cm.T);
  const Eigen::MatrixXd S = T.block(6 * tip, g->first_column, 6, 6);
  const Eigen::MatrixXd C = T.block(6 * centre, g->first_column, 6, 6);
  const Eigen::MatrixXd A = C * S.inverse();
  Eigen::VectorXd mc(6);
  mc << m, m, m, Ic(0), Ic(1), Ic(2);
  const Eigen::MatrixXd M = A.transpose() * mc.asDiagonal() * A;
  Eigen::MatrixXd ref(6, 6);
  const Eigen::Matrix3d E = cross(e);
  ref.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  ref.topRightCorner<3, 3>() = -m * E;
  ref.bottomLeftCorner<3, 3>() = m * E;
  ref.bottomRightCorner<3, 3>() = Eigen::Matrix3d(Ic.asDiagonal()) - m * E * E;
  // 1e-12 of the largest entry: T holds direction cosines and lever arms of order 1, so the
  // products round at ~1e-16 relative; 1e-12 leaves room for S^-1 and still catches any wrong
  // sign or lever arm (each changes an entry by m |e| ~ 100 kg m, 1e-1 relative).
  const double err = (M - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
  EXPECT_LT(err, 1e-12) << "M =\n" << M << "\nclosed form =\n" << ref;
  std::printf("  point mass on offset: |T^T M T - closed form| / max = %.2e\n", err);
}

TEST(ModelcPointMassOffsetPhysics, TipMassOnARigidArmVibratesAtTheBeamTheoryFrequency) {
  // A nearly massless cantilever (rho 1e-3 kg/m^3: 2e-5 kg against 100 kg) carrying 100 kg on a
  // rigid arm e = 0.5 m along its axis. A transverse force P at the mass centre moves it by
  // P f_C, f_C = L^3 / (3 EI) + L^2 e / EI + L e^2 / EI (tip deflection and rotation of a
  // cantilever under P and the moment P e, carried over the arm), so omega^2 = 1 / (m f_C) in
  // each bending plane (Iy: along z, Iz: along y). The Euler-Bernoulli element is exact for
  // nodal loads, so the only error is the beam's own mass, 2e-7 of the tip's: tolerance 1e-6.
  // One element: the tip's DOFs then take their mass from the tree (interior nodes with the
  // beam's tiny mass alone make the eigenproblem ill-conditioned: measured 1e-5 off with 4).
  const double m = 100, L = 2, e = 0.5, E = 2.1e11;
  const ModelDescription d =
      load_text(cantilever("1e-3", "1", "mass = 100\noffset = [0.5, 0, 0]\n"));
  ntn::modal::ModalOptions o;
  o.modes = 2;
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(d.view(), o);
  ASSERT_TRUE(r.ok()) << r.error;
  auto omega = [&](double I) {
    const double f = L * L * L / (3 * E * I) + L * L * e / (E * I) + L * e * e / (E * I);
    return std::sqrt(1.0 / (m * f));
  };
  const double w_y = omega(8e-6), w_z = omega(2e-5);  // the softer plane first
  EXPECT_NEAR(r.omega(0) / w_y, 1.0, 1e-6);
  EXPECT_NEAR(r.omega(1) / w_z, 1.0, 1e-6);
  std::printf("  tip mass on a rigid arm: %.6f / %.6f Hz (modal) vs %.6f / %.6f Hz (beam theory)\n",
              r.frequency(0), r.frequency(1), w_y / (2 * std::numbers::pi),
              w_z / (2 * std::numbers::pi));
}

// AFNOR SDLL15/89 b (good/sdll15b.toml): a 10 m cantilever tube with 1000 kg on a 1 m rigid
// offset. Published: 1.636 Hz (bending + torsion) and 1.642 Hz (bending + tension), then 13.46,
// 13.59, 28.90, 31.96 Hz. Tolerance 0.5 % on the first two; 20 lumped-mass
// Euler-Bernoulli elements are within 0.1 % there (the tip mass dominates). The higher modes are
// printed beside the reference: the beam's own lumped mass matters more there.
TEST(ModelcPointMassOffsetPhysics, Sdll15bFirstFrequenciesAreThePublishedOnes) {
  const auto r0 = ntn::modelc::load_model(std::string(NTN_MODELC_GOOD_DIR) + "/sdll15b.toml");
  ASSERT_TRUE(r0.ok());
  ntn::modal::ModalOptions o;
  o.modes = 6;
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(r0.model->view(), o);
  ASSERT_TRUE(r.ok()) << r.error;
  const double ref[6] = {1.636, 1.642, 13.46, 13.59, 28.90, 31.96};
  for (int i = 0; i < 6; ++i) {
    std::printf("  SDLL15b mode %d: %.4f Hz, reference %.3f Hz (%+.2f %%)\n", i + 1, r.frequency(i),
                ref[i], 100 * (r.frequency(i) / ref[i] - 1));
  }
  EXPECT_NEAR(r.frequency(0), 1.636, 0.005 * 1.636);
  EXPECT_NEAR(r.frequency(1), 1.642, 0.005 * 1.642);
}

namespace arm = ntn::models::tip_mass_arm;
ntn::Model<arm::kSizes> g_arm;
ntn::State<arm::kSizes> g_arm_s;
ntn::Scratch<arm::kSizes> g_arm_w;

TEST(ModelcPointMassOffsetPhysics, KernelVibratesAtTheModalFrequency) {
  // As tests/modal/modal_kernel_test.cpp: started from mode 1's shape (1 mm at the largest entry)
  // the kernel's ntn_exact step keeps the mass centre in that mode; the zero crossings of its
  // displacement along y over ~30 periods give the frequency, which must be central difference's
  // discrete one, omega_h = (2 / dt) asin(omega dt / 2), to 1e-6 (there measured to 1.2e-7; a
  // wrong lever arm or effective mass of the offset moves it by 1e-3 or more).
  const ModelDescription d = load("tip_mass_arm.toml");
  ntn::modal::ModalOptions o;
  o.modes = 1;
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(d.view(), o);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_TRUE(ntn_test::init_model(arm::kSpec, g_arm).ok());
  const Eigen::VectorXd phi = r.shapes.col(0);
  ASSERT_EQ(static_cast<std::size_t>(phi.size()), g_arm_s.u.size());
  const double scale = 1e-3 / phi.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < phi.size(); ++j)
    g_arm_s.u[static_cast<std::size_t>(j)] = scale * phi(j);
  const int centre = d.hinges[0].node2;
  const auto uy = static_cast<std::size_t>(6 * centre + ntn::kUy);
  ASSERT_GT(std::abs(g_arm_s.u[uy]), 1e-4);  // mode 1 bends along y (Iz is the softer axis)
  const double dt = g_arm.dt;
  const double omega_h = 2.0 / dt * std::asin(r.omega(0) * dt / 2.0);
  const auto steps = static_cast<long>(30.25 * 2 * std::numbers::pi / omega_h / dt);
  ntn_test::ZeroCrossings zc(g_arm_s.u[uy]);
  ASSERT_EQ(ntn::start(g_arm, g_arm_s, g_arm_w, {}), ntn::StepStatus::kOk);
  for (long n = 0; n < steps; ++n) {
    ASSERT_EQ(ntn::step(g_arm, g_arm_s, g_arm_w, {}), ntn::StepStatus::kOk);
    zc.add(g_arm_s.u[uy], static_cast<double>(g_arm_s.tick) * dt, dt);
  }
  EXPECT_GE(zc.count(), 50);
  const double err = zc.omega() / omega_h - 1.0;
  EXPECT_LT(std::abs(err), 1e-6);
  std::printf(
      "  tip mass on a rigid arm, kernel: %.6f Hz (modal %.6f Hz), omega / omega_h - 1 = "
      "%+.2e over %ld steps\n",
      zc.omega() / (2 * std::numbers::pi), r.frequency(0), err, steps);
}

TEST(ModelcPointMassOffsetPhysics, PenaltySpringsApproachTheExactOffset) {
  // Under "penalty" the rigid offset is six stiff springs (the rotations without inertia free):
  // modal analysis with those springs (penalty_as_springs) must approach the exact ties: the
  // gap is of order (the mode's stiffness / the penalty stiffness), tiny with the default
  // penalty of 1e4 x the stiffest element term (measured 3e-8): tolerance 1e-6. A wrong lever
  // arm (a spring tying u2 to u1 alone) would drop the arm from the flexibility f_C: tens of %.
  std::string text;
  {
    std::FILE* f =
        std::fopen((std::string(NTN_MODELC_GOOD_DIR) + "/tip_mass_arm.toml").c_str(), "rb");
    ASSERT_NE(f, nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
      text.append(buf, n);
    std::fclose(f);
  }
  const std::string exact_text = text;
  const std::string at = "name = \"tip_mass_arm\"\n";
  text.replace(text.find(at), at.size(), at + "hinge_method = \"penalty\"\n");
  const ModelDescription exact = load_text(exact_text);
  const ModelDescription pen = load_text(text);
  ntn::modal::ModalOptions o;
  o.modes = 2;
  const ntn::modal::ModalResult re = ntn::modal::modal_analysis(exact.view(), o);
  o.penalty_as_springs = true;
  const ntn::modal::ModalResult rp = ntn::modal::modal_analysis(pen.view(), o);
  ASSERT_TRUE(re.ok()) << re.error;
  ASSERT_TRUE(rp.ok()) << rp.error;
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(rp.frequency(i) / re.frequency(i), 1.0, 1e-6) << "mode " << i + 1;
    std::printf("  tip mass on a rigid arm, mode %d: penalty %.6f Hz, exact %.6f Hz (%+.2e)\n",
                i + 1, rp.frequency(i), re.frequency(i), rp.frequency(i) / re.frequency(i) - 1);
  }
}

}  // namespace modelc_nodes_physics_test
