// `ntn-model modes`: the command's JSON parsed back and held against the
// 20-element cantilever's closed form, its effective masses against the model's total mass, the
// JSON against the library's report bit for bit, the hinge directions against the model file,
// a mechanism, rigid-body modes (null periods), a model error's position, and the strictness of
// the JSON reader used.
//
// Closed form (Euler-Bernoulli cantilever, length L, clamped at x = 0): bending mode n has
//   f_n = (beta_n L)^2 / (2 pi L^2) sqrt(E I / (rho A)),   cos(x) cosh(x) = -1:
//   beta_n L = 1.8751, 4.6941, 7.8548 (refined by Newton below),
// and the effective mass, as a fraction of the member's mass rho A L,
//   m_n / (rho A L) = 4 s_n^2 / b^2,   s_n = (sinh b - sin b) / (cosh b + cos b),   b = beta_n L
// (61.31 %, 18.83 %, 6.47 %).
//
// Tolerances, from the discretisation error of 20 cubic (Hermite) elements with the kernel's
// lumped (HRZ) mass: the discrete model's frequencies lie below the closed form by 0.129 %,
// 0.499 % and 0.892 % (tests/validation/cantilever_test.cpp derives this; a second-order error:
// 0.032 %, 0.125 %, 0.225 % at 40 elements) and its effective-mass fractions by 0.127 %, 0.022 %
// and 0.206 % (0.032 %, 0.006 %, 0.051 % at 40). The test allows 0.15 %, 0.55 %, 0.95 % on the
// frequencies (the error rounded up to the next 0.05 %, and it must be negative: lumped mass
// lowers them) and 0.25 % on the effective masses. A wrong unit (rad/s for Hz: x 6.3), a wrong
// plane (Iy for Iz: x 2) or a wrong mode order fails by far.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "json.hpp"  // tools/io
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "ntn/modelc/modes_report.hpp"
#include "support/closed_forms.hpp"
#include "support/json_value.hpp"
#include "support/temp_files.hpp"

