// A real-to-complex FFT of one size with its FFTW plan and its buffers, made once and reused for
// every segment and channel.
//
// Planner: FFTW_ESTIMATE by default. It picks the plan from the size alone, so the same input
// gives the same bits on every run (FFTW_MEASURE times candidate algorithms and may pick another
// plan, hence other rounding, on another run or under another load), and planning costs
// microseconds instead of up to seconds. tests/bench/README.md ("Spectra") measures what
// FFTW_MEASURE would gain on the Welch benchmark.
//
// Threads: FFTW's planner (plan creation and destruction) is not thread-safe. RealFft takes
// fftw_planner_mutex() around both, so RealFft objects may be created and destroyed from several
// threads; other code that calls the FFTW planner directly in the same process must take the same
// mutex. Executing distinct RealFft objects concurrently is safe; one object is not.
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <span>

struct fftw_plan_s;  // FFTW's plan type (fftw_plan is a pointer to it); fftw3.h stays private

namespace ntn::spectral {

enum class Planner : std::uint8_t { kEstimate, kMeasure };

std::mutex& fftw_planner_mutex();

class RealFft {
 public:
  // Plans an out-of-place r2c transform of n >= 1 real samples; throws Error if FFTW fails.
  explicit RealFft(std::size_t n, Planner planner = Planner::kEstimate);
  ~RealFft();
  RealFft(RealFft&& other) noexcept;
  RealFft& operator=(RealFft&& other) noexcept;
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  std::size_t size() const { return n_; }
  std::size_t lines() const { return n_ / 2 + 1; }  // one-sided lines 0..n/2

  // Fill input(), then execute(); output() holds X_k = sum_n x_n exp(-2 pi i k n / N),
  // k = 0..N/2 (FFTW's unnormalized forward transform). execute() may overwrite input().
  std::span<double> input() { return {in_, n_}; }
  void execute();
  std::span<const std::complex<double>> output() const { return {out_, lines()}; }

 private:
  void release() noexcept;
  std::size_t n_ = 0;
  double* in_ = nullptr;                 // fftw_malloc'd (SIMD-aligned)
  std::complex<double>* out_ = nullptr;  // fftw_malloc'd; layout-compatible with fftw_complex
  fftw_plan_s* plan_ = nullptr;
};

}  // namespace ntn::spectral
