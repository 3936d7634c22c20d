// Second-order geometry (geometry = "p_delta", leaning columns: ntn/geometry.hpp) against closed
// forms of stability theory (Timoshenko and Gere, Theory of Elastic Stability, 2nd ed., §1.2,
// §2.1, §2.15) and the statics of a mechanism:
// 1. a pinned column's lateral frequency under an axial load P falls as
//    omega_0 sqrt(1 - P / P_cr), P_cr = pi^2 E I / L^2 (the buckling and the vibration mode are
//    the same sine), from free vibration about the static preload; above P_cr it diverges;
// 2. a cantilever column's lateral deflection under a tip force H and an axial P is
//    H / (P k) (tan kL - kL), k = sqrt(P / E I), about 1 / (1 - P / P_cr) times the linear one,
//    P_cr = pi^2 E I / (4 L^2), from the static preload, where the kernel's step keeps it at rest;
// 3. a portal with perfectly plastic hinges under gravity and a slowly growing lateral force
//    forms its sway mechanism at H h = 4 M_p - P Delta (the P-Delta-reduced mechanism load),
//    where the linear portal needs H h = 4 M_p; a leaning column carries its load into the same
//    equation without stiffness of its own;
// 4. the stable step's bound of the second-order terms: a bar in tension past the bound is
//    counted and flagged, one below it is not;
// 5. geometry = "linear" is the model without the key, to the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "books_run.hpp"
#include "ntn/hil/energy.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "text_model.hpp"

namespace p_delta_test {

using Rt = ntn::hil::LoadedModel;
constexpr double kPi = std::numbers::pi;

// A steel column of an IPE 200 about its strong axis, in the x-z plane: E I = 4.08e6 N m^2.
constexpr double kE = 210e9, kIy = 1943e-8, kA = 28.48e-4, kRho = 7850;
constexpr double kL = 4.0;
constexpr double kEI = kE * kIy;

std::string materials() {
  return R"(
[[materials]]
id = "S355"
E = 210e9
nu = 0.3
rho = 7850.0

[[sections]]
id = "IPE200"
A = 28.48e-4
Iy = 1943e-8
Iz = 142.4e-8
J = 6.98e-8
)";
}

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A vertical column of kL in `divisions` elements from node 1 (base) to node 2 (top), with an
// axial load -P at the top (preloaded statically) and a lateral load H there.
std::string column(const std::string& base, const std::string& top, double P, double H,
                   const std::string& geometry, int divisions) {
  std::string t = R"(
[model]
name = "column"
plane = "xz"
)";
  if (!geometry.empty()) t += "geometry = \"" + geometry + "\"\n";
  t += materials();
  t += R"(
[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [0.0, 0.0, 4.0]

[[members]]
id = "C"
nodes = [1, 2]
material = "S355"
section = "IPE200"
divisions = )" +
       std::to_string(divisions) +
       R"(

[[supports]]
node = 1
fix = )" +
       base +
       R"(

[[supports]]
node = 2
fix = )" +
       top +
       R"(

[[loads]]
node = 2
dof = "uz"
value = )" +
       num(-P) +
       R"(

[[loads]]
node = 2
dof = "ux"
value = )" +
       num(H) +
       R"(

[[outputs]]
name = "mid_ux"
kind = "displacement"
node = { member = "C", at = 0.5 }
dof = "ux"

[[outputs]]
name = "top_ux"
kind = "displacement"
node = 2
dof = "ux"

[initial]
gravity = "static"
)";
  return t;
}

std::unique_ptr<Rt> load(const std::string& text) {
  return ntn_test::load_text_model(text, "column.toml");
}

// Starts from the preload u_0 plus `du` (per DOF), runs `steps` and returns output `channel`.
std::vector<double> run(Rt& rt, std::span<const double> du, long steps, std::size_t channel) {
  ntn::Model<ntn::kRunTime>& m = rt.model();
  ntn::State<ntn::kRunTime>& s = rt.state();
  ntn::Scratch<ntn::kRunTime>& w = rt.scratch();
  ntn::initial_state(m, s);
  for (std::size_t j = 0; j < du.size(); ++j)
    s.u[j] += du[j];
  std::vector<double> none;
  EXPECT_NE(ntn::start(m, s, w, std::span<const double>(none)), ntn::StepStatus::kDiverged);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(steps));
  for (long n = 0; n < steps; ++n) {
    if (ntn::step(m, s, w, std::span<const double>(none)) == ntn::StepStatus::kDiverged) break;
    out.push_back(w.outputs[channel]);
  }
  return out;
}

