// Hinges that turn with their nodes (a hinge between two nodes of corotational members:
// ntn/hinge.hpp's hinge_turned), against closed forms and equivalent models:
// 1. a free bar of two members joined by a rotational spring, bent by equal and opposite end
//    moments: the spring's rotation is M / k and the bar's end rotation M L / E I + M / k at any
//    size (pure bending; Euler's elastica of a constant moment is a circle), and the whole
//    answer is the same turned by R when the bar starts turned by R (a rigid rotation of 60
//    degrees about a skew axis): the hinge's axes turn with it, where a hinge whose axes stay
//    put sends the bending into its stiff directions;
// 2. Mattiasson's cantilever (P L^2 / E I = 5, tip rotation 1.2 rad) cut at mid-span by a hinge
//    whose six directions are coupled (ntn_exact): the same tip as the uncut cantilever;
// 3. the energy books close through the turned bending of 1;
// 4. what a turning hinge may not hold yet is an error at its key with the reason
//    (turning_hinge_check), and a release whose rotations are all free or all sprung loads.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "books_run.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"
#include "text_model.hpp"

namespace turning_hinge_test {

using Rt = ntn::hil::LoadedModel;
using V3 = std::array<double, 3>;

using ntn_test::num;

std::string vec(const V3& v) {
  return "[" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) + "]";
}

// ntn_test::kSlenderBar: E I = 2.1e5 N m^2 about both axes, E A = 2.1e9 N (a pure moment
// stretches nothing).
constexpr double kEI = 210e9 * 1e-6;
constexpr double kL = 4.0;  // the bar, two members of L / 2
const char* const kMaterial = ntn_test::kSlenderBar;

// Rodrigues' rotation of v about the unit axis a by the angle t (test side: libm is fine here).
V3 rotate(const V3& a, double t, const V3& v) {
  const double c = std::cos(t), s = std::sin(t), d = a[0] * v[0] + a[1] * v[1] + a[2] * v[2];
  const V3 x{a[1] * v[2] - a[2] * v[1], a[2] * v[0] - a[0] * v[2], a[0] * v[1] - a[1] * v[0]};
  V3 r;
  for (std::size_t k = 0; k < 3; ++k)
    r[k] = v[k] * c + x[k] * s + a[k] * d * (1 - c);
  return r;
}

// 1. The free bar along x: nodes 1..5 at x = 0 .. L/2 (member A, four elements of one member each
// so that every node has an [initial] entry), nodes 6..10 at x = L/2 .. L (member B), the hinge
// [6, 5] coupled in its translations, springs in its rotations: k about y (the bending one), 1e3 k
// about x and z. Moments -M and +M about y at nodes 1 and 10, ramped over 1 s and held; alpha
// damps everything to rest. `turn` (angle t about the unit axis a) starts the whole bar turned: u0
// = R X - X, rotations t a, the moments R (0, M, 0). `turning` false: the hinge's axes stay put (a
// linear-geometry bar is not used: the elements turn in both runs).
constexpr double kSpring = 2.0 * kEI;   // N m/rad
constexpr double kMoment = 0.25 * kEI;  // N m: M L / E I = 1 rad, M / k = 0.125 rad

std::string free_bar(const V3& a, double t, const std::string& method = "ntn_exact") {
  std::string s = R"(
[model]
name = "turned_bar"
geometry = "corotational"
hinge_method = ")" +
                  method + R"("
damping_velocity = "lagged"

[model.damping]
alpha = 6.0
)";
  s += kMaterial;
  std::string initial = "\n[initial]\n";
  for (int n = 1; n <= 10; ++n) {
    const double x = (n <= 5 ? n - 1 : n - 2) * kL / 8;
    const V3 X{x, 0, 0};
    s += "\n[[nodes]]\nid = " + std::to_string(n) + "\nxyz = " + vec(X) + "\n";
    const V3 RX = rotate(a, t, X);
    const V3 theta{t * a[0], t * a[1], t * a[2]};
    initial += "\n[[initial.nodes]]\nnode = " + std::to_string(n) + "\nu = [" + num(RX[0] - X[0]) +
               ", " + num(RX[1] - X[1]) + ", " + num(RX[2] - X[2]) + ", " + num(theta[0]) + ", " +
               num(theta[1]) + ", " + num(theta[2]) + "]\n";
  }
  for (int e = 0; e < 8; ++e) {
    const int i = e < 4 ? e + 1 : e + 2;
    s += "\n[[members]]\nid = \"E" + std::to_string(e) + "\"\nnodes = [" + std::to_string(i) +
         ", " + std::to_string(i + 1) + "]\nmaterial = \"steel\"\nsection = \"bar\"\n";
  }
  s += R"(
