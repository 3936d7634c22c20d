// A block on a hinge to the ground, as a model file loaded as ntn-run loads it: the small models
// of constraint_channels_test and energy_books_test. 1000 kg at node 1 on the ground hinge "base"
// (its z axis down, so N < 0 presses), tethered to a clamped node by a member of 1e-10 N/m (its
// force is below the rounding of every check), dt = 1e-4 s.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "ntn/hil/energy.hpp"
#include "ntn/hil/loaded_model.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/diagnostic.hpp"
#include "ntn/modelc/load_model.hpp"
#include "text_model.hpp"

namespace ntn_test::block {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;
constexpr double kMass = 1000.0;
constexpr double kDt = 1e-4;

// Channels, in the order block_model() gives them.
enum Channel {
  kUx,
  kAx,
  kAbsAx,
  kVx,
  kHingeVx,
  kFx,
  kUz,
  kAz,
  kAbsAz,
  kVz,
  kFz,
  kRz,
  kHingeDx,
  kSlip
};

struct Block {
  std::string method = "ntn_exact";
  std::string ux = "\"rigid\"";  // the base's ux behaviour
  std::string uz = "\"rigid\"";  // its uz (the normal)
  std::string extra;             // more tables (curves)
  std::string initial;           // an [[initial.nodes]] table
  bool ground_motion = true;     // the input ag_x
  bool slip_state = false;       // a hinge_slip_state channel on ux
};

inline std::string block_model(const Block& b) {
  std::string t = R"([model]
name = "block"
gravity = [0.0, 0.0, -9.81]
dt = 1e-4
frame_rate = 1000.0
limit_stiffness = 1e12
hinge_method = ")" +
                  b.method + R"("

[[materials]]
id = "soft"
E = 1e-6
nu = 0.3
rho = 1e-9

[[sections]]
id = "thin"
A = 1e-4
Iy = 1e-8
Iz = 1e-8
J = 1e-8

[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [1.0, 0.0, 0.0]

[[members]]
id = "tether"
nodes = [1, 2]
material = "soft"
section = "thin"

[[supports]]
node = 2
fix = "all"

[[hinges]]
id = "base"
nodes = [1, "ground"]
axes = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]
ux = )" + b.ux +
                  "\nuz = " + b.uz + R"(

[[point_masses]]
node = 1
mass = 1000.0
)" + b.extra + b.initial;
  if (b.ground_motion)
    t += "\n[[inputs]]\nname = \"ag_x\"\nkind = \"ground_acceleration\"\ndirection = \"x\"\n";
  const auto node = [&](const char* name, const char* kind, const char* dof) {
    t += std::string("\n[[outputs]]\nname = \"") + name + "\"\nkind = \"" + kind +
         "\"\nnode = 1\ndof = \"" + dof + "\"\n";
  };
  const auto hinge = [&](const char* name, const char* kind, const char* direction) {
    t += std::string("\n[[outputs]]\nname = \"") + name + "\"\nkind = \"" + kind +
         "\"\nhinge = \"base\"\ndirection = \"" + direction + "\"\n";
  };
  node("ux", "displacement", "ux");
  node("ax", "acceleration", "ux");
  node("abs_ax", "absolute_acceleration", "ux");
  node("vx", "velocity", "ux");
  hinge("hinge_vx", "hinge_velocity", "ux");
  hinge("fx", "hinge_force", "ux");
  node("uz", "displacement", "uz");
  node("az", "acceleration", "uz");
  node("abs_az", "absolute_acceleration", "uz");
  node("vz", "velocity", "uz");
  hinge("fz", "hinge_force", "uz");
  t += "\n[[outputs]]\nname = \"rz\"\nkind = \"reaction\"\ndirection = \"z\"\n";
  hinge("hinge_dx", "hinge_displacement", "ux");
  if (b.slip_state) hinge("slip", "hinge_slip_state", "ux");
  return t;
}

// The model loaded as ntn-run loads it, init()ed and started with a_g(0) = ag0.
inline std::unique_ptr<ntn::hil::LoadedModel> load(const Block& b, double ag0 = 0.0) {
  auto rt = load_text_model(block_model(b), "block.toml");
  if (rt == nullptr) return nullptr;
  ntn::initial_state(rt->model(), rt->state());
  std::vector<double> in(rt->model().sizes.inputs, 0.0);
  if (!in.empty()) in[0] = ag0;
  EXPECT_EQ(ntn::start(rt->model(), rt->state(), rt->scratch(), in), ntn::StepStatus::kOk);
  return rt;
}

using Books = ntn::hil::EnergyBalance<ntn::kRunTime>;

// One run: every step's channels (at t_n), a_g(t) as the input; the energy books in `books` (begun
// here) where given.
template <class Ground>
inline std::vector<std::vector<double>> run(ntn::hil::LoadedModel& rt, long steps, Ground&& ag,
                                            Books* books = nullptr) {
  std::vector<std::vector<double>> rows;
  std::vector<double> in(rt.model().sizes.inputs, 0.0);
  if (books != nullptr) {
    books->reserve(rt.model().dofs());
    books->begin(rt.model(), rt.state());
  }
  for (long n = 0; n < steps; ++n) {
    if (!in.empty()) in[0] = ag(static_cast<double>(n) * kDt);
    EXPECT_EQ(ntn::step(rt.model(), rt.state(), rt.scratch(), in), ntn::StepStatus::kOk);
    if (books != nullptr) books->after_step(rt.model(), rt.state(), rt.scratch());
    rows.emplace_back(rt.scratch().outputs.begin(), rt.scratch().outputs.end());
  }
  return rows;
}

// The ground motion of most cases: 4 m/s^2 at 1 Hz, past mu g = 1.962 m/s^2 for mu = 0.2.
inline double sine(double t) {
  return 4.0 * std::sin(2 * kPi * t);
}

}  // namespace ntn_test::block
