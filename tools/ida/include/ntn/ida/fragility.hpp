// Fragility functions from incremental dynamic analysis: lognormal fits by maximum
// likelihood to the intensities at which each record reaches a limit state (its IM capacities),
// with the records that never reached it within the intensities run as right-censored data;
// and the empirical fractiles that summarise a set of IDA curves.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace ntn::ida {

// A lognormal distribution: P(capacity <= x) = Phi(ln(x / median) / beta).
struct LognormalFit {
  double median = 0;  // the intensity's unit
  double beta = 0;    // dispersion: the standard deviation of ln(capacity)
  int observed = 0;   // capacities given
  int censored = 0;   // records above their highest intensity run
  std::string error;  // not empty: no fit (fewer than two distinct observed capacities, or a
                      // value that is not finite and > 0)
  bool ok() const { return error.empty(); }
};

// The maximum-likelihood lognormal of capacities: `observed` (each > 0) are capacities; each of
// `censored_above` (> 0) says that a record's capacity exceeds it (the record did not reach the
// limit state at any intensity up to that one). Without censored data this is the closed form
// (median = exp(mean ln x), beta = the population standard deviation of ln x).
LognormalFit fit_lognormal(std::span<const double> observed,
                           std::span<const double> censored_above);

// Phi(ln(x / median) / beta); 0 for x <= 0, 1 for x = +infinity; NaN unless median and beta are
// finite and > 0, or for x NaN.
double lognormal_cdf(double x, double median, double beta);

// The p-fractile (0 <= p <= 1) of the values by linear interpolation between order statistics
// (Hyndman and Fan's definition 7, numpy's default). +infinity is a value (a collapsed record):
// a fractile that falls on it or between it and the value below is +infinity; one that falls
// exactly on the finite value below it is that value (numpy's arithmetic gives NaN in some of
// these cases: inf - inf, inf * 0).
// NaN for an empty set, p outside [0, 1], or a value that is NaN or -infinity.
double fractile(std::vector<double> values, double p);

}  // namespace ntn::ida