[[hinges]]
id = "spring"
nodes = [6, 5]
rx = { linear = )" +
       num(1e3 * kSpring) + " }\nry = { linear = " + num(kSpring) +
       " }\nrz = { linear = " + num(1e3 * kSpring) + R"( }

[[time_functions]]
id = "ramp"
points = [[0.0, 0.0], [1.0, 1.0], [100.0, 1.0]]
)";
  const V3 m = rotate(a, t, V3{0, kMoment, 0});
  const char* const dofs[3] = {"rx", "ry", "rz"};
  for (int end = 0; end < 2; ++end) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (m[k] == 0) continue;
      s += "\n[[loads]]\nnode = " + std::string(end == 0 ? "1" : "10") + "\ndof = \"" + dofs[k] +
           "\"\nvalue = " + num(end == 0 ? -m[k] : m[k]) + "\nfunction = \"ramp\"\n";
    }
  }
  for (const char* d : {"rx", "ry", "rz"}) {
    s += std::string("\n[[outputs]]\nname = \"hinge_") + d +
         "\"\nkind = \"hinge_displacement\"\nhinge = \"spring\"\ndirection = \"" + d + "\"\n";
  }
  for (const char* d : {"ux", "uy", "uz"}) {
    for (const int n : {1, 10}) {
      s += "\n[[outputs]]\nname = \"n" + std::to_string(n) + "_" + d +
           "\"\nkind = \"displacement\"\nnode = " + std::to_string(n) + "\ndof = \"" + d + "\"\n";
    }
  }
  for (const int n : {1, 10}) {
    s += "\n[[outputs]]\nname = \"n" + std::to_string(n) +
         "_ry\"\nkind = \"displacement\"\nnode = " + std::to_string(n) + "\ndof = \"ry\"\n";
  }
  return s + initial;
}

// The channels of free_bar: hinge rx, ry, rz, then ux of nodes 1 and 10, uy, uz, then their ry
// (the spins' sum: the rotation itself while it is about y alone).
struct BarEnd {
  V3 hinge{};
  V3 chord{};               // node 10's position less node 1's
  double end_rotation = 0;  // node 10's ry less node 1's
};

BarEnd settle(Rt& rt, double seconds) {
  ntn::Model<ntn::kRunTime>& m = rt.model();
  ntn::State<ntn::kRunTime>& s = rt.state();
  ntn::Scratch<ntn::kRunTime>& w = rt.scratch();
  ntn::initial_state(m, s);
  const std::vector<double> none;
  EXPECT_EQ(ntn::start(m, s, w, std::span<const double>(none)), ntn::StepStatus::kOk);
  const long steps = std::lround(seconds / m.dt);
  for (long n = 0; n < steps; ++n)
    EXPECT_EQ(ntn::step(m, s, w, std::span<const double>(none)), ntn::StepStatus::kOk);
  BarEnd b;
  for (std::size_t k = 0; k < 3; ++k) {
    b.hinge[k] = w.outputs[k];
    b.chord[k] = w.outputs[3 + 2 * k + 1] - w.outputs[3 + 2 * k];
  }
  b.chord[0] += kL;
  b.end_rotation = w.outputs[10] - w.outputs[9];
  EXPECT_EQ(s.geometry_bound, 0U);
  return b;
}

// Closed form of the bar at rest: curvature M / E I along both members, a kink M / k at the hinge.
// Each element's chord keeps its length (no axial force) and its end rotations are kappa l / 2, so
// the bar is the polygon of chords of length l at angles -Theta/2 + (j + 1/2) kappa l (+ M / k past
// the hinge), Theta = kappa L + M / k the end rotations' difference: the loads are symmetric about
// the bar's mid-plane, so is its shape (the chord between its ends stays along x).
V3 polygon_chord() {
  const double l = kL / 8, kappa = kMoment / kEI, kink = kMoment / kSpring;
  const double theta = kappa * kL + kink;
  V3 c{0, 0, 0};
  for (int j = 0; j < 8; ++j) {
    const double phi = -0.5 * theta + (j + 0.5) * kappa * l + (j >= 4 ? kink : 0.0);
    c[0] += l * std::cos(phi), c[2] -= l * std::sin(phi);
  }
  return c;
}

