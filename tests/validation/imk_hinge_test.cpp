// The IMK law (HysteresisRule::kImk, ntn/laws/imk.hpp: the modified Ibarra-Medina-Krawinkler
// model, bilinear) against truth no one here chose:
// 1. the monotonic backbone of Ibarra et al. (2005) / Lignos and Krawinkler (2011), point by
//    point from its parameters: yield, hardening to the capping point, the post-capping slope
//    -F_c / theta_pc, the residual plateau, no strength past theta_u (exact to rounding);
// 2. under a symmetric cyclic protocol of constant amplitude the strength after each excursion
//    follows the energy rule beta_i = (E_i / (E_t - sum E_j))^c, F_y,i = (1 - beta_s) F_y,i-1,
//    K_s,i = (1 - beta_s) K_s,i-1 in the sense the next excursion loads (the other keeps its
//    strength: OpenSees' IMKBilin, for which the published Lambda were calibrated),
//    K_u,i = (1 - beta_k) K_u,i-1 (beta_k against 2 E_t), computed here with std::pow from
//    the energies the direction reports at each excursion's end (to rounding, 1e-12), and the
//    direction breaks in the excursion where the test's own sum of E_j spends E_t; on this
//    file's direction and on the example parameter set of OpenSees' IMKBilin documentation;
// 3. the energy it reports equals the work of its force, the trapezoid of f dd over the path, at
//    every zero force (where no elastic energy is held; the step's path has one kink, so 1e-3);
// 4. an SDOF of config/sdof.toml on an IMK spring under El Centro 1940 x 1.5 collapses (drifts past
//    theta_u and breaks) where the same SDOF with the bilinear law of the same k, F_y and
//    hardening (no capping, no deterioration) stays well inside theta_u;
// 5. the model compiler words the kernel's rule at the key (imk_check: one rule, two layers).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "ntn/hysteresis.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modelc/load_model.hpp"
#include "record.hpp"
#include "support/temp_files.hpp"
#include "text_model.hpp"

namespace imk_hinge_test {

namespace P = ntn::imk;

// k = 1000, F_y = 100 (yield at 0.1), theta_p = 0.2 (capping at 0.3, F_c = 120: K_s = 100),
// theta_pc = 0.6 (K_c = 200: the residual 40 is reached at 0.7), theta_u = 1.0.
constexpr double kK = 1000, kFy = 100;

// A symmetric IMK direction and the constant-amplitude protocol it is cycled through.
struct Cycled {
  double k, fy, theta_p, theta_pc, theta_u, capping, residual;  // the backbone
  double lambda, lambda_k, c;                                   // the deterioration
  double amplitude, step;
  int cycles;
  bool breaks;  // the protocol spends E_t
};

ntn::HysteresisSpec law(const Cycled& p) {
  ntn::HysteresisSpec s;
  s.rule = ntn::HysteresisRule::kImk;
  s.yield_pos = s.yield_neg = p.fy;
  auto& v = s.parameters;
  for (std::size_t i = 0; i < 2; ++i) {
    v[P::kPreCapping + i] = p.theta_p;
    v[P::kPostCapping + i] = p.theta_pc;
    v[P::kUltimate + i] = p.theta_u;
    v[P::kCappingRatio + i] = p.capping;
    v[P::kResidualRatio + i] = p.residual;
    v[P::kRate + i] = 1.0;
  }
  for (std::size_t j = 0; j < 3; ++j) {
    v[P::kLambda + j] = j == 2 ? p.lambda_k : p.lambda;
    v[P::kExponent + j] = p.c;
  }
  return s;
}

// The direction above without deterioration.
ntn::HysteresisSpec steady() {
  return law(Cycled{kK, kFy, 0.2, 0.6, 1.0, 1.2, 0.4, 0.0, 0.0, 1.0, 0.2, 1e-3, 0, false});
}

// The backbone by its definition (Ibarra et al. 2005, Fig. 1): force at deformation x >= 0.
double backbone(double x) {
  if (x > 1.0) return 0.0;
  if (x <= 0.1) return kK * x;
  if (x <= 0.3) return kFy + 100 * (x - 0.1);
  return std::max(120 - 200 * (x - 0.3), 40.0);
}

struct Direction {
  ntn::HysteresisData h;
  double dp = 0, w = 0, peak = 0;
  ntn::LawState x{};
  bool broke = false;
  double force(double d) {
    broke = ntn::hysteresis_update(h, d, dp, w, peak, x) || broke;
    return h.k * (d - dp);
  }
};

TEST(ImkLaw, MonotonicBackboneIsExact) {
  const ntn::HysteresisSpec s = steady();
  ASSERT_TRUE(ntn::hysteresis_valid(s, kK, 0.0));
  for (const int sense : {1, -1}) {
    Direction dir{ntn::make_hysteresis(s, kK)};
    int breaks = 0;
    for (int n = 1; n <= 1050; ++n) {
      const double x = n * 1e-3;
      const bool before = dir.broke;
      const double f = dir.force(sense * x);
      breaks += dir.broke && !before ? 1 : 0;
      EXPECT_NEAR(sense * f, backbone(x), 1e-12 * 120) << "at x = " << x;
    }
    EXPECT_EQ(breaks, 1);
    // The envelope the plots draw: B, C, D (the residual reached), E.
    const auto e = ntn::law_envelope(s, kK, sense);
    const double want[4][2] = {{0.1, 100}, {0.3, 120}, {0.7, 40}, {1.0, 40}};
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_NEAR(e[i].d, want[i][0], 1e-15);
      EXPECT_NEAR(e[i].force, want[i][1], 1e-12);
    }
  }
}