namespace {

using ntn_test::Json;

struct Output {
  int exit = -1;
  std::string out;  // stdout
};

// Runs ntn-model with `args` (words already quoted for the shell): stdout captured, and stderr
// with it when `with_stderr` (else to /dev/null).
Output ntn_model(const std::string& args, bool with_stderr = false) {
  Output r;
  const std::string cmd =
      std::string("'") + NTN_MODEL_EXE + "' " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0)
    r.out.append(buf, n);
  const int status = ::pclose(p);
  r.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

const std::string kCantilever = NTN_CONFIG_DIR "/cantilever.toml";
const std::string kHingedBeam = NTN_CONFIG_DIR "/hinged_beam.toml";
constexpr const char* kAxis[3] = {"x", "y", "z"};
constexpr const char* kDirection[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};

Json modes_json(const std::string& args) {
  const Output r = ntn_model("modes " + args + " --json");
  EXPECT_EQ(r.exit, 0) << args;
  return Json::parse(r.out);
}

TEST(ModelModes, CantileverMatchesTheClosedForm) {
  const auto loaded = ntn::modelc::load_model(kCantilever);
  ASSERT_TRUE(loaded.ok());
  const ntn::modelc::ModelDescription& m = *loaded.model;
  ASSERT_EQ(m.elements.size(), 20U);
  const ntn::ElementSpec& e = m.elements[0];
  const double L = 2.0;  // m: the file's member, nodes 1 and 2
  const double member_mass = e.rho * e.A * L;

  const Json j = modes_json("'" + kCantilever + "' -n 12");
  EXPECT_EQ(j["schema"].string(), ntn::modelc::kModesSchema);
  EXPECT_EQ(j["model"].string(), "cantilever");
  EXPECT_EQ(j["requested_modes"].number(), 12);
  const Json& modes = j["modes"];
  ASSERT_EQ(modes.size(), 12U);
  const double free_mass = j["total_mass_kg"]["y"].number();

  const double f_tol[3] = {0.15e-2, 0.55e-2, 0.95e-2};  // the header: discretisation error
  const double m_tol = 0.25e-2;
  // Deflection uy bends about z (Iz), uz about y (Iy). A plane's bending modes are the ones with
  // effective mass along its deflection (the closed form's fractions are all above 6 %).
  for (const auto& [axis, I] : {std::pair{1, e.Iz}, std::pair{2, e.Iy}}) {
    int found = 0;
    for (std::size_t i = 0; i < modes.size() && found < 3; ++i) {
      const Json& mode = modes[i];
      EXPECT_EQ(mode["mode"].number(), static_cast<double>(i + 1));
      const double pct = mode["effective_mass_percent"][kAxis[axis]].number();
      if (pct < 1.0) continue;
      const double b = ntn_test::cantilever_beta_l(found);
      const double f = b * b / (2 * std::numbers::pi * L * L) * std::sqrt(e.E * I / (e.rho * e.A));
      const double s_n = (std::sinh(b) - std::sin(b)) / (std::cosh(b) + std::cos(b));
      const double fraction = 4 * s_n * s_n / (b * b);
      const double hz = mode["frequency_hz"].number();
      const double f_err = hz / f - 1;
      const double m_err = pct / 100 * free_mass / member_mass / fraction - 1;
      std::printf(
          "  %s bending %d (mode %zu): %.5f Hz, closed form %.5f Hz, %+.3f %%; "
          "effective mass %.3f %% of rho A L, closed form %.3f %%, %+.3f %%\n",
          kAxis[axis], found + 1, i + 1, hz, f, 100 * f_err,
          100 * pct / 100 * free_mass / member_mass, 100 * fraction, 100 * m_err);
      EXPECT_LT(f_err, 0.0) << "lumped mass lowers the frequencies";
      EXPECT_GT(f_err, -f_tol[found]) << kAxis[axis] << " bending mode " << found + 1;
      EXPECT_LT(std::abs(m_err), m_tol) << kAxis[axis] << " bending mode " << found + 1;
      // Period and circular frequency are the same number in other units (rounding only).
      EXPECT_NEAR(mode["period_s"].number() * hz, 1.0, 1e-14);
      EXPECT_NEAR(mode["omega_rad_s"].number() / (2 * std::numbers::pi * hz), 1.0, 1e-14);
      ++found;
    }
    EXPECT_EQ(found, 3) << "plane " << kAxis[axis];
  }
  // Ascending frequencies.
  for (std::size_t i = 1; i < modes.size(); ++i)
    EXPECT_LE(modes[i - 1]["frequency_hz"].number(), modes[i]["frequency_hz"].number());
}

// Every mode (-n above the 120 of the problem): the effective masses add up to the model's total
// mass free to move, which is the kernel's lumped mass of the unsupported DOFs (mass_totals, the
// figure `ntn-model info` prints) and, for this cantilever, rho A L (1 - 1/40): the support holds
// half an element's mass. Rounding only: 1e-12 relative for the totals (a sum of 21 lumped masses
// in another order), 1e-9 for the sums over 120 modes (Gamma^2 of unit-mass shapes from a
// symmetric eigensolver: orthogonality to ~1e-13 per mode).
// A model without members (config/sdof.toml: m = 1000 kg on k = 400 kN/m to the ground along x,
// the other directions rigid): one mode, f = sqrt(k / m) / (2 pi) = 3.1831 Hz with all the mass
// along x. Tolerance 1e-12 relative: a 1 x 1 eigenproblem, k / m and a square root (the hinge's
// dashpot is left out, as for every model: the modes are undamped).
TEST(ModelModes, SdofIsTheOscillator) {
  const Json j = modes_json("'" NTN_CONFIG_DIR "/sdof.toml'");
  EXPECT_EQ(j["dofs"].number(), 6);
  EXPECT_EQ(j["eigenproblem_size"].number(), 1);
  const Json& modes = j["modes"];
  ASSERT_EQ(modes.size(), 1U);
  const double omega = std::sqrt(4.0e5 / 1000.0);
  EXPECT_NEAR(modes[0]["frequency_hz"].number() / (omega / (2 * std::numbers::pi)), 1.0, 1e-12);
  EXPECT_NEAR(modes[0]["omega_rad_s"].number() / omega, 1.0, 1e-12);
  EXPECT_NEAR(modes[0]["effective_mass_kg"]["x"].number() / 1000.0, 1.0, 1e-12);
  EXPECT_EQ(modes[0]["effective_mass_kg"]["y"].number(), 0.0);
}

TEST(ModelModes, EffectiveMassesAddUpToTheTotalMass) {
  const auto loaded = ntn::modelc::load_model(kCantilever);
  ASSERT_TRUE(loaded.ok());
  const ntn::modelc::MassTotals totals = ntn::modelc::mass_totals(*loaded.model);
  const ntn::ElementSpec& e = loaded.model->elements[0];
  const double closed = e.rho * e.A * 2.0 * (1.0 - 1.0 / 40.0);

  const Json j = modes_json("'" + kCantilever + "' -n 1000");
  const Json& modes = j["modes"];
  ASSERT_EQ(modes.size(), 120U) << "6 DOFs x 20 free nodes";
  EXPECT_EQ(j["eigenproblem_size"].number(), 120);
  for (int d = 0; d < 3; ++d) {
    const double total = j["total_mass_kg"][kAxis[d]].number();
    EXPECT_NEAR(total / totals.free[static_cast<std::size_t>(d)], 1.0, 1e-12) << kAxis[d];
    EXPECT_NEAR(total / closed, 1.0, 1e-12) << kAxis[d];
    double kg = 0, pct = 0, previous = 0;
    for (std::size_t i = 0; i < modes.size(); ++i) {
      kg += modes[i]["effective_mass_kg"][kAxis[d]].number();
      pct += modes[i]["effective_mass_percent"][kAxis[d]].number();
      const double cumulative = modes[i]["cumulative_percent"][kAxis[d]].number();
      EXPECT_NEAR(cumulative, pct, 1e-9 * 100);
      EXPECT_GE(cumulative, previous) << "mode " << i + 1;  // summing toward 100 %
      previous = cumulative;
    }
    EXPECT_NEAR(kg / total, 1.0, 1e-9) << kAxis[d];
    EXPECT_NEAR(previous, 100.0, 1e-9 * 100) << kAxis[d];
    EXPECT_NEAR(j["reachable_mass_kg"][kAxis[d]].number() / total, 1.0, 1e-9) << kAxis[d];
  }
  // The 12 lowest modes hold most of the lateral mass, not all of it (the closed form: 61.3 +
  // 18.8 + 6.5 + 3.6 % ... per plane; the 12 lowest include the first four or five of each).
  const Json j12 = modes_json("'" + kCantilever + "' -n 12");
  const double y12 = j12["modes"][11]["cumulative_percent"]["y"].number();
  EXPECT_GT(y12, 90.0);
  EXPECT_LT(y12, 99.9);
}

// The command prints the library's report, and the JSON reads back as its numbers bit for bit
// (17 significant digits); every key of the documented schema is there.
TEST(ModelModes, JsonReadsBackAsTheReport) {
  const auto loaded = ntn::modelc::load_model(kHingedBeam);
  ASSERT_TRUE(loaded.ok());
  const ntn::modelc::ModesReport rep = ntn::modelc::modes_report(*loaded.model, 6);
  ASSERT_TRUE(rep.result.ok()) << rep.result.error;
  const std::string text = ntn::modelc::modes_json(rep);

  const Output cli = ntn_model("modes '" + kHingedBeam + "' -n 6 --json");
  EXPECT_EQ(cli.exit, 0);
  // The command was given the same path: its output is the library's, byte for byte.
  EXPECT_EQ(cli.out, text);

  const Json j = Json::parse(text);
  const std::vector<std::string> keys = {"schema",
                                         "model",
                                         "model_file",
                                         "requested_modes",
                                         "dofs",
                                         "coordinates",
                                         "eigenproblem_size",
                                         "rigid_trees",
                                         "mechanism_dofs",
                                         "condensed",
                                         "solver",
                                         "total_mass_kg",
                                         "reachable_mass_kg",
                                         "alpha_per_s",
                                         "beta_s",
                                         "modes",
                                         "hinges",
                                         "mechanisms",
                                         "notes"};
  EXPECT_EQ(j.keys(), keys);
  EXPECT_EQ(j["alpha_per_s"].number(), rep.alpha);
  EXPECT_EQ(j["beta_s"].number(), rep.beta);
  const ntn::modal::ModalResult& r = rep.result;
  EXPECT_EQ(j["dofs"].number(), r.dofs);
  EXPECT_EQ(j["coordinates"].number(), r.coordinates);
  EXPECT_EQ(j["rigid_trees"].number(), r.trees);
  EXPECT_EQ(j["solver"].string(), "dense");
  ASSERT_EQ(j["modes"].size(), static_cast<std::size_t>(r.modes()));
  ASSERT_EQ(r.modes(), 6);
  for (int i = 0; i < r.modes(); ++i) {
    const Json& mode = j["modes"][static_cast<std::size_t>(i)];
    EXPECT_EQ(mode.keys(),
              (std::vector<std::string>{"mode", "frequency_hz", "period_s", "omega_rad_s",
                                        "damping_ratio", "effective_mass_kg",
                                        "effective_mass_percent", "cumulative_percent"}));
    EXPECT_EQ(mode["frequency_hz"].number(), r.frequency(i));
    EXPECT_EQ(mode["period_s"].number(), r.period(i));
    EXPECT_EQ(mode["omega_rad_s"].number(), r.omega(i));
    EXPECT_EQ(mode["damping_ratio"].number(), r.damping_ratio(i));
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(mode["effective_mass_kg"][kAxis[d]].number(), r.effective_mass(i, d));
      EXPECT_EQ(mode["effective_mass_percent"][kAxis[d]].number(), 100.0 * r.mass_fraction(i, d));
    }
  }
  for (int d = 0; d < 3; ++d)
    EXPECT_EQ(j["total_mass_kg"][kAxis[d]].number(), r.total_mass[static_cast<std::size_t>(d)]);
  ASSERT_EQ(j["notes"].size(), r.notes.size());
  for (std::size_t k = 0; k < r.notes.size(); ++k)
    EXPECT_EQ(j["notes"][k].string(), r.notes[k]);
}

