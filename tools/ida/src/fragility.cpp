// Lognormal fragility fits by maximum likelihood with right-censored records, and the empirical
// fractiles of IDA curves.
#include "ntn/ida/fragility.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace ntn::ida {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kLnSqrt2Pi = 0.91893853320467274178;  // ln sqrt(2 pi)

// Beyond this z the upper tail 1 - Phi(z) is taken from its asymptotic series: erfc(z / sqrt 2)
// would underflow from z ~ 37.5, and at z = 30 the series' first omitted term is below 1e-19.
constexpr double kTailStart = 30;

// (1 - Phi(z)) z / phi(z) - 1 for z >= kTailStart: the asymptotic series of Mills' ratio,
// sum_k>=1 (-1)^k (2k - 1)!! / z^2k, to k = 8 (an alternating series: the error is below the
// first omitted term). Returned without its leading 1 so that h - z below keeps its digits.
double mills_ratio_series_tail(double z) {
  double term = 1;
  double sum = 0;
  for (int k = 1; k <= 8; ++k) {
    term *= -static_cast<double>(2 * k - 1) / (z * z);
    sum += term;
  }
  return sum;
}

// ln(1 - Phi(z)), accurate for every z: through log1p where 1 - Phi is near 1, erfc in the
// middle, and the asymptotic series where erfc would underflow.
double log_upper_tail(double z) {
  if (z < 0) return std::log1p(-0.5 * std::erfc(-z / std::numbers::sqrt2));
  if (z < kTailStart) return std::log(0.5 * std::erfc(z / std::numbers::sqrt2));
  return -0.5 * z * z - kLnSqrt2Pi - std::log(z) + std::log1p(mills_ratio_series_tail(z));
}

// The hazard h(z) = phi(z) / (1 - Phi(z)) = -d/dz ln(1 - Phi(z)), and h - z (h'(z) = h (h - z)).
struct Hazard {
  double h;
  double h_minus_z;
};

Hazard hazard(double z) {
  if (z < kTailStart) {
    const double h =
        std::exp(-0.5 * z * z - kLnSqrt2Pi) / (0.5 * std::erfc(z / std::numbers::sqrt2));
    return {h, h - z};
  }
  // h = z / (1 + s), s the series' tail: h - z = -z s / (1 + s).
  const double s = mills_ratio_series_tail(z);
  return {z / (1 + s), -z * s / (1 + s)};
}

// The log-likelihood of standardized log-capacities y (observed) and log-censoring intensities
// (censored), with its gradient and Hessian, in tau = 1 / beta and m = mu / beta: z = tau y - m is
// linear in them, and ln phi, ln(1 - Phi) and ln tau are concave, so the log-likelihood is
// strictly concave there: one maximum, and Newton's direction always climbs (in (mu, ln beta) it
// is not concave far from the maximum). Constant terms (-ln x_i, the standardization's scale)
// are left out.
struct LogLikelihood {
  double value = 0;
  double d_tau = 0;
  double d_m = 0;
  double d_tau_tau = 0;
  double d_tau_m = 0;
  double d_m_m = 0;
};

LogLikelihood log_likelihood(const std::vector<double>& observed,
                             const std::vector<double>& censored, double tau, double m) {
  LogLikelihood l;
  const double log_tau = std::log(tau);
  for (const double y : observed) {
    // ln phi(z) + ln tau: the density of y is tau phi(tau y - m).
    const double z = tau * y - m;
    l.value += -0.5 * z * z - kLnSqrt2Pi + log_tau;
    l.d_tau += -z * y + 1 / tau;
    l.d_m += z;
    l.d_tau_tau += -y * y - 1 / (tau * tau);
    l.d_tau_m += y;
    l.d_m_m += -1;
  }
  for (const double y : censored) {
    // ln(1 - Phi(z)): the record's capacity exceeds its highest intensity run.
    const double z = tau * y - m;
    const Hazard hz = hazard(z);
    const double curvature = hz.h * hz.h_minus_z;  // -d2/dz2 ln(1 - Phi(z)), in (0, 1)
    l.value += log_upper_tail(z);
    l.d_tau += -hz.h * y;
    l.d_m += hz.h;
    l.d_tau_tau += -curvature * y * y;
    l.d_tau_m += curvature * y;
    l.d_m_m += -curvature;
  }
  return l;
}

std::string describe(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// The error for a value that is not a finite positive number, or empty.
std::string check_values(std::span<const double> values, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!(std::isfinite(values[i]) && values[i] > 0)) {
      return std::string(what) + " " + std::to_string(i + 1) + " is " + describe(values[i]) +
             ": not a finite positive intensity";
    }
  }
  return {};
}

}  // namespace