// Tolerance 1e-7 (rad, and m on the 4 m bar): the motion left after 12 s of alpha = 6 / s (the
// slowest mode, the bar's free bending, decays as exp(-alpha t / 2) from ~1e-1: ~1e-9), far above
// the rounding of either run.
TEST(TurningHinge, APureMomentBendsTheSpringByMOverKTurnedOrNot) {
  const V3 skew{1 / std::sqrt(3.0), 1 / std::sqrt(3.0), 1 / std::sqrt(3.0)};
  const double t = 60.0 * std::acos(-1.0) / 180.0;
  const auto plain = ntn_test::load_text_model(free_bar(skew, 0.0), "bar.toml");
  const auto turned = ntn_test::load_text_model(free_bar(skew, t), "bar.toml");
  ASSERT_NE(plain, nullptr);
  ASSERT_NE(turned, nullptr);
  const BarEnd p = settle(*plain, 12.0);
  const BarEnd q = settle(*turned, 12.0);
  const V3 want = polygon_chord();
  std::printf("  hinge ry %.9f rad (-M/k %.9f), turned %.9f; rx, rz %.1e, %.1e turned %.1e %.1e\n",
              p.hinge[1], -kMoment / kSpring, q.hinge[1], p.hinge[0], p.hinge[2], q.hinge[0],
              q.hinge[2]);
  // The hinge is [6, 5]: its rotation is node 5's (the left half's) relative to node 6's, -M / k.
  EXPECT_NEAR(p.hinge[1], -kMoment / kSpring, 1e-7);
  EXPECT_NEAR(q.hinge[1], -kMoment / kSpring, 1e-7);
  for (const std::size_t k : {std::size_t{0}, std::size_t{2}}) {
    EXPECT_NEAR(p.hinge[k], 0.0, 1e-7);
    EXPECT_NEAR(q.hinge[k], 0.0, 1e-7);
  }
  const V3 want_turned = rotate(skew, t, want);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(p.chord[k], want[k], 1e-7) << k;
    EXPECT_NEAR(q.chord[k], want_turned[k], 1e-7) << k;
  }
  // The continuous elastica (arcs of curvature kappa = M / E I and the kink k = M / k_s): its
  // chord 2 (sin(Theta/2) - sin(k/2)) / kappa; the chords' polygon is within (kappa l)^2 / 24 of
  // it, 6.5e-4 relative here (kappa l = 0.125 rad).
  const double kappa = kMoment / kEI, kink = kMoment / kSpring, theta = kappa * kL + kink;
  const double arc_x = 2 * (std::sin(0.5 * theta) - std::sin(0.5 * kink)) / kappa;
  EXPECT_NEAR(p.chord[0] / arc_x, 1.0, 1e-3);
  // Theta itself, from the ends' rotations, is exact at any size: M L / E I + M / k.
  EXPECT_NEAR(p.end_rotation, theta, 1e-7);
}

// 2. Mattiasson's cantilever at P L^2 / E I = 5 as one member, and cut at mid-span: members
// 1-2 and 3-4 with node 3 on node 2 and a hinge [3, 2] with all six directions coupled.
std::string cantilever(bool cut) {
  std::string s = R"(
[model]
name = "mattiasson_cut"
plane = "xz"
geometry = "corotational"

[model.damping]
alpha = 20.0
)";
  s += kMaterial;
  s += R"(
[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [2.0, 0.0, 0.0]

[[nodes]]
id = 4
xyz = [4.0, 0.0, 0.0]

[[supports]]
node = 1
fix = "all"

[[time_functions]]
id = "ramp"
points = [[0.0, 0.0], [1.0, 1.0], [10.0, 1.0]]

[[loads]]
node = 4
dof = "uz"
value = )" +
       num(-5 * kEI / (kL * kL)) +
       R"(
function = "ramp"

[[outputs]]
name = "tip_ux"
kind = "displacement"
node = 4
dof = "ux"

[[outputs]]
name = "tip_uz"
kind = "displacement"
node = 4
dof = "uz"

[[outputs]]
name = "tip_ry"
kind = "displacement"
node = 4
dof = "ry"

[[members]]
id = "A"
nodes = [1, 2]
material = "steel"
section = "bar"
divisions = 10
)";
  if (!cut) {
    return s + R"(
[[members]]
id = "B"
nodes = [2, 4]
material = "steel"
section = "bar"
divisions = 10
)";
  }
  return s + R"(
[[nodes]]
id = 3
xyz = [2.0, 0.0, 0.0]

[[members]]
id = "B"
nodes = [3, 4]
material = "steel"
section = "bar"
divisions = 10

[[hinges]]
id = "splice"
nodes = [3, 2]
)";
}