// ux = a sin(pi z / L) at every node of the column (its first buckling and vibration mode).
std::vector<double> sine_mode(const Rt& rt, double a) {
  const auto& nodes = rt.spec().nodes;
  std::vector<double> du(ntn::kDofsPerNode * nodes.size(), 0.0);
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    du[ntn::kDofsPerNode * n + ntn::kUx] = a * std::sin(kPi * nodes[n].z / kL);
    du[ntn::kDofsPerNode * n + ntn::kRy] = a * kPi / kL * std::cos(kPi * nodes[n].z / kL);
    for (std::size_t k = 0; k < ntn::kDofsPerNode; ++k)
      if ((nodes[n].fixed >> k) & 1U) du[ntn::kDofsPerNode * n + k] = 0.0;  // a support's
  }
  return du;
}

// The mean period of x - mean(x) from its upward zero crossings (linear interpolation), s.
double period(const std::vector<double>& x, double dt) {
  double mean = 0;
  for (double v : x)
    mean += v;
  mean /= static_cast<double>(x.size());
  std::vector<double> up;
  for (std::size_t n = 1; n < x.size(); ++n) {
    const double a = x[n - 1] - mean, b = x[n] - mean;
    if (a < 0 && b >= 0) up.push_back((static_cast<double>(n - 1) + a / (a - b)) * dt);
  }
  if (up.size() < 2) return 0;
  return (up.back() - up.front()) / static_cast<double>(up.size() - 1);
}

constexpr const char* kPinned = "\"pinned\"";
constexpr const char* kRoller = "[\"ux\", \"uy\"]";
constexpr double kPcrPinned = kPi * kPi * kEI / (kL * kL);  // 2.517 MN

// 1. The pinned column's lateral frequency against sqrt(1 - P / P_cr). Tolerance 0.5 %: the
// column is 20 elements, whose chord strings (P-Delta per element) underestimate the buckling
// load by about (pi / 20)^2 / 12 = 0.2 %, which moves sqrt(1 - P / P_cr) by 0.2 % at P = 0.7
// P_cr; the period is read from 40 crossings to 1e-5. omega_0 itself is the discrete column's
// (measured at P = 0), so the test is the ratio.
TEST(PDelta, PinnedColumnFrequencyFallsAsTheSquareRootOfOneLessPOverPcr) {
  double T0 = 0;
  for (const double ratio : {0.0, 0.25, 0.5, 0.7}) {
    const auto rt = load(column(kPinned, kRoller, ratio * kPcrPinned, 0.0, "p_delta", 20));
    ASSERT_NE(rt, nullptr);
    const double dt = rt->model().dt;
    const std::vector<double> du = sine_mode(*rt, 1e-4 * kL);
    // The first period at P = 0: pi / L^2 sqrt(E I / (rho A)) -> 0.0358 s; 40 periods at 0.7.
    const long steps = std::lround(40 * 0.0358 / std::sqrt(1 - ratio) / dt);
    const std::vector<double> x = run(*rt, du, steps, 0);
    ASSERT_EQ(x.size(), static_cast<std::size_t>(steps));
    const double T = period(x, dt);
    if (ratio == 0.0) T0 = T;
    const double measured = T0 / T, expected = std::sqrt(1 - ratio);
    std::printf(
        "  P / P_cr = %.2f: period %.6f s, omega / omega_0 = %.5f, sqrt(1 - P/P_cr) = "
        "%.5f (%+.3f %%)\n",
        ratio, T, measured, expected, 100 * (measured / expected - 1));
    EXPECT_NEAR(measured / expected, 1.0, 5e-3);
    EXPECT_EQ(rt->state().geometry_bound, 0U);
    // Modal analysis about the preload (K + K_g of its axial forces) gives the same frequency as
    // the run (1e-3: the period's reading and the central difference's dispersion at this dt).
    ntn::modal::ModalOptions o;
    o.modes = 1;
    const ntn::modal::ModalResult modes = ntn::modal::modal_analysis(rt->description().view(), o);
    ASSERT_TRUE(modes.ok()) << modes.error;
    EXPECT_NEAR(modes.frequency(0) * T, 1.0, 1e-3);
    if (ratio == 0.7) {  // ntn-model info says how P-Delta moves the lowest frequency
      const std::string info = ntn::modelc::info_text(rt->description());
      EXPECT_NE(info.find("20 p_delta element(s)"), std::string::npos) << info;
      EXPECT_NE(info.find("Hz about the preload with P-Delta"), std::string::npos) << info;
    }
  }
  // The discrete omega_0 against the continuous column's pi^2 / L^2 sqrt(E I / (rho A)): 1 %.
  const double omega0 = kPi * kPi / (kL * kL) * std::sqrt(kEI / (kRho * kA));
  EXPECT_NEAR(2 * kPi / T0 / omega0, 1.0, 1e-2);
}

