// Lognormal fragility fits: the closed form without censoring; with censored records,
// the maximum of a log-likelihood written here independently (a grid search and its gradient),
// and the recovery of a known lognormal from a censored sample; the errors; the fractiles against
// numpy's definition.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ntn/ida/fragility.hpp"

namespace ntn::ida {
namespace fragility_test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// log L = sum_obs [ln phi(z_i) - ln beta - ln x_i] + sum_cens ln(1 - Phi(z_c)),
// z = (ln x - mu) / beta, as the issue states it. 1 - Phi by erfc directly: the data here keep
// |z| < 10, where it has its full precision.
double log_likelihood(const std::vector<double>& observed, const std::vector<double>& censored,
                      double mu, double beta) {
  double sum = 0;
  for (const double x : observed) {
    const double z = (std::log(x) - mu) / beta;
    sum += -0.5 * z * z - 0.5 * std::log(2 * std::numbers::pi) - std::log(beta) - std::log(x);
  }
  for (const double c : censored) {
    const double z = (std::log(c) - mu) / beta;
    sum += std::log(0.5 * std::erfc(z / std::numbers::sqrt2));
  }
  return sum;
}

// The gradient and Hessian of log_likelihood in (mu, beta) by central differences of step h.
struct Derivatives {
  double d_mu, d_beta;
  double d_mu_mu, d_mu_beta, d_beta_beta;
};

Derivatives derivatives(const std::vector<double>& observed, const std::vector<double>& censored,
                        double mu, double beta, double h) {
  auto l = [&](double dm, double db) {
    return log_likelihood(observed, censored, mu + dm * h, beta + db * h);
  };
  Derivatives d{};
  d.d_mu = (l(1, 0) - l(-1, 0)) / (2 * h);
  d.d_beta = (l(0, 1) - l(0, -1)) / (2 * h);
  d.d_mu_mu = (l(1, 0) - 2 * l(0, 0) + l(-1, 0)) / (h * h);
  d.d_beta_beta = (l(0, 1) - 2 * l(0, 0) + l(0, -1)) / (h * h);
  d.d_mu_beta = (l(1, 1) - l(1, -1) - l(-1, 1) + l(-1, -1)) / (4 * h * h);
  return d;
}

TEST(FitLognormal, WithoutCensoringIsTheClosedForm) {
  const std::vector<double> x{0.42, 0.55, 0.61, 0.73, 0.9, 1.12, 1.35};
  double sum = 0;
  for (const double v : x) {
    sum += std::log(v);
  }
  const double mu = sum / 7;
  double squares = 0;
  for (const double v : x) {
    squares += (std::log(v) - mu) * (std::log(v) - mu);
  }
  const double beta = std::sqrt(squares / 7);  // population, not sample (/ 6)

  const LognormalFit fit = fit_lognormal(x, {});
  ASSERT_TRUE(fit.ok()) << fit.error;
  EXPECT_EQ(fit.observed, 7);
  EXPECT_EQ(fit.censored, 0);
  // 1e-14: the same sums, whose order might differ by rounding (seven terms of order 1).
  EXPECT_NEAR(fit.median, std::exp(mu), 1e-14 * std::exp(mu));
  EXPECT_NEAR(fit.beta, beta, 1e-14 * beta);
}

// Eight capacities and three records that did not reach the limit state at 1.2 (three of eleven
// records right-censored there move the median up and widen beta).
TEST(FitLognormal, WithCensoringIsTheLikelihoodsMaximum) {
  const std::vector<double> observed{0.35, 0.48, 0.52, 0.66, 0.71, 0.84, 0.97, 1.1};
  const std::vector<double> censored{1.2, 1.2, 1.2};
  const LognormalFit fit = fit_lognormal(observed, censored);
  ASSERT_TRUE(fit.ok()) << fit.error;
  EXPECT_EQ(fit.observed, 8);
  EXPECT_EQ(fit.censored, 3);
  const double mu = std::log(fit.median);
  const double beta = fit.beta;

  // A grid of 2e-4 over +-0.1 around the fit (1001 x 1001 nodes): its best node is within one
  // spacing of the fit in each coordinate (mu and beta are weakly correlated here, so the best
  // node is the nearest one or its neighbour), and no node is above the fit's log L beyond
  // rounding (1e-12 relative).
  const double spacing = 2e-4;
  const int half = 500;
  const double at_fit = log_likelihood(observed, censored, mu, beta);
  double best = -kInf;
  int best_i = 0;
  int best_j = 0;
  for (int i = -half; i <= half; ++i) {
    for (int j = -half; j <= half; ++j) {
      const double l = log_likelihood(observed, censored, mu + i * spacing, beta + j * spacing);
      if (l > best) {
        best = l;
        best_i = i;
        best_j = j;
      }
    }
  }
  std::printf("  censored fit: median %.6f beta %.6f; grid maximum at (%d, %d) spacings\n",
              fit.median, fit.beta, best_i, best_j);
  EXPECT_LE(std::abs(best_i), 1);
  EXPECT_LE(std::abs(best_j), 1);
  EXPECT_LE(best, at_fit + 1e-12 * std::abs(at_fit));

  // The gradient at the fit, by central differences (h = 1e-5: truncation ~h^2 |L'''| ~ 1e-7,
  // rounding ~1e-16 |L| / h ~ 1e-10), divided by the curvature: Newton's distance to the
  // maximum, under 1e-7 in mu and beta (a fit off by 1e-4, the grid's resolution, shows 1e-4).
  const Derivatives d = derivatives(observed, censored, mu, beta, 1e-5);
  std::printf("  censored fit: Newton distance mu %.1e, beta %.1e\n", d.d_mu / d.d_mu_mu,
              d.d_beta / d.d_beta_beta);
  EXPECT_LT(std::abs(d.d_mu / d.d_mu_mu), 1e-7);
  EXPECT_LT(std::abs(d.d_beta / d.d_beta_beta), 1e-7);
  EXPECT_GT(fit.median, std::exp(-0.35));  // above the observed geometric mean (0.70)
}

// 2000 capacities from a lognormal (median 0.6, beta 0.45; std::mt19937_64 seed 19), those above
// its 80 % fractile (0.6 exp(0.45 x 0.8416)) censored there. The fit recovers median and beta
// within 3 standard errors, from the observed information (the inverse Hessian of log L at the
// fit, by differences). The closed form of the observed capacities alone (ignoring the censoring)
// is more than 3 standard errors off: the test tells the two apart.
TEST(FitLognormal, RecoversAKnownLognormalFromACensoredSample) {
  const double true_median = 0.6;
  const double true_beta = 0.45;
  const double censoring = true_median * std::exp(true_beta * 0.8416212335729143);
  std::mt19937_64 generator(19);
  std::lognormal_distribution<double> capacity(std::log(true_median), true_beta);
  std::vector<double> observed;
  std::vector<double> censored;
  for (int i = 0; i < 2000; ++i) {
    const double x = capacity(generator);
    if (x > censoring) {
      censored.push_back(censoring);
    } else {
      observed.push_back(x);
    }
  }
  ASSERT_GT(censored.size(), 300u);  // ~20 %
  ASSERT_LT(censored.size(), 500u);

  const LognormalFit fit = fit_lognormal(observed, censored);
  ASSERT_TRUE(fit.ok()) << fit.error;
  const double mu = std::log(fit.median);
  const Derivatives d = derivatives(observed, censored, mu, fit.beta, 1e-4);
  // Covariance = (-H)^-1.
  const double det = d.d_mu_mu * d.d_beta_beta - d.d_mu_beta * d.d_mu_beta;
  ASSERT_GT(det, 0);
  ASSERT_LT(d.d_mu_mu, 0);
  const double se_mu = std::sqrt(-d.d_beta_beta / det);
  const double se_beta = std::sqrt(-d.d_mu_mu / det);
  const double mu_error = (mu - std::log(true_median)) / se_mu;
  const double beta_error = (fit.beta - true_beta) / se_beta;
  std::printf(
      "  n = 2000, %zu censored: median %.5f (SE %.4f of ln), beta %.5f (SE %.4f): %.2f and %.2f "
      "standard errors off\n",
      censored.size(), fit.median, se_mu, fit.beta, se_beta, mu_error, beta_error);
  EXPECT_LT(std::abs(mu_error), 3);
  EXPECT_LT(std::abs(beta_error), 3);

  const LognormalFit ignoring = fit_lognormal(observed, {});
  ASSERT_TRUE(ignoring.ok());
  EXPECT_GT(std::abs(std::log(ignoring.median / true_median)), 3 * se_mu);
}

// Censoring intensities far from the capacities: far below (1 - Phi = 1 to the last bit: the fit
// is the closed form) and far above (z = 170 at the closed form, where erfc underflows: the
// fit must widen beta until the record is plausible, and still be the maximum).
TEST(FitLognormal, CensoringFarFromTheCapacities) {
  const std::vector<double> observed{0.9, 1.0, 1.1, 1.25};
  const std::vector<double> far_below{1e-3};
  const LognormalFit closed = fit_lognormal(observed, {});
  const LognormalFit below = fit_lognormal(observed, far_below);
  ASSERT_TRUE(below.ok()) << below.error;
  EXPECT_NEAR(below.median, closed.median, 1e-14 * closed.median);
  EXPECT_NEAR(below.beta, closed.beta, 1e-14 * closed.beta);

  const std::vector<double> far_above{1e6};
  const LognormalFit above = fit_lognormal(observed, far_above);
  ASSERT_TRUE(above.ok()) << above.error;
  EXPECT_GT(above.beta, 3 * closed.beta);
  const double mu = std::log(above.median);
  const Derivatives d = derivatives(observed, far_above, mu, above.beta, 1e-5);
  std::printf("  far censoring: beta %.4f (closed form %.4f), Newton distance %.1e, %.1e\n",
              above.beta, closed.beta, d.d_mu / d.d_mu_mu, d.d_beta / d.d_beta_beta);
  EXPECT_LT(std::abs(d.d_mu / d.d_mu_mu), 1e-7);
  EXPECT_LT(std::abs(d.d_beta / d.d_beta_beta), 1e-7);
}

TEST(FitLognormal, Errors) {
  const std::vector<double> ok{1.0, 2.0};
  ASSERT_TRUE(fit_lognormal(ok, {}).ok());  // the control
  struct Case {
    std::vector<double> observed;
    std::vector<double> censored;
    const char* says;
  };
  const std::vector<Case> cases{
      {{}, {}, "fewer than two distinct"},
      {{1.0}, {2.0}, "fewer than two distinct"},
      {{1.5, 1.5, 1.5}, {2.0}, "fewer than two distinct"},
      {{1.0, 0.0}, {}, "observed capacity 2"},
      {{1.0, -2.0}, {}, "observed capacity 2"},
      {{1.0, kNaN}, {}, "observed capacity 2"},
      {{1.0, kInf}, {}, "observed capacity 2"},
      {{1.0, 2.0}, {0.0}, "censoring intensity 1"},
      {{1.0, 2.0}, {3.0, kInf}, "censoring intensity 2"},
      {{1.0, 2.0}, {kNaN}, "censoring intensity 1"},
  };
  for (const Case& c : cases) {
    const LognormalFit fit = fit_lognormal(c.observed, c.censored);
    EXPECT_FALSE(fit.ok()) << c.says;
    EXPECT_NE(fit.error.find(c.says), std::string::npos) << fit.error;
  }
}

// Phi at z = 0 and 1 (Phi(1) = 0.841344746068542948585...); 1e-15: erfc's rounding.
TEST(LognormalCdf, Values) {
  EXPECT_NEAR(lognormal_cdf(0.8, 0.8, 0.4), 0.5, 1e-15);
  EXPECT_NEAR(lognormal_cdf(0.8 * std::exp(0.4), 0.8, 0.4), 0.8413447460685429, 1e-15);
  EXPECT_NEAR(lognormal_cdf(0.8 / std::exp(0.4), 0.8, 0.4), 1 - 0.8413447460685429, 1e-15);
  EXPECT_EQ(lognormal_cdf(0.0, 0.8, 0.4), 0.0);
  EXPECT_EQ(lognormal_cdf(-1.0, 0.8, 0.4), 0.0);
  EXPECT_EQ(lognormal_cdf(kInf, 0.8, 0.4), 1.0);
  EXPECT_TRUE(std::isnan(lognormal_cdf(1.0, 0.0, 0.4)));
  EXPECT_TRUE(std::isnan(lognormal_cdf(1.0, 0.8, 0.0)));
  EXPECT_TRUE(std::isnan(lognormal_cdf(kNaN, 0.8, 0.4)));
}

// numpy.quantile(values, p) (linear, Hyndman and Fan 7): sorted x, h = (n - 1) p,
// x[floor h] + (h - floor h) (x[floor h + 1] - x[floor h]). Values by hand; exact where h is a
// binary fraction, else 1e-15 (h = 4 x 0.3 rounds to 1.2000000000000002).
TEST(Fractile, NumpyDefinition) {
  const std::vector<double> x{3, 1, 4, 1, 5};  // sorted: 1 1 3 4 5
  EXPECT_EQ(fractile(x, 0.0), 1.0);
  EXPECT_EQ(fractile(x, 0.25), 1.0);          // h = 1
  EXPECT_NEAR(fractile(x, 0.3), 1.4, 1e-15);  // h = 1.2: 1 + 0.2 (3 - 1)
  EXPECT_EQ(fractile(x, 0.5), 3.0);           // h = 2
  EXPECT_EQ(fractile(x, 0.625), 3.5);         // h = 2.5
  EXPECT_NEAR(fractile(x, 0.9), 4.6, 1e-15);  // h = 3.6: 4 + 0.6 (5 - 4)
  EXPECT_EQ(fractile(x, 1.0), 5.0);
  const std::vector<double> four{4, 2, 1, 3};
  EXPECT_EQ(fractile(four, 0.5), 2.5);    // h = 1.5
  EXPECT_EQ(fractile(four, 0.25), 1.75);  // h = 0.75
  EXPECT_EQ(fractile(four, 0.75), 3.25);  // h = 2.25
  const std::vector<double> one{7};
  EXPECT_EQ(fractile(one, 0.0), 7.0);
  EXPECT_EQ(fractile(one, 0.37), 7.0);
  EXPECT_EQ(fractile(one, 1.0), 7.0);
}

// +infinity (a collapsed record) sorts last; a fractile between it and the value below is +inf;
// one exactly on a finite order statistic is that value.
TEST(Fractile, InfiniteValues) {
  const std::vector<double> x{2, kInf, 1};  // sorted: 1 2 inf
  EXPECT_EQ(fractile(x, 0.0), 1.0);
  EXPECT_EQ(fractile(x, 0.25), 1.5);   // h = 0.5
  EXPECT_EQ(fractile(x, 0.5), 2.0);    // h = 1: on the median record, next to the collapse
  EXPECT_EQ(fractile(x, 0.6), kInf);   // h = 1.2
  EXPECT_EQ(fractile(x, 0.75), kInf);  // h = 1.5
  EXPECT_EQ(fractile(x, 1.0), kInf);
  const std::vector<double> two{kInf, 1, kInf};  // sorted: 1 inf inf
  EXPECT_EQ(fractile(two, 0.0), 1.0);
  EXPECT_EQ(fractile(two, 0.25), kInf);  // between 1 and inf
  EXPECT_EQ(fractile(two, 0.5), kInf);   // on inf
  EXPECT_EQ(fractile(two, 0.75), kInf);  // between two infinities
  EXPECT_EQ(fractile(two, 1.0), kInf);
}

TEST(Fractile, NaNCases) {
  EXPECT_TRUE(std::isnan(fractile({}, 0.5)));
  const std::vector<double> x{1, 2, 3};
  EXPECT_TRUE(std::isnan(fractile(x, -0.1)));
  EXPECT_TRUE(std::isnan(fractile(x, 1.1)));
  EXPECT_TRUE(std::isnan(fractile(x, kNaN)));
  EXPECT_TRUE(std::isnan(fractile({1, kNaN, 3}, 0.5)));
  EXPECT_TRUE(std::isnan(fractile({1, -kInf, 3}, 0.5)));
}

}  // namespace fragility_test
}  // namespace ntn::ida