LognormalFit fit_lognormal(std::span<const double> observed,
                           std::span<const double> censored_above) {
  LognormalFit fit;
  fit.observed = static_cast<int>(observed.size());
  fit.censored = static_cast<int>(censored_above.size());
  fit.error = check_values(observed, "observed capacity");
  if (fit.error.empty()) fit.error = check_values(censored_above, "censoring intensity");
  if (!fit.error.empty()) return fit;

  std::vector<double> log_observed(observed.size());
  std::transform(observed.begin(), observed.end(), log_observed.begin(),
                 [](double x) { return std::log(x); });
  // Distinct logarithms, not values: two neighbouring doubles near 1e300 have the same log.
  std::vector<double> distinct = log_observed;
  std::sort(distinct.begin(), distinct.end());
  const auto distinct_count = std::unique(distinct.begin(), distinct.end()) - distinct.begin();
  if (distinct_count < 2) {
    fit.error = "fewer than two distinct observed capacities (" + std::to_string(observed.size()) +
                " observed, " + std::to_string(distinct_count) + " distinct): no dispersion to fit";
    return fit;
  }

  // The closed form of the observed capacities alone: the mean and population standard
  // deviation of ln x, summed in the order given.
  const double n = static_cast<double>(log_observed.size());
  double sum = 0;
  for (const double y : log_observed) {
    sum += y;
  }
  const double mean = sum / n;
  double sum_of_squares = 0;
  for (const double y : log_observed) {
    sum_of_squares += (y - mean) * (y - mean);
  }
  const double deviation = std::sqrt(sum_of_squares / n);

  if (censored_above.empty()) {
    fit.median = std::exp(mean);
    fit.beta = deviation;
    return fit;
  }

  // Censored data: maximise from the closed form, in units standardized by it (y = (ln x -
  // mean) / deviation), where that start is tau = 1, m = 0 and the steps are of order 1.
  std::vector<double> y_observed(log_observed.size());
  for (std::size_t i = 0; i < y_observed.size(); ++i) {
    y_observed[i] = (log_observed[i] - mean) / deviation;
  }
  std::vector<double> y_censored(censored_above.size());
  for (std::size_t i = 0; i < y_censored.size(); ++i) {
    y_censored[i] = (std::log(censored_above[i]) - mean) / deviation;
  }

  // Newton's method with step halving. Halving needs the log-likelihood to tell a gain from
  // rounding, which it cannot near the maximum (a gain of d^2 against a rounding of ~n 1e-16
  // stops at d ~ 1e-8): once the quadratic model predicts a gain below kQuadraticRegion, the full
  // Newton step is taken, as Newton converges quadratically there. Converged when a step moves
  // beta by under kTolerance of itself and mu by under kTolerance of beta.
  constexpr double kQuadraticRegion = 1e-6;
  constexpr double kTolerance = 1e-12;
  constexpr int kMaxIterations = 100;
  constexpr double kSmallestStep = 1e-20;
  double tau = 1;
  double m = 0;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const LogLikelihood at = log_likelihood(y_observed, y_censored, tau, m);
    // The Newton step solves H step = -gradient (H negative definite: det > 0).
    const double det = at.d_tau_tau * at.d_m_m - at.d_tau_m * at.d_tau_m;
    const double step_tau = -(at.d_m_m * at.d_tau - at.d_tau_m * at.d_m) / det;
    const double step_m = -(at.d_tau_tau * at.d_m - at.d_tau_m * at.d_tau) / det;
    const double predicted_gain = 0.5 * (at.d_tau * step_tau + at.d_m * step_m);

    double fraction = 1;
    if (predicted_gain > kQuadraticRegion) {
      for (;;) {
        const double trial_tau = tau + fraction * step_tau;
        if (trial_tau > 0 &&
            log_likelihood(y_observed, y_censored, trial_tau, m + fraction * step_m).value >=
                at.value) {
          break;
        }
        fraction *= 0.5;
        if (fraction < kSmallestStep) break;
      }
    }
    const double next_tau = tau + fraction * step_tau;
    const double next_m = m + fraction * step_m;
    if (!(fraction >= kSmallestStep && next_tau > 0 && std::isfinite(next_m))) break;

    const double beta_change = std::abs(1 / next_tau - 1 / tau);
    const double mu_change = std::abs(next_m / next_tau - m / tau);
    tau = next_tau;
    m = next_m;
    if (beta_change <= kTolerance / tau && mu_change <= kTolerance / tau) {
      fit.median = std::exp(mean + deviation * m / tau);
      fit.beta = deviation / tau;
      return fit;
    }
  }
  fit.error = "the maximum-likelihood fit did not converge";  // not seen: the problem is concave
  return fit;
}

double lognormal_cdf(double x, double median, double beta) {
  const bool valid = std::isfinite(median) && median > 0 && std::isfinite(beta) && beta > 0;
  if (!valid || std::isnan(x)) return kNaN;
  if (x <= 0) return 0;
  const double z = (std::log(x) - std::log(median)) / beta;
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

double fractile(std::vector<double> values, double p) {
  if (values.empty() || !(p >= 0 && p <= 1)) return kNaN;
  for (const double v : values) {
    if (std::isnan(v) || v == -kInfinity) return kNaN;
  }
  std::sort(values.begin(), values.end());  // +infinity last

  // Hyndman and Fan 7 as numpy computes it: index (n - 1) p, its fractional part the weight of
  // the value above.
  const double index = static_cast<double>(values.size() - 1) * p;
  const double below_index = std::floor(index);
  const auto below = static_cast<std::size_t>(below_index);
  const double weight = index - below_index;
  const double lower = values[below];
  // On an order statistic (also one just below +infinity: numpy's inf * 0 gives NaN there).
  if (weight == 0) return lower;
  const double upper = values[below + 1];  // weight > 0: index < n - 1
  if (std::isinf(upper)) return upper;     // between a value and +infinity, or two infinities
  // numpy's _lerp: from the nearer end, so the same bits as numpy.quantile.
  return weight < 0.5 ? lower + (upper - lower) * weight : upper - (upper - lower) * (1 - weight);
}

}  // namespace ntn::ida
