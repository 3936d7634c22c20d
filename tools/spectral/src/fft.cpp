#include "ntn/spectral/fft.hpp"

#include <fftw3.h>

#include <limits>
#include <string>
#include <utility>

#include "ntn/spectral/error.hpp"

namespace ntn::spectral {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

RealFft::RealFft(std::size_t n, Planner planner) : n_(n) {
  if (n == 0) throw Error("an FFT needs at least one sample");
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("FFT length " + std::to_string(n) + " is too large for FFTW's int sizes");
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  in_ = static_cast<double*>(fftw_malloc(sizeof(double) * n));
  out_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * lines()));
  if (in_ == nullptr || out_ == nullptr) {
    fftw_free(in_);
    fftw_free(out_);
    throw Error("cannot allocate FFT buffers of " + std::to_string(n) + " samples");
  }
  // FFTW_MEASURE overwrites the arrays while planning; they hold nothing yet.
  const unsigned flags = planner == Planner::kMeasure ? FFTW_MEASURE : FFTW_ESTIMATE;
  plan_ =
      fftw_plan_dft_r2c_1d(static_cast<int>(n), in_, reinterpret_cast<fftw_complex*>(out_), flags);
  if (plan_ == nullptr) {
    fftw_free(in_);
    fftw_free(out_);
    throw Error("FFTW could not plan a transform of " + std::to_string(n) + " samples");
  }
}

void RealFft::release() noexcept {
  if (plan_ == nullptr && in_ == nullptr && out_ == nullptr) return;
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  if (plan_ != nullptr) fftw_destroy_plan(plan_);
  fftw_free(in_);
  fftw_free(out_);
  plan_ = nullptr;
  in_ = nullptr;
  out_ = nullptr;
}

RealFft::~RealFft() {
  release();
}

RealFft::RealFft(RealFft&& other) noexcept
    : n_(std::exchange(other.n_, 0)),
      in_(std::exchange(other.in_, nullptr)),
      out_(std::exchange(other.out_, nullptr)),
      plan_(std::exchange(other.plan_, nullptr)) {}

RealFft& RealFft::operator=(RealFft&& other) noexcept {
  if (this != &other) {
    release();
    n_ = std::exchange(other.n_, 0);
    in_ = std::exchange(other.in_, nullptr);
    out_ = std::exchange(other.out_, nullptr);
    plan_ = std::exchange(other.plan_, nullptr);
  }
  return *this;
}

void RealFft::execute() {
  fftw_execute(plan_);
}

}  // namespace ntn::spectral