// A triangular protocol of amplitude a, `cycles` full cycles, in steps of `step` (exact at the
// vertices, where n is a multiple of the quarter cycle).
std::vector<double> protocol(double a, int cycles, double step = 1e-3) {
  const int quarter = static_cast<int>(std::lround(a / step));
  std::vector<double> d;
  for (int n = 0; n <= 4 * quarter * cycles; ++n) {
    const int m = n % (4 * quarter);
    const int along = m <= quarter ? m : m <= 3 * quarter ? 2 * quarter - m : m - 4 * quarter;
    d.push_back(along * step);
  }
  return d;
}

void follows_the_energy_rule(const Cycled& p) {
  const double et = p.lambda * p.fy, et_k = 2 * p.lambda_k * p.fy;  // K_u: against 2 E_t
  // the backbone's lines: hardening slope K_s, post-capping slope -K_c and its intercept at 0
  const double fc = p.capping * p.fy, ks0 = (fc - p.fy) / p.theta_p, kc = fc / p.theta_pc;
  const double intercept = fc + kc * (p.fy / p.k + p.theta_p);
  Direction dir{ntn::make_hysteresis(law(p), p.k)};
  const std::vector<double> d = protocol(p.amplitude, p.cycles, p.step);
  const auto quarter = static_cast<std::size_t>(std::lround(p.amplitude / p.step));
  double keep_s[2] = {1, 1}, keep_c[2] = {1, 1}, keep_k = 1, sign = 0, e_at = 0, work = 0,
         f_last = 0;
  int excursions = 0, vertices = 0;
  bool spent = false;
  for (std::size_t n = 1; n < d.size(); ++n) {
    const double f = dir.force(d[n]);
    work += 0.5 * (f + f_last) * (d[n] - d[n - 1]);
    if (dir.broke) {
      // It broke at an excursion's end (well inside theta_u): the energy so far (this step's
      // release of f^2 / 2k, a few mJ, included) spends E_t - E_i.
      const double e = dir.w - e_at;
      spent = et - dir.w <= e + 2.5e-5 * et;
      EXPECT_TRUE(spent) << "broke at step " << n << " with " << et - dir.w << " J left";
      EXPECT_LT(std::abs(d[n]), 0.5 * p.theta_u);
      break;
    }
    if (f != 0 && (f > 0 ? 1.0 : -1.0) != sign) {  // an excursion ends: the rule, by hand
      if (sign != 0) {
        const double e = dir.w - e_at;
        e_at = dir.w;
        ++excursions;
        ASSERT_GT(et - dir.w, e) << "its capacity is spent, yet it holds";
        const double beta = std::pow(e / (et - dir.w), p.c);
        const int next = f > 0 ? 0 : 1;  // the sense the next excursion loads
        keep_s[next] *= 1 - beta;
        keep_c[next] *= 1 - beta;
        keep_k *= 1 - std::pow(e / (et_k - dir.w), p.c);
        // The ledger against the trapezoid of f dd at (nearly) zero force: what is left is the
        // elastic energy of the small force reached, f^2 / 2 K_u, and the kink in the step.
        EXPECT_NEAR(dir.w, work, 1e-3 * dir.w + f * f / (2 * p.k * keep_k) + 1e-9);
      }
      sign = f > 0 ? 1.0 : -1.0;
    }
    if (std::abs(d[n]) == d[quarter]) {  // a vertex: on the deteriorated bound
      // the hardening line through (F_y,i / k, F_y,i) of slope K_s,i; the post-capping line of
      // slope -K_c, its intercept at d = 0 deteriorated; the residual under it
      const int at = d[n] > 0 ? 0 : 1;
      const double fy = p.fy * keep_s[at], ks = ks0 * keep_s[at];
      const double hardening = fy + ks * (p.amplitude - fy / p.k);
      const double post = intercept * keep_c[at] - kc * p.amplitude;
      const double bound = hardening <= post ? hardening : std::max(post, p.residual * p.fy);
      EXPECT_NEAR(std::abs(f), bound, 1e-12 * p.fy) << "vertex at step " << n;
      ++vertices;
      // and it unloads at K_u
      Direction probe = dir;
      const double step = d[n] > 0 ? -0.1 * p.step : 0.1 * p.step;
      const double slope = (probe.force(d[n] + step) - f) / step;
      EXPECT_NEAR(slope, p.k * keep_k, 1e-9 * p.k) << "unloading at step " << n;
    }
    f_last = f;
  }
  std::printf(
      "  c = %.2f: %d excursions, %d vertices checked, strength left %.4f / %.4f of F_y, "
      "broke: %s\n",
      p.c, excursions, vertices, keep_s[0], keep_s[1], dir.broke ? "yes" : "no");
  EXPECT_EQ(dir.broke, p.breaks);
  EXPECT_EQ(spent, p.breaks);
  EXPECT_GE(vertices, 8);
  EXPECT_GE(excursions, 8);
  EXPECT_LT(keep_s[0], 0.9);  // both senses deteriorated
  EXPECT_LT(keep_s[1], 0.9);
}