// Each hinge direction as the model file gives it: rigid -> tied, linear k > 0 -> spring k,
// free -> free; the gap curve of H_gap (ux) has zero slope at the origin (inside the gap): free.
TEST(ModelModes, HingeDirectionsFollowTheModel) {
  const auto loaded = ntn::modelc::load_model(kHingedBeam);
  ASSERT_TRUE(loaded.ok());
  const ntn::modelc::ModelDescription& m = *loaded.model;
  const Json j = modes_json("'" + kHingedBeam + "' -n 3");
  const Json& hinges = j["hinges"];
  ASSERT_EQ(hinges.size(), m.hinges.size());
  ASSERT_EQ(m.hinges.size(), 5U);
  int curves = 0;
  for (std::size_t h = 0; h < m.hinges.size(); ++h) {
    const Json& hj = hinges[h];
    EXPECT_EQ(hj["index"].number(), static_cast<double>(h));
    EXPECT_EQ(hj["name"].string(), m.hinge_info[h].name);
    EXPECT_EQ(hj["description"].string(), m.describe_hinge(static_cast<int>(h)));
    for (std::size_t k = 0; k < 6; ++k) {
      const Json& dir = hj["directions"][kDirection[k]];
      const std::string& t = dir["treatment"].string();
      const std::string where = m.hinge_info[h].name + " " + kDirection[k];
      switch (m.hinges[h].behaviour[k]) {
        case ntn::HingeBehaviour::kRigid:
        case ntn::HingeBehaviour::kRigidPlastic:  // below its yield: rigid
          EXPECT_EQ(t, "tied") << where;
          EXPECT_TRUE(dir["stiffness"].is_null()) << where;
          break;
        case ntn::HingeBehaviour::kFree:
          EXPECT_EQ(t, "free") << where;
          break;
        case ntn::HingeBehaviour::kLinear:
        case ntn::HingeBehaviour::kPlastic:  // below yield: its elastic stiffness
          if (m.hinges[h].stiffness[k] > 0) {
            EXPECT_EQ(t, "spring") << where;
            EXPECT_EQ(dir["stiffness"].number(), m.hinges[h].stiffness[k]) << where;
          } else {
            EXPECT_EQ(t, "free") << where;
          }
          break;
        case ntn::HingeBehaviour::kCurve:
          ++curves;
          EXPECT_EQ(where, "H_gap ux");
          EXPECT_EQ(t, "free") << where;
          break;
      }
    }
  }
  EXPECT_EQ(curves, 1);
  // H_spring: rotational spring ry of 2e6 N m/rad (config/hinged_beam.toml), the rest tied.
  EXPECT_EQ(hinges[0]["name"].string(), "H_spring");
  EXPECT_EQ(hinges[0]["directions"]["ry"]["stiffness"].number(), 2e6);
  // The table lists the same, one line per hinge.
  const Output table = ntn_model("modes '" + kHingedBeam + "' -n 3");
  EXPECT_EQ(table.exit, 0);
  EXPECT_NE(table.out.find("  hinge H_spring: tied ux, uy, uz, rx, rz; spring ry 2e+06 N m/rad\n"),
            std::string::npos)
      << table.out;
  EXPECT_NE(table.out.find("  member-end release P1.end: tied ux, uy, uz, rx; free ry, rz\n"),
            std::string::npos)
      << table.out;
}