// Above P_cr there is no static equilibrium (the compiler's preload says so at the key), and a
// column preloaded below it diverges once the load passes P_cr: the sine grows by more than 1e3
// where at 0.9 P_cr it stays at its amplitude.
TEST(PDelta, AColumnAbovePcrHasNoEquilibriumAndDiverges) {
  const ntn::modelc::LoadResult r = ntn::modelc::load_model_from_string(
      column(kPinned, kRoller, 1.1 * kPcrPinned, 0.0, "p_delta", 20), "column.toml");
  ASSERT_FALSE(r.ok());
  const std::string errors = ntn::modelc::format_all(r.errors);
  EXPECT_NE(errors.find("initial.gravity"), std::string::npos) << errors;
  EXPECT_NE(errors.find("buckl"), std::string::npos) << errors;

  // 0.9 P_cr preloaded, then 0.2 P_cr more over 0.1 s: past P_cr from t = 0.05 s.
  std::string text = column(kPinned, kRoller, 0.9 * kPcrPinned, 0.0, "p_delta", 20);
  text += R"(
[[time_functions]]
id = "ramp"
points = [[0.0, 0.0], [0.1, 1.0]]

[[loads]]
node = 2
dof = "uz"
value = )" +
          num(-0.2 * kPcrPinned) +
          R"(
function = "ramp"
)";
  const auto below = load(column(kPinned, kRoller, 0.9 * kPcrPinned, 0.0, "p_delta", 20));
  const auto above = load(text);
  ASSERT_NE(below, nullptr);
  ASSERT_NE(above, nullptr);
  const double a = 1e-6 * kL;
  const long steps = std::lround(0.6 / below->model().dt);
  auto peak = [](const std::vector<double>& x) {
    double p = 0;
    for (double v : x)
      p = std::max(p, std::abs(v));
    return p;
  };
  const double grown_below = peak(run(*below, sine_mode(*below, a), steps, 0)) / a;
  const double grown_above = peak(run(*above, sine_mode(*above, a), steps, 0)) / a;
  std::printf("  peak |u_mid| / a over 0.6 s: %.3f at 0.9 P_cr, %.3e past P_cr\n", grown_below,
              grown_above);
  EXPECT_LT(grown_below, 1.01);
  EXPECT_GT(grown_above, 1e3);
}