// Amplitude 0.2 of the direction above: beyond yield (0.1), short of capping (0.3): every vertex
// is on the bound of its sense, first the hardening line, later the post-capping line as its
// deterioration pulls it in, then the residual. Lambda = 4: E_t = 400 J, cycles of 40 J or less.
// The unloading stiffness deteriorates ten times slower (Lambda_k = 40): with Lambda_k =
// Lambda_s the loops shrink toward elastic ones and the capacity is approached, not spent.
Cycled own(double c) {
  return {kK, kFy, 0.2, 0.6, 1.0, 1.2, 0.4, 4.0, 40.0, c, 0.2, 1e-3, 80, true};
}

TEST(ImkLaw, CyclicStrengthFollowsTheEnergyRule) {
  follows_the_energy_rule(own(1.0));
}

TEST(ImkLaw, CyclicStrengthFollowsTheEnergyRuleWithAFractionalExponent) {
  follows_the_energy_rule(own(1.5));  // the step's r^1.5 without libm against std::pow
}

// The example parameter set of OpenSees' IMKBilin documentation (OpenSeesDocumentation,
// uniaxialMaterials/IMKBilin): Ke = 1e5, M_y = 100, M_c / M_y = 1.15, M_r / M_y = 0.1,
// theta_p = 0.01, theta_pc = 0.1, theta_u = 0.2, Lambda_s = Lambda_c = Lambda_k = 1, c = 1,
// D = 1; cycled at +-0.008 (yield at 0.001, capping at 0.011) for 40 cycles: with Lambda_k =
// Lambda_s the loops narrow as K_u falls, and the capacity E_t = 100 is approached, not spent.
TEST(ImkLaw, TheReferenceDocumentationsParameterSetFollowsTheEnergyRule) {
  follows_the_energy_rule(
      {1e5, 100, 0.01, 0.1, 0.2, 1.15, 0.1, 1.0, 1.0, 1.0, 0.008, 1e-5, 40, false});
}

