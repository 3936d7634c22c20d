// The two eigensolver paths, participation and effective masses, per-node shapes, MAC and the
// mode table (DESIGN §9).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/frame_models.hpp"
#include "modal_models.hpp"
#include "ntn/modal/modal.hpp"
#include "support/assemble.hpp"

namespace modal_solvers_test {

using ntn::modal::ModalOptions;
using ntn::modal::ModalResult;
using ntn::modal::Solver;

ModalResult run(const ntn::SpecView& v, int modes, Solver solver) {
  ModalOptions o;
  o.modes = modes;
  o.solver = solver;
  return ntn::modal::modal_analysis(v, o);
}

// Dense (Eigen, all eigenpairs of the reduced problem) and sparse (Spectra, shift-invert Lanczos
// around 0 with a sparse LDL^T) agree on a medium model: the benchmark frame with every hinge
// kind (pinned beam ends, gap curves read as free at the origin, rotational springs), ~1 700
// DOFs. Tolerance 1e-8 relative on the first 20 frequencies (the brief's figure): both converge
// to working precision (Spectra's tolerance 1e-12 on the Ritz values of the inverted operator),
// so they differ by the dense solver's rounding, ~1e-16 ||A|| / lambda_1 ~ 1e-10 here. Shapes:
// MAC >= 1 - 1e-8 for modes whose frequency is separated from its neighbours by more than 1e-6
// (a repeated frequency has no unique shape).
TEST(ModalSolvers, DenseAndSparseAgree) {
  constexpr ntn::bench::Grid kG{.nx = 3, .ny = 2, .storeys = 3, .col_div = 2, .beam_div = 3};
  auto& spec = ntn::bench::static_instance<
      ntn::ModelSpec<ntn::bench::sizes_of(kG, ntn::bench::Joints::kMixed)>>();
  ntn::bench::build_frame<kG, ntn::bench::Joints::kMixed>(spec);
  const ntn::SpecView v = ntn::view(spec);
  const ModalResult d = run(v, 20, Solver::kDense);
  const ModalResult s = run(v, 20, Solver::kSparse);
  ASSERT_TRUE(d.ok()) << d.error;
  ASSERT_TRUE(s.ok()) << s.error;
  EXPECT_EQ(d.solver, Solver::kDense);
  EXPECT_EQ(s.solver, Solver::kSparse);
  std::printf("  %d DOFs, %d coordinates, %d in the eigenproblem; sparse: %d restarts, %d solves\n",
              d.dofs, d.coordinates, d.reduced, s.iterations, s.operations);
  ASSERT_EQ(d.modes(), 20);
  ASSERT_EQ(s.modes(), 20);
  double worst = 0;
  for (int i = 0; i < 20; ++i)
    worst = std::max(worst, std::abs(s.omega(i) / d.omega(i) - 1.0));
  std::printf("  f1 %.5f Hz, f20 %.5f Hz; max |sparse / dense - 1| = %.2e\n", d.frequency(0),
              d.frequency(19), worst);
  EXPECT_LT(worst, 1e-8);
  int compared = 0;
  for (int i = 0; i < 20; ++i) {
    const double below = i > 0 ? d.omega(i) / d.omega(i - 1) - 1 : 1.0;
    const double above = i < 19 ? d.omega(i + 1) / d.omega(i) - 1 : 1.0;
    if (std::min(below, above) < 1e-6) continue;
    ++compared;
    EXPECT_GT(ntn::modal::mac(d.shapes.col(i), s.shapes.col(i)), 1 - 1e-8) << "mode " << i + 1;
    // The same sign convention on both paths: the largest entry positive.
    EXPECT_GT(d.shapes.col(i).dot(s.shapes.col(i)), 0.0) << "mode " << i + 1;
    EXPECT_NEAR(s.effective_mass(i, 0), d.effective_mass(i, 0), 1e-8 * d.total_mass[0]);
  }
  EXPECT_GE(compared, 10);
  // kAuto picks dense at this size and sparse when the limit is lower.
  ModalOptions o;
  o.modes = 5;
  EXPECT_EQ(ntn::modal::modal_analysis(v, o).solver, Solver::kDense);
  o.dense_limit = 100;
  EXPECT_EQ(ntn::modal::modal_analysis(v, o).solver, Solver::kSparse);
}

// The sum of the lumped masses of every unsupported node, along any direction, computed here
// from the spec (rho A l / 2 per element end, point masses), not with the kernel's assembly.
double free_mass(const ntn::SpecView& v, int d) {
  double m = 0;
  for (const ntn::ElementSpec& e : v.elements) {
    const ntn::NodeSpec& a = v.nodes[static_cast<std::size_t>(e.node_i)];
    const ntn::NodeSpec& b = v.nodes[static_cast<std::size_t>(e.node_j)];
    const double l = std::hypot(b.x - a.x, b.y - a.y, b.z - a.z);
    for (const ntn::NodeSpec* n : {&a, &b})
      if (!((n->fixed >> d) & 1U)) m += e.rho * e.A * l / 2;
  }
  for (const ntn::NodeSpec& n : v.nodes)
    if (!((n.fixed >> d) & 1U)) m += n.added[static_cast<std::size_t>(d)];
  return m;
}

// With all modes computed the effective masses add up to the mass that can move: every
// translation of the unsupported nodes is admissible here (no hinge ties a node to a support or
// the ground), so sum_i Gamma_id^2 = iota^T M iota over the unsupported DOFs (the modes are an
// M-orthonormal basis). Checked on a small frame with pinned beam ends (dense, all modes) to
// 1e-10 relative (a sum of ~600 squares); the cumulative fraction reaches 1.
TEST(ModalSolvers, EffectiveMassesSumToTheTotalMass) {
  constexpr ntn::bench::Grid kG{.nx = 1, .ny = 1, .storeys = 2, .col_div = 2, .beam_div = 2};
  auto& spec = ntn::bench::static_instance<
      ntn::ModelSpec<ntn::bench::sizes_of(kG, ntn::bench::Joints::kPinned)>>();
  ntn::bench::build_frame<kG, ntn::bench::Joints::kPinned>(spec);
  const ntn::SpecView v = ntn::view(spec);
  const ModalResult r = run(v, 0, Solver::kDense);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.modes(), r.reduced);
  for (int d = 0; d < 3; ++d) {
    const double total = free_mass(v, d);
    double sum = 0;
    for (int i = 0; i < r.modes(); ++i)
      sum += r.effective_mass(i, d);
    std::printf("  %c: %d modes, sum of effective masses %.6f kg, free mass %.6f kg\n", "xyz"[d],
                r.modes(), sum, total);
    EXPECT_NEAR(sum, total, 1e-10 * total);
    EXPECT_NEAR(r.total_mass[static_cast<std::size_t>(d)], total, 1e-12 * total);
    EXPECT_NEAR(r.reachable_mass[static_cast<std::size_t>(d)], total, 1e-10 * total);
    EXPECT_NEAR(r.cumulative_fraction(r.modes() - 1, d), 1.0, 1e-10);
  }
}