// 2. The cantilever's amplification, from the static preload: the exact second-order deflection
// H / (P k) (tan kL - kL) to 0.5 % (20 elements; the string discretization error is 0.2 % of
// P_cr, which the amplification at P = 0.5 P_cr doubles), and 1 / (1 - P / P_cr) times the
// linear H L^3 / (3 E I) to 1 % (the approximation's own error, 0.6 % at 0.5 P_cr). A run from
// the preload stays at rest: the step's second-order forces are the static solve's (1e-9 of the
// deflection).
TEST(PDelta, CantileverDeflectionIsAmplifiedByOneOverOneLessPOverPcr) {
  constexpr double kH = 1000;                               // N
  constexpr double kPcr = kPi * kPi * kEI / (4 * kL * kL);  // 629 kN
  const double linear = kH * kL * kL * kL / (3 * kEI);
  for (const double ratio : {0.25, 0.5}) {
    const double P = ratio * kPcr;
    const auto rt = load(column("\"all\"", "[\"uy\"]", P, kH, "p_delta", 20));
    ASSERT_NE(rt, nullptr);
    const std::size_t top = ntn::kDofsPerNode * 1 + ntn::kUx;  // node 2 is the second node
    const double d = rt->model().u0[top];
    const double k = std::sqrt(P / kEI);
    const double exact = kH / (P * k) * (std::tan(k * kL) - k * kL);
    const double approx = linear / (1 - ratio);
    std::printf(
        "  P / P_cr = %.2f: tip %.6e m, exact %.6e (%+.3f %%), 1/(1-P/Pcr) x linear %.6e "
        "(%+.3f %%), amplification %.4f\n",
        ratio, d, exact, 100 * (d / exact - 1), approx, 100 * (d / approx - 1), d / linear);
    EXPECT_NEAR(d / exact, 1.0, 5e-3);
    EXPECT_NEAR(d / approx, 1.0, 1e-2);
    const std::vector<double> none;
    const std::vector<double> x = run(*rt, none, 2000, 1);
    double moved = 0;
    for (double v : x)
      moved = std::max(moved, std::abs(v - d));
    EXPECT_LE(moved, 1e-9 * d);
  }
  // The same cantilever with geometry "linear": the linear deflection.
  const auto lin = load(column("\"all\"", "[\"uy\"]", 0.5 * kPcr, kH, "linear", 20));
  ASSERT_NE(lin, nullptr);
  EXPECT_NEAR(lin->model().u0[ntn::kDofsPerNode + ntn::kUx] / linear, 1.0, 1e-3);
}

// 3. A portal of h = 4 m, L = 6 m (IPE 200 columns and beam), perfectly plastic moment hinges at
// the column bases and beam ends (M_p = 78.3 kN m, 100 x the column's 4 E I / h elastic), gravity
// P = 150 kN on each joint (preloaded), and a lateral force H on the left joint growing at
// 2 kN/s. The sway mechanism forms when the fourth hinge reaches M_p: then, by the columns'
// moment equilibrium in the deformed shape, H h = 4 M_p - (sum P) Delta with Delta the joints'
// drift (the columns' axial forces sum to 2 P whatever the overturning). Tolerance 1 %: the force
// grows slowly, and P is small enough that the frame keeps a positive stiffness once its bases
// have yielded (at 400 kN per joint it does not: the last hinges then form in a dynamic sway, 5 %
// above the static value), so inertia stays below 1e-3 of 4 M_p; the hinges are 1 % flexible.
// The leaning-column variant carries half of the left joint's load on a leaning column tied to
// the joint by a link (both Geometry::kLeaning): the same equation with its P in the sum.
struct Mechanism {
  double H = 0, drift = 0, t = 0;
};

constexpr double kMp = 78313.0, kH = 4.0, kP = 150e3;

std::string portal(const std::string& geometry, bool leaning) {
  const std::string hinge = "{ plastic = 4.08e8, yield = " + num(kMp) + ", hardening = 0.0 }";
  std::string t = R"(
[model]
name = "portal"
plane = "xz"
)";
  if (!geometry.empty()) t += "geometry = \"" + geometry + "\"\n";
  t += R"(
[model.damping]
ratio = 0.02
modes = [1, 2]
)";
  t += materials();
  t += R"(
[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [0.0, 0.0, 4.0]

[[nodes]]
id = 3
xyz = [6.0, 0.0, 4.0]

[[nodes]]
id = 4
xyz = [6.0, 0.0, 0.0]

[[members]]
id = "C1"
nodes = [1, 2]
material = "S355"
section = "IPE200"
divisions = 4

[[members]]
id = "C2"
nodes = [4, 3]
material = "S355"
section = "IPE200"
divisions = 4

[[members]]
id = "B"
nodes = [2, 3]
material = "S355"
section = "IPE200"
divisions = 4
geometry = "linear"
release_start = { ry = )" +
       hinge +
       R"( }
release_end = { ry = )" +
       hinge +
       R"( }

[[hinges]]
id = "base_left"
nodes = [1, "ground"]
ry = )" +
       hinge +
       R"(

[[hinges]]
id = "base_right"
nodes = [4, "ground"]
ry = )" +
       hinge +
       R"(

[[point_masses]]
node = 2
mass = 10000.0