TEST(ImkLaw, NoDeteriorationWithoutLambdaIsTheBilinearLawInsideTheCap) {
  // Lambda = 0 and amplitudes short of capping: the bilinear law with b = K_s / k = 0.1, the
  // same forces to rounding.
  Direction imk{ntn::make_hysteresis(steady(), kK)};
  ntn::HysteresisSpec b;
  b.yield_pos = b.yield_neg = kFy;
  b.hardening = 0.1;
  const ntn::HysteresisData bh = ntn::make_hysteresis(b, kK);
  double dp = 0, w = 0, peak = 0;
  ntn::LawState x{};
  for (const double d : protocol(0.25, 4)) {
    ntn::hysteresis_update(bh, d, dp, w, peak, x);
    EXPECT_NEAR(imk.force(d), kK * (d - dp), 1e-11 * kFy) << "at d = " << d;
  }
  EXPECT_NEAR(imk.w, w, 1e-9 * w);
}

// ---- 4. An SDOF that collapses: config/sdof.toml (1 t; k = 4e5 N/m, T = 0.314 s) with its
// spring an IMK direction of F_y = 2.5 kN (0.25 g of its weight), theta_p = 0.02 m, F_c / F_y =
// 1.1, theta_pc = 0.05 m, no residual, theta_u = 0.1 m, Lambda = 0.5 m, against the bilinear
// law of the same k, F_y and hardening (K_s / k = 0.03125).
std::string sdof_with(const std::string& spring) {
  std::string t = ntn_test::read_file(NTN_CONFIG_DIR "/sdof.toml");
  const std::string damped = "ux = { linear = 4.0e5, dashpot = 2.0e3 }";
  const std::size_t at = t.find(damped);
  if (at == std::string::npos) return "";
  t.replace(at, damped.size(), "ux = " + spring);
  return t;
}

struct Drift {
  double peak = 0;
  bool broke = false;
};

Drift run_el_centro(const std::string& spring, double scale) {
  const auto rt = ntn_test::load_text_model(sdof_with(spring), "sdof.toml");
  if (rt == nullptr) return {};
  const ntn::io::ReadResult rec =
      ntn::io::read_at2(std::string(NTN_CONFIG_DIR) + "/ground-motions/elCentro.AT2");
  EXPECT_TRUE(rec.record.has_value());
  if (!rec.record) return {};
  ntn::Model<ntn::kRunTime>& m = rt->model();
  ntn::State<ntn::kRunTime>& s = rt->state();
  ntn::Scratch<ntn::kRunTime>& w = rt->scratch();
  ntn::initial_state(m, s);
  std::vector<double> in = {scale * rec.record->at(0.0)};
  EXPECT_EQ(ntn::start(m, s, w, std::span<const double>(in)), ntn::StepStatus::kOk);
  Drift out;
  const long steps = static_cast<long>(30.0 / m.dt);
  for (long n = 1; n <= steps; ++n) {
    in[0] = scale * rec.record->at(static_cast<double>(n) * m.dt);
    EXPECT_EQ(ntn::step(m, s, w, std::span<const double>(in)), ntn::StepStatus::kOk);
    out.peak = std::max(out.peak, std::abs(w.outputs[0]));
  }
  out.broke = s.first_slip[0] != 0;
  return out;
}