// Tolerance 1e-9 of L: the two runs differ by the forest's rounding alone (the coupled pair is
// the merged node exactly), which the damped, slowly loaded bar does not amplify; and both are
// Mattiasson's (-u/L 0.38763, -w/L 0.71379, theta 1.21537) to 0.5 % (corotational_step_test.cpp).
TEST(TurningHinge, ACoupledSpliceIsTheUncutCantilever) {
  const auto whole = ntn_test::load_text_model(cantilever(false), "c.toml");
  const auto cut = ntn_test::load_text_model(cantilever(true), "c.toml");
  ASSERT_NE(whole, nullptr);
  ASSERT_NE(cut, nullptr);
  std::array<std::vector<double>, 2> end;
  for (int r = 0; r < 2; ++r) {
    Rt& rt = r == 0 ? *whole : *cut;
    ntn::initial_state(rt.model(), rt.state());
    const std::vector<double> none;
    ASSERT_EQ(ntn::start(rt.model(), rt.state(), rt.scratch(), std::span<const double>(none)),
              ntn::StepStatus::kOk);
    const long steps = std::lround(4.0 / rt.model().dt);
    for (long n = 0; n < steps; ++n)
      ASSERT_EQ(ntn::step(rt.model(), rt.state(), rt.scratch(), std::span<const double>(none)),
                ntn::StepStatus::kOk);
    end[static_cast<std::size_t>(r)].assign(rt.scratch().outputs.begin(),
                                            rt.scratch().outputs.end());
  }
  std::printf("  uncut tip (%.9f, %.9f, %.9f), cut (%.9f, %.9f, %.9f)\n", end[0][0], end[0][1],
              end[0][2], end[1][0], end[1][1], end[1][2]);
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(end[1][k], end[0][k], 1e-9 * kL) << k;
  EXPECT_NEAR(-end[1][0] / kL / 0.38763, 1.0, 5e-3);
  EXPECT_NEAR(-end[1][1] / kL / 0.71379, 1.0, 5e-3);
  EXPECT_NEAR(end[1][2] / 1.21537, 1.0, 5e-3);
}

// 3. The energy books of the turned bar of 1 (loaded over 1 s, held to 4 s): the moments' work is
// the kinetic, elastic (elements and the hinge's springs) and viscous energy to 1e-10 of it.
TEST(TurningHinge, EnergyBooksCloseThroughTheTurnedBending) {
  const V3 skew{1 / std::sqrt(3.0), 1 / std::sqrt(3.0), 1 / std::sqrt(3.0)};
  const auto turned =
      ntn_test::load_text_model(free_bar(skew, 60.0 * std::acos(-1.0) / 180.0), "bar.toml");
  ASSERT_NE(turned, nullptr);
  EXPECT_LE(std::abs(ntn_test::books_residual(*turned, 4.0)), 1e-10);
}

// 4. The rule (turning_hinge_check) at the key, with its reason.
std::string errors_of(const std::string& text) {
  const ntn::modelc::LoadResult r = ntn::modelc::load_model_from_string(text, "c.toml");
  return r.ok() ? std::string() : ntn::modelc::format_all(r.errors);
}

TEST(TurningHinge, WhatCannotTurnYetIsAnErrorAtItsKey) {
  const std::string bar = free_bar({0, 0, 1}, 0.0);
  const std::string rz_spring = "rz = { linear = " + num(1e3 * kSpring) + " }";
  ASSERT_NE(bar.find(rz_spring), std::string::npos);
  std::string part = bar;  // rz coupled, rx and ry sprung: part of the rotation block
  part.replace(part.find(rz_spring), rz_spring.size(), "rz = \"rigid\"");
  std::string e = errors_of(part);
  EXPECT_NE(e.find("c.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("hinge 'spring'"), std::string::npos) << e;
  EXPECT_NE(e.find("part of a block (rx is not coupled)"), std::string::npos) << e;
  // The same hinge under penalty (its rigid direction a spring) loads.
  std::string penalty = free_bar({0, 0, 1}, 0.0, "penalty");
  penalty.replace(penalty.find(rz_spring), rz_spring.size(), "rz = \"rigid\"");
  EXPECT_EQ(errors_of(penalty), "");
  // A dashpot under damping_velocity = "central".
  std::string central = bar;
  central.replace(central.find("damping_velocity = \"lagged\""), 27,
                  "damping_velocity = \"central\"");
  central.replace(central.find(rz_spring), rz_spring.size(),
                  rz_spring.substr(0, rz_spring.size() - 2) + ", dashpot = 10.0 }");
  e = errors_of(central);
  EXPECT_NE(e.find("rz's dashpot"), std::string::npos) << e;
  EXPECT_NE(e.find("damping_velocity = \"lagged\""), std::string::npos) << e;
  // ntn_paper's coupled translations.
  e = errors_of(free_bar({0, 0, 1}, 0.0, "ntn_paper"));
  EXPECT_NE(e.find("ntn_paper"), std::string::npos) << e;
  // A member-end release of all three rotations (a ball joint) loads.
  std::string ball = bar;
  ball += R"(
[[nodes]]
id = 11
xyz = [0.0, 1.0, 0.0]

[[members]]
id = "arm"
nodes = [1, 11]
material = "steel"
section = "bar"
release_start = ["rx", "ry", "rz"]
)";
  EXPECT_EQ(errors_of(ball), "");
}

}  // namespace turning_hinge_test