// A mechanism (tests/modelc/good/pinned_joint.toml: node 1's rz has no mass and no stiffness) is
// listed; -n beyond the problem gives all modes and says so in the table.
TEST(ModelModes, MechanismsAndFewerModesThanAskedFor) {
  const Json j = modes_json("'" NTN_MODELC_GOOD_DIR "/pinned_joint.toml' -n 100000");
  ASSERT_EQ(j["mechanisms"].size(), 1U);
  EXPECT_EQ(j["mechanisms"][0]["description"].string(), "node 1");
  ASSERT_EQ(j["mechanisms"][0]["dofs"].size(), 1U);
  EXPECT_EQ(j["mechanisms"][0]["dofs"][0].string(), "rz");
  EXPECT_EQ(j["mechanism_dofs"].number(), 1);
  EXPECT_EQ(j["modes"].size(), static_cast<std::size_t>(j["eigenproblem_size"].number()));
  const Output table = ntn_model("modes '" NTN_MODELC_GOOD_DIR "/pinned_joint.toml' -n 100000");
  EXPECT_EQ(table.exit, 0);
  EXPECT_NE(table.out.find("(100000 asked for: the eigenproblem has "), std::string::npos)
      << table.out;
}

// A model file with errors: exit 1, the errors as file:line:column on stderr (as check and info);
// a bad -n: exit 2 (tests/robustness/cases.txt holds the hostile values).
TEST(ModelModes, ModelErrorsKeepTheirPositions) {
  ntn_test::TempDir dir("model_modes");
  const std::string bad = dir / "bad.toml";
  ntn_test::write_file(
      bad, ntn_test::read_file(kCantilever) + "\n[[nodes]]\nid = 1\nxyz = [0.0, 0.0, 0.0]\n");
  const Output o = ntn_model("modes '" + bad + "'", true);
  const std::string& out = o.out;
  EXPECT_EQ(o.exit, 1) << out;
  // The repeated id is on the third line after the file's last: its value at column 6.
  const std::string text = ntn_test::read_file(kCantilever);
  const auto line = std::count(text.begin(), text.end(), '\n') + 3;
  EXPECT_NE(out.find(bad + ":" + std::to_string(line) +
                     ":6: error: key 'nodes[2].id': duplicate "
                     "node id 1"),
            std::string::npos)
      << out;
  EXPECT_EQ(ntn_model("modes '" + kCantilever + "' -n 0").exit, 2);
}