TEST(ImkSdof, DeterioratingSdofCollapsesWhereTheBilinearOneDoesNot) {
  const std::string imk =
      "{ imk = 4.0e5, yield = 2500.0, pre_capping = 0.02, capping_ratio = 1.1, "
      "post_capping = 0.05, residual_ratio = 0.0, ultimate = 0.1, lambda = 0.5 }";
  const std::string bilinear = "{ plastic = 4.0e5, yield = 2500.0, hardening = 0.03125 }";
  const double scale = 1.5;
  const Drift a = run_el_centro(imk, scale);
  const Drift b = run_el_centro(bilinear, scale);
  std::printf("  El Centro x %.1f: IMK peak drift %.4g m (broke: %s), bilinear %.4g m\n", scale,
              a.peak, a.broke ? "yes" : "no", b.peak);
  EXPECT_TRUE(a.broke);
  EXPECT_GT(a.peak, 0.1);  // past theta_u
  EXPECT_FALSE(b.broke);
  EXPECT_LT(b.peak, 0.08);  // well inside theta_u = 0.1
}

// ---- 5. The compiler's words for the kernel's rule, at the key.
std::string errors_of(const std::string& spring) {
  const ntn::modelc::LoadResult r =
      ntn::modelc::load_model_from_string(sdof_with(spring), "sdof.toml");
  return r.ok() ? std::string() : ntn::modelc::format_all(r.errors);
}

TEST(ImkReader, WordsTheKernelsRuleAtTheKey) {
  const std::string base =
      "imk = 4.0e5, yield = 2500.0, pre_capping = 0.02, post_capping = 0.05, ultimate = 0.1";
  EXPECT_EQ(errors_of("{ " + base + ", capping_ratio = 1.1 }"), "");
  const struct {
    std::string extra, key, words;
  } cases[] = {
      {"capping_ratio = 0.9", "capping_ratio", "must be at least 1"},
      {"capping_ratio = 5.0", "capping_ratio", "is not below the elastic stiffness k = 400000"},
      {"capping_ratio = 1.1, residual_ratio = 1.5", "residual_ratio",
       "must lie between 0 and capping_ratio = 1.1"},
      {"capping_ratio = [1.1, 1.1], exponent = 1.3", "exponent",
       "must be a multiple of 0.25 from 0.25 to 4"},
      {"capping_ratio = 1.1, rate = [1.0, 0.0]", "rate", "(negative sense)"},
      {"capping_ratio = 1.1, dashpot = 10.0", "dashpot", "an imk direction takes no dashpot"},
  };
  for (const auto& c : cases) {
    const std::string e = errors_of("{ " + base + ", " + c.extra + " }");
    EXPECT_NE(e.find("key 'hinges[0].ux." + c.key + "'"), std::string::npos) << e;
    EXPECT_NE(e.find(c.words), std::string::npos) << e;
  }
  // ultimate short of the capping point F_y / k + theta_p = 0.02625
  const std::string short_u = errors_of(
      "{ imk = 4.0e5, yield = 2500.0, pre_capping = 0.02, post_capping = 0.05, "
      "ultimate = 0.02, capping_ratio = 1.1 }");
  EXPECT_NE(short_u.find("must lie beyond the capping point F_y / k + theta_p = 0.02625"),
            std::string::npos)
      << short_u;
  // its keys only with imk
  EXPECT_NE(errors_of("{ linear = 1.0, pre_capping = 0.02 }").find("only applies with 'imk'"),
            std::string::npos);
}

}  // namespace imk_hinge_test
