// A spectral peak of noise is not a mode. Gaussian white noise with no structure, 60 s at 1 kHz
// (the demo's record length, a single Welch segment at the default resolution), checked for the
// default frame's first mode along x within 1 %: before the noise test a random peak inside the
// search band passed in 14 of 20 seeds. Now a matched peak must stand out of its local floor by
// the chi-square threshold of a 1 % false alarm in the search band, so noise fails in at least 99
// of 100 seeds, on one channel (PSD) and on two (FDD), and on a record of 20 segments (where the
// threshold is set by the average's degrees of freedom). The real response passes:
// ModeCheckEndToEnd.ElCentroResponsePassesAboveTheNoise. The seeds are fixed: the counts are the
// same on every machine.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "ntn/modecheck/modecheck.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/spectral/significance.hpp"

namespace modecheck_noise_test {

namespace mc = ntn::modecheck;

const ntn::modelc::ModelDescription& frame3d() {
  static const ntn::modelc::LoadResult r = ntn::modelc::load_model(NTN_FRAME3D);
  return *r.model;
}

// Passes of the check of mode 1 along x against `seeds` records of white noise on `names`: the
// steps of check_data, with the model's modes computed once.
int noise_passes(const std::vector<std::string>& names, double seconds, int seeds,
                 double resolution = 0) {
  mc::Options o;
  o.modes = 1;
  o.direction = 0;
  o.resolution_hz = resolution;
  int passes = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
    std::normal_distribution<double> gauss(0.0, 1e-3);
    ntn::spectral::Channels ch;
    ch.source = "noise";
    ch.fs = 1000;
    for (const std::string& n : names) {
      ch.names.push_back(n);
      ch.units.emplace_back("m");
      std::vector<double> x(static_cast<std::size_t>(seconds * ch.fs));
      for (double& v : x)
        v = gauss(rng);
      ch.data.push_back(std::move(x));
    }
    // check_data's steps, with the model's modes computed once for every seed.
    const mc::Selection here = mc::select_channels(&frame3d(), ch, names);
    static std::map<std::size_t, mc::ModelModes> modes;
    if (!modes.count(names.size())) modes[names.size()] = mc::model_modes(frame3d(), here, o);
    const mc::ModelModes& m = modes[names.size()];
    const double f = m.frequency.front();
    const double df = mc::resolve_resolution(ch, f, o, nullptr);
    const mc::Identification id =
        mc::identify(ch, here, df, f * (1 - o.search_band), f * (1 + o.search_band), o);
    const mc::Report r = mc::compare(m, id, here, o);
    passes += r.pass ? 1 : 0;
    EXPECT_EQ(r.modes.size(), 1U);
  }
  return passes;
}

TEST(ModeCheckNoise, WhiteNoiseOnOneChannelFails) {
  EXPECT_LE(noise_passes({"roof_ux"}, 60, 100), 1);
}

TEST(ModeCheckNoise, WhiteNoiseOnTwoChannelsFails) {
  EXPECT_LE(noise_passes({"roof_ux", "floor1_ux"}, 60, 100), 1);
}

// 20 Hann segments of 10 s with half overlap: about 37 degrees of freedom, a threshold of a few
// times the floor instead of 11.
TEST(ModeCheckNoise, WhiteNoiseOverManySegmentsFails) {
  EXPECT_LE(noise_passes({"roof_ux"}, 105, 50, 0.1), 1);
}

// The threshold's parts against closed forms.
TEST(ModeCheckNoise, DegreesOfFreedomAndThresholdMatchClosedForms) {
  ntn::spectral::Grid g;
  g.window = ntn::spectral::Window::kHann;
  g.segment = 1000, g.step = 500;
  // Hann at 50 % overlap: rho_1 = 1/6 (Percival and Walden, table 292), so
  // nu = 2 K^2 / (K + 2 (K - 1) / 36); the window's samples give it to 1e-3.
  for (const std::size_t K : {2U, 5U, 20U}) {
    g.segments = K;
    const double k = static_cast<double>(K);
    EXPECT_NEAR(ntn::spectral::welch_dof(g), 2 * k * k / (k + 2 * (k - 1) / 36.0), 1e-3 * k);
  }
  g.segments = 1;
  EXPECT_EQ(ntn::spectral::welch_dof(g), 2.0);
  // Two degrees of freedom: chi^2_2 / 2 is exponential, median ln 2; one line at 1 %:
  // t = ln(100) / ln(2).
  EXPECT_NEAR(ntn::spectral::noise_threshold(2, 1, 0.01), std::log(100.0) / std::log(2.0), 1e-9);
  // M lines: exp(-t ln2) = 1 - 0.99^(1/M).
  const double m = 21;
  EXPECT_NEAR(ntn::spectral::noise_threshold(2, m, 0.01),
              -std::log(1 - std::pow(0.99, 1 / m)) / std::log(2.0), 1e-9);
}

}  // namespace modecheck_noise_test