// A model without supports (the cantilever's file with its support and reaction output removed):
// six rigid-body modes at ~0 Hz carry all the mass; a mode whose frequency is exactly 0 (a
// rounding-negative eigenvalue, clamped) has an infinite period and damping ratio, written as
// null, and the JSON still reads back.
TEST(ModelModes, RigidBodyModesOfAFreeModel) {
  std::string text = ntn_test::read_file(kCantilever);
  const std::size_t support = text.find("[[supports]]"), loads = text.find("[[loads]]");
  const std::size_t reaction = text.rfind("[[outputs]]");
  ASSERT_TRUE(support < loads && loads < reaction && reaction != std::string::npos);
  ASSERT_NE(text.find("kind = \"reaction\"", reaction), std::string::npos);
  text = text.substr(0, support) + text.substr(loads, reaction - loads);
  ntn_test::TempDir dir("model_modes_free");
  const std::string path = dir / "free.toml";
  ntn_test::write_file(path, text);
  const Json j = modes_json("'" + path + "' -n 8");
  const Json& modes = j["modes"];
  ASSERT_EQ(modes.size(), 8U);
  EXPECT_EQ(j["coordinates"].number(), 126);
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const double hz = modes[i]["frequency_hz"].number();
    EXPECT_EQ(modes[i]["period_s"].is_null(), hz == 0.0) << "mode " << i + 1;
    EXPECT_EQ(modes[i]["damping_ratio"].is_null(), hz == 0.0) << "mode " << i + 1;
    // Rigid-body modes: ~1e-4 Hz of rounding against a first bending mode of 65 Hz.
    if (i < 6) {
      EXPECT_LT(hz, 1e-2) << "mode " << i + 1;
    } else {
      EXPECT_GT(hz, 10.0) << "mode " << i + 1;
    }
  }
  for (int d = 0; d < 3; ++d)
    EXPECT_NEAR(modes[5]["cumulative_percent"][kAxis[d]].number(), 100.0, 1e-6) << kAxis[d];
}