[[point_masses]]
node = 3
mass = 10000.0

[[time_functions]]
id = "push"
points = [[0.0, 0.0], [100.0, 1.0]]

[[loads]]
node = 2
dof = "ux"
value = 200e3
function = "push"

[[loads]]
node = 2
dof = "uz"
value = )" +
       num(leaning ? -kP / 2 : -kP) +
       R"(

[[loads]]
node = 3
dof = "uz"
value = )" +
       num(-kP) +
       R"(

[[outputs]]
name = "joint_ux"
kind = "displacement"
node = 2
dof = "ux"
)";
  for (const char* h : {"base_left", "base_right", "B.start", "B.end"}) {
    t += "\n[[outputs]]\nname = \"" + std::string(h) + "\"\nkind = \"hinge_force\"\nhinge = \"" +
         h + "\"\ndirection = \"ry\"\n";
  }
  if (leaning) {
    t += R"(
[[nodes]]
id = 5
xyz = [-2.0, 0.0, 0.0]

[[nodes]]
id = 6
xyz = [-2.0, 0.0, 4.0]

[[leaning_columns]]
id = "L"
nodes = [5, 6]
material = "S355"
A = 0.01

[[leaning_columns]]
id = "link"
nodes = [6, 2]
material = "S355"
A = 0.01

[[supports]]
node = 5
fix = "pinned"

[[point_masses]]
node = 6
mass = 100.0

[[loads]]
node = 6
dof = "uz"
value = )" +
         num(-kP / 2) + "\n";
  }
  t += "\n[initial]\ngravity = \"static\"\n";
  return t;
}

// The push until all four hinges are at M_p (to 1e-6): the force and drift then.
Mechanism push(Rt& rt) {
  ntn::Model<ntn::kRunTime>& m = rt.model();
  ntn::State<ntn::kRunTime>& s = rt.state();
  ntn::Scratch<ntn::kRunTime>& w = rt.scratch();
  ntn::initial_state(m, s);
  std::vector<double> none;
  EXPECT_EQ(ntn::start(m, s, w, std::span<const double>(none)), ntn::StepStatus::kOk);
  const long steps = std::lround(60.0 / m.dt);
  for (long n = 0; n < steps; ++n) {
    EXPECT_EQ(ntn::step(m, s, w, std::span<const double>(none)), ntn::StepStatus::kOk);
    bool all = true;
    for (std::size_t c = 1; c <= 4; ++c)
      all = all && std::abs(w.outputs[c]) >= kMp * (1 - 1e-6);
    if (all) return {200e3 * w.time / 100.0, w.outputs[0], w.time};
  }
  ADD_FAILURE() << "no mechanism within 60 s";
  return {};
}

TEST(PDelta, PortalMechanismLoadIsReducedByPDelta) {
  const double linear_load = 4 * kMp / kH;  // 78.3 kN
  for (const bool leaning : {false, true}) {
    const auto pd = load(portal("p_delta", leaning));
    ASSERT_NE(pd, nullptr);
    const Mechanism mp = push(*pd);
    const double expected = (4 * kMp - 2 * kP * mp.drift) / kH;
    std::printf(
        "  p_delta%s: mechanism at t = %.2f s, drift %.4f m, H = %.3f kN, "
        "(4 M_p - P Delta) / h = %.3f kN (%+.3f %%), 4 M_p / h = %.3f kN\n",
        leaning ? " with a leaning column" : "", mp.t, mp.drift, mp.H / 1e3, expected / 1e3,
        100 * (mp.H / expected - 1), linear_load / 1e3);
    EXPECT_NEAR(mp.H / expected, 1.0, 1e-2);
    EXPECT_LT(mp.H, 0.95 * linear_load);  // the reduction is more than the tolerance
  }
  const auto lin = load(portal("linear", false));
  ASSERT_NE(lin, nullptr);
  const Mechanism ml = push(*lin);
  std::printf(
      "  linear: mechanism at t = %.2f s, drift %.4f m, H = %.3f kN (%+.3f %% of 4 M_p / "
      "h)\n",
      ml.t, ml.drift, ml.H / 1e3, 100 * (ml.H / linear_load - 1));
  EXPECT_NEAR(ml.H / linear_load, 1.0, 1e-2);
}