// Tied to the ground: the inclined support holds part of the column base's mass, so the effective
// masses add up to less than the unsupported mass; the library says so and reports the sum over
// all modes it would reach (reachable_mass), which the full dense solution confirms (1e-10).
TEST(ModalSolvers, MassTiedToTheGroundIsReported) {
  static ntn::ModelSpec<modal_test::kSupported> s;
  modal_test::build_supported(s);
  const ModalResult r = run(ntn::view(s), 0, Solver::kDense);
  ASSERT_TRUE(r.ok()) << r.error;
  bool noted = false;
  for (const std::string& n : r.notes)
    noted = noted || n.find("cannot translate rigidly") != std::string::npos;
  EXPECT_TRUE(noted);
  for (int d = 0; d < 3; ++d) {
    double sum = 0;
    for (int i = 0; i < r.modes(); ++i)
      sum += r.effective_mass(i, d);
    EXPECT_NEAR(sum, r.reachable_mass[static_cast<std::size_t>(d)],
                1e-10 * r.total_mass[static_cast<std::size_t>(d)]);
    EXPECT_LE(r.reachable_mass[static_cast<std::size_t>(d)],
              r.total_mass[static_cast<std::size_t>(d)] * (1 + 1e-12));
  }
}

// Per-node shape access for measured channels and MAC.
TEST(ModalSolvers, ChannelsAndMac) {
  static ntn::ModelSpec<modal_test::kStar> s;
  modal_test::build_star(s);
  const ModalResult r = run(ntn::view(s), 6, Solver::kAuto);
  ASSERT_TRUE(r.ok()) << r.error;
  const std::vector<ntn::modal::Channel> ch{{0, ntn::kUx}, {0, ntn::kUy}, {3, ntn::kUz}};
  const Eigen::MatrixXd at = ntn::modal::shapes_at(r, ch);
  ASSERT_EQ(at.rows(), 3);
  ASSERT_EQ(at.cols(), 6);
  for (int i = 0; i < 6; ++i) {
    for (std::size_t c = 0; c < ch.size(); ++c)
      EXPECT_EQ(at(static_cast<Eigen::Index>(c), i), r.shape(i, ch[c].node, ch[c].dof));
  }
  // MAC by hand: a = (1, 0), b = (1, 1): (a.b)^2 / (|a|^2 |b|^2) = 1 / 2; scale-free; 0 for
  // orthogonal vectors and for a zero vector.
  const Eigen::Vector2d a(1, 0), b(1, 1), c(0, 2);
  EXPECT_DOUBLE_EQ(ntn::modal::mac(a, b), 0.5);
  EXPECT_DOUBLE_EQ(ntn::modal::mac(b, -3.0 * b), 1.0);
  EXPECT_EQ(ntn::modal::mac(a, c), 0.0);
  EXPECT_EQ(ntn::modal::mac(a, Eigen::Vector2d::Zero()), 0.0);
  // Complex (e.g. operational shapes): a phase factor does not change it; (1, i) vs (1, 1): 1/2.
  const Eigen::Vector2cd z(std::complex<double>(1, 0), std::complex<double>(0, 1));
  EXPECT_NEAR(ntn::modal::mac(z, Eigen::Vector2cd(std::complex<double>(0, 2) * z)), 1.0, 1e-15);
  EXPECT_NEAR(ntn::modal::mac(z, Eigen::Vector2cd(1.0, 1.0)), 0.5, 1e-15);
  // The model's shapes at the channels against themselves: 1 on the diagonal.
  const Eigen::MatrixXd M = ntn::modal::mac_matrix(at, at);
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(M(i, i), 1.0, 1e-15);
}

// The mode table: a header, one line per mode with its frequency and period, the totals.
TEST(ModalSolvers, ModeTable) {
  static ntn::ModelSpec<modal_test::kChain> s;
  modal_test::build_chain(s);
  const ModalResult r = run(ntn::view(s), 4, Solver::kAuto);
  ASSERT_TRUE(r.ok()) << r.error;
  const std::string t = ntn::modal::mode_table(r);
  std::printf("%s", t.c_str());
  EXPECT_NE(t.find("mode"), std::string::npos);
  EXPECT_NE(t.find("Mx %"), std::string::npos);
  char line[64];
  for (int i = 0; i < 4; ++i) {
    std::snprintf(line, sizeof line, "%5d %11.5g %10.5g", i + 1, r.frequency(i), r.period(i));
    EXPECT_NE(t.find(line), std::string::npos) << line;
  }
  EXPECT_NE(t.find("total mass free to move"), std::string::npos);
  ModalResult bad;
  bad.error = "x";
  EXPECT_NE(ntn::modal::mode_table(bad).find("failed: x"), std::string::npos);
}

}  // namespace modal_solvers_test