// The reader the tests above rely on refuses what is not JSON (so "parsed back" means valid), and
// ntn::json writes what JSON cannot hold as null.
TEST(ModelModes, TheJsonReaderIsStrict) {
  for (const char* bad : {"{\"a\": 1,}", "[1,]", "[NaN]", "[inf]", "{\"a\": 1} x", "[01]", "[1.]",
                          "{\"a\": 1, \"a\": 2}", "[\"\x01\"]", "[\"\\x\"]", "{'a': 1}", ""}) {
    EXPECT_THROW(Json::parse(bad), std::runtime_error) << bad;
  }
  const Json ok = Json::parse(" {\"a\": [1, -2.5e-3, true, null, \"\\u00e9\\\"\"]} ");
  EXPECT_EQ(ok["a"][1].number(), -2.5e-3);
  EXPECT_TRUE(ok["a"][3].is_null());
  EXPECT_EQ(ok["a"][4].string(), "\u00e9\"");
  EXPECT_EQ(ntn::json::number(INFINITY), "null");
  EXPECT_EQ(ntn::json::number(NAN), "null");
  const double v = 0.1 + 0.2;  // not a short decimal: 17 digits needed
  EXPECT_EQ(Json::parse(ntn::json::number(v)).number(), v);
  EXPECT_EQ(Json::parse(ntn::json::quoted("a\"\\\n\t\x01"
                                          "b"))
                .string(),
            "a\"\\\n\t\x01"
            "b");
}

}  // namespace