// The energy books of the P-Delta portal with its leaning column, pushed through its mechanism
// (to 36 s): the work of the loads is the kinetic, elastic (the second-order strain energy with
// it), viscous and hysteretic energy, to 1e-10 of the input. With damping alpha M alone the
// elastic account is the elements' work; with Rayleigh damping (beta K_el) it is the staggered
// strain energy plus the second-order part at u_{n+1} (energy.hpp), the viscous account taking the
// rest of the elements' work (beta K's, and the O(dt^2) between the second-order part's change and
// its work).
TEST(PDelta, EnergyBooksCloseThroughTheMechanism) {
  std::string alpha = portal("p_delta", true);
  const std::string rayleigh = "[model.damping]\nratio = 0.02\nmodes = [1, 2]\n";
  const std::size_t at = alpha.find(rayleigh);
  ASSERT_NE(at, std::string::npos);
  alpha.replace(at, rayleigh.size(), "[model.damping]\nalpha = 0.3\n");
  const auto a = load(alpha);
  const auto r = load(portal("p_delta", true));
  ASSERT_NE(a, nullptr);
  ASSERT_NE(r, nullptr);
  EXPECT_LE(std::abs(ntn_test::books_residual(*a, 36.0)), 1e-10);
  EXPECT_LE(std::abs(ntn_test::books_residual(*r, 36.0)), 1e-10);
}

// 4. A bar of 1 m fixed at one end, pulled at the other: its stable-step bound at the step the
// model takes, Q_max = (r - 1) omega_e^2 rho A l^2 / 4 (r = dt_stable / dt >= 1 / 0.9 with
// dt = "auto"), is of the order of 0.1 E A or more. A pull of half of it is inside, one of 1.5
// times it past it: counted at every force evaluation (start and each step) and flagged, the run
// going on.
std::string bar(double pull) {
  std::string t = R"(
[model]
name = "bar"
geometry = "p_delta"
)";
  t += materials();
  t += R"(
[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [1.0, 0.0, 0.0]

[[members]]
id = "T"
nodes = [1, 2]
material = "S355"
section = "IPE200"

[[supports]]
node = 1
fix = "all"

[[supports]]
node = 2
fix = ["uy", "uz", "rx", "ry", "rz"]

[[loads]]
node = 2
dof = "ux"
value = )" +
       num(pull) +
       R"(

[[outputs]]
name = "ux"
kind = "displacement"
node = 2
dof = "ux"

[initial]
gravity = "static"
)";
  return t;
}

TEST(PDelta, TensionPastTheStableStepsBoundIsCountedAndFlagged) {
  const double EA = kE * kA;
  const auto probe = load(bar(0.0));
  ASSERT_NE(probe, nullptr);
  const double limit = probe->model().geometric[0].limit;
  std::printf("  Q_max = %.3f E A at dt = %.3e s (dt_stable %.3e s)\n", limit / EA,
              probe->model().dt, probe->model().stable.dt_stable);
  EXPECT_GT(limit, 0.05 * EA);
  for (const double share : {0.5, 1.5}) {
    const auto rt = load(bar(share * limit));
    ASSERT_NE(rt, nullptr);
    EXPECT_EQ(rt->model().geometric[0].limit, limit);
    run(*rt, {}, 100, 0);
    const bool over = share > 1;
    EXPECT_EQ(rt->state().geometry_bound, over ? 101U : 0U);  // start() and 100 steps
    EXPECT_EQ((rt->state().faults & ntn::kFaultGeometryBound) != 0, over);
  }
}

// 5. geometry = "linear" in the file is the file without it: the same compiled model.
TEST(PDelta, LinearGeometryIsTheModelWithoutTheKey) {
  const auto a = load(column(kPinned, kRoller, 1e5, 100.0, "", 8));
  const auto b = load(column(kPinned, kRoller, 1e5, 100.0, "linear", 8));
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(a->model().sizes.geometric, 0U);
  const std::vector<double> xa = run(*a, {}, 500, 1), xb = run(*b, {}, 500, 1);
  ASSERT_EQ(xa.size(), xb.size());
  for (std::size_t n = 0; n < xa.size(); ++n)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(xa[n]), std::bit_cast<std::uint64_t>(xb[n]));
}

}  // namespace p_delta_test
