// Rayleigh damping set at two of a model's own modes ([model.damping] ratio with modes = [1, 2],
// config/README.md), integrated by the kernel: free decay from each of the two mode shapes gives
// the specified ratio.
//
// The model: a 2 m steel cantilever strip, 200 mm wide (along y) and 20 mm thick (along z), 5
// elements; Iz / Iy = 100, so modes 1 and 2 are the first two bending modes in the x-z plane
// (4.1 and 24 Hz; the first bending mode about z is near 41 Hz, torsion above that), which the
// test checks by their effective masses. The compiler computes the modes (ntn::modal, as
// `ntn-model modes`) and sets alpha = 2 xi w1 w2 / (w1 + w2), beta = 2 xi / (w1 + w2). Rotary
// inertia and 5 elements keep the test short: beta K makes the stable step about
// 2 / (beta omega_max^2), and the strip's stiff in-plane bending of short elements against their
// small HRZ rotation masses sets omega_max (10 elements without rotary inertia: dt = 3e-7 s and
// a 13 s test). The discretisation does not matter here: the modes are the model's own.
//
// The truth is the definition of the damping ratio: a linear mode with ratio xi decays as
// A exp(-xi w t) cos(w_d t), so the logarithmic decrement between maxima one damped period apart
// is delta = 2 pi xi / sqrt(1 - xi^2), xi = delta / sqrt(4 pi^2 + delta^2). C = alpha M + beta K
// is proportional (no hinges), so a mode shape stays a mode. Measurement: the modal coordinate
// q = phi^T M u after the start from u = a phi (the analysis' mass-normalized shape), v = 0;
// delta over several cycles, from its maxima. Tolerance 2 % relative on xi (the issue's): the
// damping lagged to v_{n-1/2} and the discrete maxima shift it by O(w dt), here below 1e-3.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "ntn/kernel.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "support/init_model.hpp"

namespace modal_damping_test {

constexpr ntn::Sizes kS{.nodes = 6, .elements = 5};

ntn::ModelSpec<kS> spec;
ntn::Model<kS> model;
ntn::State<kS> state;
ntn::Scratch<kS> scratch;

const char* const kModel = R"(
[model]
name = "strip"
dt = "auto"
frame_rate = 1000.0
rotary_inertia = true

[model.damping]
ratio = 0.02
modes = [1, 2]

[[materials]]
id = "steel"
E = 210e9
nu = 0.3
rho = 7850.0

[[sections]]
id = "strip"
A = 4.0e-3
Iy = 1.3333333333333333e-7
Iz = 1.3333333333333333e-5
J = 5.0e-7

[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [2.0, 0.0, 0.0]

[[members]]
id = "strip"
nodes = [1, 2]
material = "steel"
section = "strip"
divisions = 5

[[supports]]
node = 1
fix = "all"
)";

// The description's arrays into the fixed-size spec (sizes checked).
template <class T, std::size_t N>
bool copy(std::span<const T> from, std::array<T, N>& to) {
  if (from.size() != N) return false;
  std::copy(from.begin(), from.end(), to.begin());
  return true;
}

TEST(RayleighDamping, FreeDecayOfBothModesGivesTheRatio) {
  const auto loaded = ntn::modelc::load_model_from_string(kModel, "strip.toml");
  ASSERT_TRUE(loaded.model.has_value()) << (loaded.errors.empty() ? "" : loaded.errors[0].message);
  const ntn::modelc::ModelDescription& d = *loaded.model;
  const ntn::SpecView v = d.view();
  ASSERT_TRUE(copy(v.nodes, spec.nodes) && copy(v.elements, spec.elements));
  spec.settings = v.settings;
  ntn::modal::ModalOptions o;
  o.modes = 2;
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(v, o);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.modes(), 2);
  // The compiler's coefficients: the ratio at both modes (1e-12: rounding of the formula).
  const double xi = 0.02;
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(r.mass_fraction(i, 2), 0.05) << "mode " << i + 1 << " bends in x-z";
    EXPECT_NEAR(r.damping_ratio(i), xi, 1e-12 * xi) << "mode " << i + 1;
  }
  EXPECT_GT(spec.settings.beta, 0.0);
  ASSERT_TRUE(ntn_test::init_model(spec, model).ok());

  const Eigen::VectorXd m = Eigen::Map<const Eigen::VectorXd>(model.mass.data(), 6 * kS.nodes);
  for (int i = 0; i < 2; ++i) {
    const Eigen::VectorXd phi = r.shapes.col(i);
    state = {};
    const double a = 1e-3 / phi.cwiseAbs().maxCoeff();  // 1 mm at the largest entry
    for (Eigen::Index j = 0; j < phi.size(); ++j)
      state.u[static_cast<std::size_t>(j)] = a * phi(j);
    auto coordinate = [&]() {
      double q = 0;
      for (Eigen::Index j = 0; j < phi.size(); ++j)
        q += phi(j) * m(j) * state.u[static_cast<std::size_t>(j)];
      return q;
    };
    ASSERT_EQ(ntn::start(model, state, scratch, {}), ntn::StepStatus::kOk);
    // Maxima of q over `cycles` damped periods (a maximum: q above both neighbours).
    const int cycles = i == 0 ? 6 : 20;
    const double period = 2 * std::numbers::pi / r.omega(i);
    const auto steps = static_cast<long>((cycles + 0.5) * period / model.dt);
    std::vector<double> maxima;
    double q0 = coordinate(), q1 = q0;
    maxima.push_back(q0);  // t = 0: v = 0, the first maximum
    for (long n = 0; n < steps; ++n) {
      ASSERT_EQ(ntn::step(model, state, scratch, {}), ntn::StepStatus::kOk);
      const double q2 = coordinate();
      if (q1 > q0 && q1 >= q2 && q1 > 0) maxima.push_back(q1);
      q0 = q1, q1 = q2;
    }
    ASSERT_GE(static_cast<int>(maxima.size()), cycles + 1) << "mode " << i + 1;
    const double delta = std::log(maxima[0] / maxima[static_cast<std::size_t>(cycles)]) / cycles;
    const double measured =
        delta / std::sqrt(4 * std::numbers::pi * std::numbers::pi + delta * delta);
    std::printf(
        "  mode %d (%.3f Hz): dt = %.3e s, %d cycles: log decrement %.5f, ratio %.5f (set "
        "%.3f): %+.3f %%\n",
        i + 1, r.frequency(i), model.dt, cycles, delta, measured, xi, 100 * (measured / xi - 1));
    EXPECT_NEAR(measured / xi, 1.0, 0.02) << "mode " << i + 1;
  }
}

}  // namespace modal_damping_test
