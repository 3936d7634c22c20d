// A structure need not have members: point masses on hinge springs are a model (config/sdof.toml,
// the single-degree-of-freedom oscillator: m = 1000 kg on k = 400 kN/m with a dashpot c = 2 kN s/m
// to the ground along x, the other directions rigid). The compiler accepts it and takes the
// stable step from the springs alone, which for one spring to the ground is the oscillator's own
// bound of central difference with the damping lagged to n - 1/2 (kernel/README.md, "Stable time
// step"):
//   dt_stable = (2 / omega) (sqrt(1 + xi^2) - xi),  omega = sqrt(k / m),  xi = (alpha + c / m) / (2
//   omega),
// 2 / omega undamped; alpha counts only with damping_velocity = "lagged" (central: alpha drops
// out, the dashpot keeps its lagged term). Tolerance 1e-12 relative: the kernel computes k / m
// as the eigenvalue of a 6x6 block with that one entry and the bound as
// 2 / (omega (sqrt(1 + xi^2) + xi)), a few roundings. `ntn-model info` prints the same number (to
// its 6 digits) and names the spring.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "support/temp_files.hpp"

namespace modelc_no_members_test {

using ntn::modelc::load_model_from_string;

const std::string kSdof = ntn_test::read_file(NTN_CONFIG_DIR "/sdof.toml");
constexpr double kM = 1000.0, kK = 4.0e5, kC = 2.0e3;  // config/sdof.toml
const std::string kDamped = "ux = { linear = 4.0e5, dashpot = 2.0e3 }";

// config/sdof.toml with its spring line replaced, and `tables` appended.
std::string sdof(const std::string& spring, const std::string& tables = "") {
  std::string t = kSdof;
  const std::size_t at = t.find(kDamped);
  if (at == std::string::npos) return "";
  t.replace(at, kDamped.size(), spring);
  return t + "\n" + tables + "\n";
}

double oscillator_step(double alpha, double c) {
  const double omega = std::sqrt(kK / kM);
  const double xi = (alpha + c / kM) / (2 * omega);
  return 2 / omega * (std::sqrt(1 + xi * xi) - xi);
}

// The report's line `stable dt    X s (...` as the number it prints.
double printed_stable_step(const std::string& info) {
  const std::string key = "\nstable dt";
  const std::size_t at = info.find(key);
  if (at == std::string::npos) return -1;
  return std::strtod(info.c_str() + at + key.size(), nullptr);
}

struct Case {
  const char* what;
  std::string text;
  double alpha, c;  // what the bound takes: alpha only with damping_velocity = "lagged"
};

// `text` with damping_velocity = "lagged" in its [model] table.
std::string lagged(std::string text) {
  const std::size_t at = text.find("[model]\n");
  if (at != std::string::npos) text.insert(at + 8, "damping_velocity = \"lagged\"\n");
  return text;
}

TEST(ModelcNoMembers, SdofStableStepIsTheOscillatorsOwn) {
  ASSERT_FALSE(kSdof.empty());
  const Case cases[] = {
      {"undamped", sdof("ux = { linear = 4.0e5 }"), 0.0, 0.0},
      {"the file's dashpot", kSdof, 0.0, kC},
      {"dashpot and alpha", sdof(kDamped, "[model.damping]\nalpha = 3.0"), 0.0, kC},
      {"alpha alone", sdof("ux = { linear = 4.0e5 }", "[model.damping]\nalpha = 3.0"), 0.0, 0.0},
      {"dashpot and alpha, lagged", lagged(sdof(kDamped, "[model.damping]\nalpha = 3.0")), 3.0, kC},
      {"alpha alone, lagged",
       lagged(sdof("ux = { linear = 4.0e5 }", "[model.damping]\nalpha = 3.0")), 3.0, 0.0},
  };
  for (const Case& c : cases) {
    const auto r = load_model_from_string(c.text, "sdof.toml");
    ASSERT_TRUE(r.ok()) << c.what << "\n" << ntn::modelc::format_all(r.errors);
    const ntn::modelc::ModelDescription& d = *r.model;
    EXPECT_EQ(d.elements.size(), 0U) << c.what;
    EXPECT_EQ(d.nodes.size(), 1U) << c.what;
    const double expected = oscillator_step(c.alpha, c.c);
    EXPECT_NEAR(d.stable.dt_stable / expected, 1.0, 1e-12) << c.what;
    EXPECT_EQ(d.stable.governing_hinge, 0) << c.what;
    EXPECT_EQ(d.stable.hinge_direction, 0) << c.what;
    EXPECT_EQ(d.stable.governing_element, -1) << c.what;
    const std::string info = ntn::modelc::info_text(d);
    char six[32];
    std::snprintf(six, sizeof six, "%.6g", expected);
    EXPECT_EQ(printed_stable_step(info), std::strtod(six, nullptr)) << c.what << "\n" << info;
    EXPECT_NE(info.find("set by hinge spring, direction ux"), std::string::npos) << info;
    EXPECT_NE(info.find("CFL (seed)   none (no elements)"), std::string::npos) << info;
    EXPECT_EQ(d.settings.dt, 1e-3) << c.what;  // "auto": the frame period, far below the step
    std::printf("  %s: dt_stable %.17g s, oscillator %.17g s\n", c.what, d.stable.dt_stable,
                expected);
  }
}

// Two point masses joined by a spring, nothing else along x: the free-free oscillator
// omega^2 = k (1 / m1 + 1 / m2), which the node bound gives exactly for one centric hinge.
TEST(ModelcNoMembers, TwoMassesOnASpringHaveTheTwoNodeStep) {
  const std::string text = R"([model]
name = "two"

[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[nodes]]
id = 2
xyz = [0.0, 0.0, 0.0]

[[point_masses]]
node = 1
mass = 1000.0
inertia = [1.0, 1.0, 1.0]

[[point_masses]]
node = 2
mass = 3000.0
inertia = [1.0, 1.0, 1.0]

[[supports]]
node = 1
fix = ["uy", "uz", "rx", "ry", "rz"]

[[supports]]
node = 2
fix = ["uy", "uz", "rx", "ry", "rz"]

[[hinges]]
id = "link"
nodes = [1, 2]
ux = { linear = 4.0e5 }
uy = "free"
uz = "free"
rx = "free"
ry = "free"
rz = "free"
)";
  const auto r = load_model_from_string(text, "two.toml");
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  const double omega = std::sqrt(4.0e5 * (1 / 1000.0 + 1 / 3000.0));
  EXPECT_NEAR(r.model->stable.dt_stable * omega / 2, 1.0, 1e-12);
}

// Without members and without any point mass nothing has mass (an error at 1:1, "members");
// a node without mass is named (check_nodes_have_mass); both in modelc_errors_test. A model of
// one massive free node with nothing bounding its step runs at the frame period.
TEST(ModelcNoMembers, AFreeMassHasNoStableStepBound) {
  const auto r = load_model_from_string(R"([model]
name = "free"

[[nodes]]
id = 1
xyz = [0.0, 0.0, 0.0]

[[point_masses]]
node = 1
mass = 10.0
inertia = [1.0, 1.0, 1.0]
)",
                                        "free.toml");
  ASSERT_TRUE(r.ok()) << ntn::modelc::format_all(r.errors);
  EXPECT_EQ(r.model->stable.dt_stable, 1e300);
  EXPECT_EQ(r.model->settings.dt, 1e-3);
  const std::string info = ntn::modelc::info_text(*r.model);
  EXPECT_NE(info.find("stable dt    none: nothing bounds it"), std::string::npos) << info;
}

}  // namespace modelc_no_members_test
