// Modal analysis of the 20-element cantilever:
// config/cantilever.toml through the model loader, the first three bending frequencies of each
// plane against the Euler-Bernoulli closed form.
//
// Closed form: omega_i = (beta_i L)^2 sqrt(E I / (rho A)) / L^2 with cos(x) cosh(x) = -1.
//
// What the issue asks and what this model can give. The issue asks for the first three within
// 0.5 %. With the kernel's lumped (HRZ) mass the discrete model itself is off the continuum by
// -0.129 %, -0.499 % and -0.892 % at 20 elements (tests/validation/cantilever_test.cpp derives and
// checks this: the error comes from the diagonal rotational mass rho A l^3 / 78 and converges at
// second order; a consistent mass would give +0.002 %). A modal analysis that solves the kernel's
// own eigenproblem exactly therefore reproduces those figures: modes 1 and 2 meet 0.5 %, mode 3
// cannot at 20 elements. So: modes 1 and 2 are held to 0.5 %; mode 3 to 1 % at 20 elements, a
// deliberate, reported deviation; and all three to 0.5 % at 40 elements (the same file with
// `divisions = 40`), where the discretization error has dropped fourfold.
//
// That the library solves exactly the kernel's problem is checked separately: its frequencies
// equal the tests' own dense solution of M^-1/2 K M^-1/2 (support/assemble.hpp, no hinges: the
// supported DOFs removed) to 1e-9 relative, the rounding of two symmetric eigensolvers on
// matrices whose eigenvalues span ~10 decades.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "support/assemble.hpp"
#include "support/closed_forms.hpp"

namespace modal_cantilever_test {

std::string read(const std::string& path) {
  std::string text;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return text;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0)
    text.append(buf, n);
  std::fclose(f);
  return text;
}

// Share of a mode's kinetic energy in the given node DOFs (lumped mass).
double energy_share(const ntn::modal::ModalResult& r, const Eigen::VectorXd& m, int mode,
                    std::initializer_list<int> dofs) {
  double part = 0, all = 0;
  for (Eigen::Index j = 0; j < r.shapes.rows(); ++j) {
    const double e = m(j) * r.shapes(j, mode) * r.shapes(j, mode);
    all += e;
    for (int d : dofs)
      if (j % 6 == d) part += e;
  }
  return part / all;
}

struct Plane {
  const char* name;
  int u, r;  // deflection and rotation DOFs
  double I;  // m^4
};

// The bending frequency errors (relative to the closed form) of the first three modes of each
// plane: [plane][mode].
std::vector<std::vector<double>> bending_errors(const std::string& text, int divisions) {
  const auto loaded = ntn::modelc::load_model_from_string(text, "cantilever.toml");
  EXPECT_TRUE(loaded.ok());
  if (!loaded.ok()) return {};
  const ntn::modelc::ModelDescription& d = *loaded.model;
  EXPECT_EQ(static_cast<int>(d.elements.size()), divisions);
  ntn::modal::ModalOptions o;
  o.modes = 16;
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(d.view(), o);
  EXPECT_TRUE(r.ok()) << r.error;
  if (!r.ok()) return {};
  const ntn::ElementSpec& e = d.elements[0];
  const double L = 2.0;  // m, the file's member length
  const Eigen::VectorXd m = ntn_test::lumped_mass(d.view());
  std::vector<std::vector<double>> out;
  for (const Plane& p : {Plane{"x-z (uz, Iy)", ntn::kUz, ntn::kRy, e.Iy},
                         Plane{"x-y (uy, Iz)", ntn::kUy, ntn::kRz, e.Iz}}) {
    std::vector<double> err;
    for (int i = 0; i < r.modes() && err.size() < 3; ++i) {
      if (energy_share(r, m, i, {p.u, p.r}) < 0.99) continue;
      const double b = ntn_test::cantilever_beta_l(static_cast<int>(err.size()));
      const double omega = b * b / (L * L) * std::sqrt(e.E * p.I / (e.rho * e.A));
      err.push_back(r.omega(i) / omega - 1.0);
      std::printf(
          "  %d elements, plane %s, bending mode %zu (mode %d): %.4f Hz, closed form "
          "%.4f Hz, error %+.3f %%\n",
          divisions, p.name, err.size(), i + 1, r.frequency(i),
          omega / (2 * 3.14159265358979323846), 100 * err.back());
    }
    EXPECT_EQ(err.size(), 3U) << p.name;
    out.push_back(err);
  }
  return out;
}

TEST(ModalCantilever, FirstThreeBendingFrequencies) {
  const std::string text = read(NTN_CONFIG_DIR "/cantilever.toml");
  ASSERT_FALSE(text.empty());
  const auto e20 = bending_errors(text, 20);
  ASSERT_EQ(e20.size(), 2U);
  for (const auto& plane : e20) {
    ASSERT_EQ(plane.size(), 3U);
    EXPECT_LT(std::abs(plane[0]), 5e-3);  // the 0.5 %
    EXPECT_LT(std::abs(plane[1]), 5e-3);  // the 0.5 %
    EXPECT_LT(std::abs(plane[2]), 1e-2);  // 1 %: lumped mass at 20 elements (see above)
    // Lumped mass lowers the frequencies: the errors are negative and grow with the mode.
    EXPECT_LT(plane[0], 0.0);
    EXPECT_LT(plane[2], plane[1]);
  }
  std::string fine = text;
  const std::size_t at = fine.find("divisions = 20");
  ASSERT_NE(at, std::string::npos);
  fine.replace(at, 14, "divisions = 40");
  const auto e40 = bending_errors(fine, 40);
  ASSERT_EQ(e40.size(), 2U);
  for (std::size_t p = 0; p < 2; ++p) {
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(e40[p][i]), 5e-3) << "40 elements, mode " << i + 1;  // the 0.5 %
      // Second order: doubling the elements divides the error by about 4 (3 to 5).
      const double ratio = e20[p][i] / e40[p][i];
      EXPECT_GT(ratio, 3.0);
      EXPECT_LT(ratio, 5.0);
    }
  }
}

// The library's eigenproblem is the kernel's: the same frequencies as the tests' dense
// M^-1/2 K M^-1/2 on the unsupported DOFs (no hinges), all modes, 1e-9 relative.
TEST(ModalCantilever, EqualsTheDenseReferenceOfTheKernelMatrices) {
  const auto loaded = ntn::modelc::load_model(NTN_CONFIG_DIR "/cantilever.toml");
  ASSERT_TRUE(loaded.ok());
  const ntn::SpecView v = loaded.model->view();
  ntn::modal::ModalOptions o;
  o.modes = 0;  // all
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(v, o);
  ASSERT_TRUE(r.ok()) << r.error;
  const ntn_test::Modes ref = ntn_test::modes(v);
  ASSERT_EQ(r.modes(), ref.omega.size());
  EXPECT_EQ(r.modes(), 6 * 20);
  double worst = 0;
  for (int i = 0; i < r.modes(); ++i)
    worst = std::max(worst, std::abs(r.omega(i) / ref.omega(i) - 1.0));
  std::printf("  all %d modes: max |library / reference - 1| = %.2e\n", r.modes(), worst);
  EXPECT_LT(worst, 1e-9);
}

}  // namespace modal_cantilever_test
