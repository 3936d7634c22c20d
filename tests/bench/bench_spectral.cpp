// Spectral tools: the Welch PSD of 16 channels x 10^6 samples with FFTW, one
// plan per Welch object reused for every segment and channel; a direct DFT of a few of the same
// segments as a sanity check of the FFTW path (same values to rounding, and how much slower);
// the cross-spectral matrix of the 16 channels and its SVD per line (FDD); FFTW_ESTIMATE (the
// library's default) against FFTW_MEASURE. README.md "Spectra" has the figures.
//
// The executable exits non-zero when the FFTW and direct-DFT PSDs differ by more than 1e-10 of
// the largest value, or a PSD does not integrate to its channel's variance within 1 %.
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ntn/spectral/fdd.hpp"
#include "ntn/spectral/reference.hpp"
#include "ntn/spectral/welch.hpp"

namespace ntn::spectral::bench {
namespace {

constexpr std::size_t kChannels = 16;
constexpr std::size_t kSamples = 1'000'000;
constexpr double kFs = 1000;  // Hz

bool g_failed = false;

// 16 channels: unit white noise plus a tone of amplitude 2 at 10 + 7 c Hz (channel c).
const std::vector<std::vector<double>>& channels() {
  static const std::vector<std::vector<double>> data = [] {
    std::vector<std::vector<double>> d(kChannels, std::vector<double>(kSamples));
    std::mt19937_64 rng(2026);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (std::size_t c = 0; c < kChannels; ++c) {
      const double f = 10 + 7 * static_cast<double>(c);
      for (std::size_t i = 0; i < kSamples; ++i) {
        d[c][i] =
            noise(rng) + 2 * std::cos(2 * std::numbers::pi * f * static_cast<double>(i) / kFs);
      }
    }
    return d;
  }();
  return data;
}

WelchOptions options(std::size_t segment, Planner planner) {
  WelchOptions o;
  o.segment = segment;
  o.overlap = 0.5;
  o.window = Window::kHann;
  o.detrend = Detrend::kMean;
  o.planner = planner;
  return o;
}

double variance(const std::vector<double>& x) {
  double m = 0;
  for (double v : x)
    m += v;
  m /= static_cast<double>(x.size());
  double s = 0;
  for (double v : x)
    s += (v - m) * (v - m);
  return s / static_cast<double>(x.size());
}

// Channel 0's PSD with FFTW_ESTIMATE plans, made before any FFTW_MEASURE planning (FFTW would
// reuse that wisdom for later ESTIMATE requests).
std::vector<double> g_estimate_psd;

// Welch PSD of every channel with one Welch object (one plan). Counters: plan_ms (creating the
// Welch object: window and plan; FFTW_MEASURE plans from no wisdom), per_sample and per_segment
// (CPU time of the whole run divided by 16 x 10^6 samples, or by the segments transformed).
void bm_welch(benchmark::State& state, Planner planner) {
  const auto segment = static_cast<std::size_t>(state.range(0));
  const auto& data = channels();
  if (planner == Planner::kMeasure) fftw_forget_wisdom();
  const auto t0 = std::chrono::steady_clock::now();
  Welch welch(kFs, options(segment, planner));
  const double plan_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t segments = welch.grid(kSamples).segments;
  for (auto _ : state) {
    for (const auto& x : data) {
      const Spectrum p = welch.psd(x);
      benchmark::DoNotOptimize(p.values.data());
    }
  }
  // Sanity: each PSD integrates to its channel's variance (Parseval, within 1 %).
  for (std::size_t c = 0; c < kChannels; c += 5) {
    const Spectrum p = welch.psd(data[c]);
    double integral = 0;
    for (double v : p.values)
      integral += v;
    integral *= p.grid.df();
    const double var = variance(data[c]);
    if (std::abs(integral - var) > 0.01 * var) {
      state.SkipWithError("a PSD does not integrate to the variance within 1 %");
      g_failed = true;
    }
  }
  if (planner == Planner::kMeasure && segment == 4096 && !g_estimate_psd.empty()) {
    const Spectrum p = welch.psd(data[0]);
    double top = 0;
    double diff = 0;
    for (std::size_t k = 0; k < p.values.size(); ++k) {
      top = std::max(top, g_estimate_psd[k]);
      diff = std::max(diff, std::abs(p.values[k] - g_estimate_psd[k]));
    }
    state.counters["rel_diff_vs_estimate"] = diff / top;
  }
  if (planner == Planner::kMeasure) fftw_forget_wisdom();
  state.counters["plan_ms"] = plan_ms;
  state.counters["segments"] = static_cast<double>(kChannels * segments);
  state.counters["per_sample"] = benchmark::Counter(
      static_cast<double>(kChannels * kSamples),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["per_segment"] = benchmark::Counter(
      static_cast<double>(kChannels * segments),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The first `count` segments of channel 0 by a direct DFT (reference.hpp), and the largest
// difference from the FFTW path over the same segments (max_rel_diff, relative to the largest
// PSD value; the run fails above 1e-10).
void bm_naive(benchmark::State& state) {
  const auto segment = static_cast<std::size_t>(state.range(0));
  const auto count = static_cast<std::size_t>(state.range(1));
  const WelchOptions o = options(segment, Planner::kEstimate);
  const std::vector<double> x(
      channels()[0].begin(),
      channels()[0].begin() + static_cast<std::ptrdiff_t>((count - 1) * (segment / 2) + segment));
  Spectrum slow;
  for (auto _ : state) {
    slow = welch_psd_naive(x, kFs, o, count);
    benchmark::DoNotOptimize(slow.values.data());
  }
  const Spectrum fast = welch_psd(x, kFs, o);
  double top = 0;
  double diff = 0;
  for (std::size_t k = 0; k < fast.values.size(); ++k) {
    top = std::max(top, slow.values[k]);
    diff = std::max(diff, std::abs(fast.values[k] - slow.values[k]));
  }
  if (fast.grid.segments != count || slow.grid.segments != count || !(diff <= 1e-10 * top)) {
    state.SkipWithError("the FFTW and direct-DFT PSDs differ");
    g_failed = true;
  }
  state.counters["max_rel_diff"] = diff / top;
  state.counters["per_segment"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}

// The 16 x 16 cross-spectral matrix of all channels (FDD's input): 16 FFTs per segment and
// 136 products per line.
void bm_matrix(benchmark::State& state) {
  const auto segment = static_cast<std::size_t>(state.range(0));
  Welch welch(kFs, options(segment, Planner::kEstimate));
  for (auto _ : state) {
    const CrossSpectralMatrix g = welch.matrix(channels());
    benchmark::DoNotOptimize(g.values.data());
  }
  state.counters["lines"] = static_cast<double>(welch.grid(kSamples).lines());
}

// FDD: a JacobiSVD of the 16 x 16 matrix at every line.
void bm_fdd(benchmark::State& state) {
  const auto segment = static_cast<std::size_t>(state.range(0));
  Welch welch(kFs, options(segment, Planner::kEstimate));
  const CrossSpectralMatrix g = welch.matrix(channels());
  for (auto _ : state) {
    const Fdd d = fdd(g);
    benchmark::DoNotOptimize(d.singular_values.data());
  }
  state.counters["per_line"] = benchmark::Counter(
      static_cast<double>(g.grid.lines()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace
}  // namespace ntn::spectral::bench

int main(int argc, char** argv) {
  using namespace ntn::spectral;
  using namespace ntn::spectral::bench;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  g_estimate_psd = welch_psd(channels()[0], kFs, options(4096, Planner::kEstimate)).values;
  // ESTIMATE first: the FFTW_MEASURE runs come last and forget their wisdom after each.
  benchmark::RegisterBenchmark("welch_psd/16ch_x_1e6/estimate", bm_welch, Planner::kEstimate)
      ->Arg(1024)
      ->Arg(4096)
      ->Arg(16384)
      ->ArgName("segment")
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("naive_dft/channel0", bm_naive)
      ->Args({4096, 4})
      ->ArgNames({"segment", "segments"})
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("csd_matrix/16ch_x_1e6", bm_matrix)
      ->Arg(4096)
      ->ArgName("segment")
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("fdd_svd/16ch", bm_fdd)
      ->Arg(4096)
      ->ArgName("segment")
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("welch_psd/16ch_x_1e6/measure", bm_welch, Planner::kMeasure)
      ->Arg(1024)
      ->Arg(4096)
      ->Arg(16384)
      ->ArgName("segment")
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return g_failed ? 1 : 0;
}
