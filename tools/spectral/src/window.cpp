#include "ntn/spectral/window.hpp"

#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "ntn/spectral/error.hpp"

namespace ntn::spectral {

namespace {

// Cosine-sum coefficients a_j (window.hpp).
std::span<const double> coefficients(Window window) {
  static constexpr std::array<double, 1> kRect{1.0};
  static constexpr std::array<double, 2> kHann{0.5, 0.5};
  static constexpr std::array<double, 2> kHamming{0.54, 0.46};
  static constexpr std::array<double, 3> kBlackman{0.42, 0.5, 0.08};
  static constexpr std::array<double, 5> kFlatTop{0.21557895, 0.41663158, 0.277263158, 0.083578947,
                                                  0.006947368};
  switch (window) {
    case Window::kRectangular:
      return kRect;
    case Window::kHann:
      return kHann;
    case Window::kHamming:
      return kHamming;
    case Window::kBlackman:
      return kBlackman;
    case Window::kFlatTop:
      return kFlatTop;
  }
  return kRect;
}

}  // namespace

std::string_view to_string(Window window) {
  switch (window) {
    case Window::kRectangular:
      return "rectangular";
    case Window::kHann:
      return "hann";
    case Window::kHamming:
      return "hamming";
    case Window::kBlackman:
      return "blackman";
    case Window::kFlatTop:
      return "flattop";
  }
  return "?";
}

Window parse_window(std::string_view name) {
  if (name == "rectangular" || name == "boxcar") return Window::kRectangular;
  if (name == "hann") return Window::kHann;
  if (name == "hamming") return Window::kHamming;
  if (name == "blackman") return Window::kBlackman;
  if (name == "flattop" || name == "flat-top") return Window::kFlatTop;
  throw Error("unknown window '" + std::string(name) +
              "' (rectangular, hann, hamming, blackman, flattop)");
}

std::vector<double> make_window(Window window, std::size_t length) {
  if (length == 0) throw Error("a window needs at least one sample");
  const std::span<const double> a = coefficients(window);
  std::vector<double> w(length);
  const double l = static_cast<double>(length);
  for (std::size_t n = 0; n < length; ++n) {
    double v = a[0];
    double sign = -1;
    for (std::size_t j = 1; j < a.size(); ++j) {
      // (j n) mod L keeps the argument in [0, 2 pi): the same value for every n with equal phase.
      const auto m = static_cast<double>((j * n) % length);
      v += sign * a[j] * std::cos(2 * std::numbers::pi * m / l);
      sign = -sign;
    }
    w[n] = v;
  }
  return w;
}

double window_response(std::span<const double> w, double delta_bins) {
  std::complex<double> s = 0;
  double s0 = 0;
  const double l = static_cast<double>(w.size());
  for (std::size_t n = 0; n < w.size(); ++n) {
    s += w[n] * std::polar(1.0, -2 * std::numbers::pi * delta_bins * static_cast<double>(n) / l);
    s0 += w[n];
  }
  return s0 != 0 ? std::abs(s) / std::abs(s0) : 0.0;
}

WindowProperties window_properties(std::span<const double> w) {
  if (w.empty()) throw Error("window_properties: empty window");
  double s1 = 0;
  double s2 = 0;
  for (double v : w) {
    s1 += v;
    s2 += v * v;
  }
  const double l = static_cast<double>(w.size());
  WindowProperties p;
  p.coherent_gain = s1 / l;
  p.power_gain = s2 / l;
  p.enbw_bins = l * s2 / (s1 * s1);
  p.scalloping_loss = 1 - window_response(w, 0.5);
  return p;
}

}  // namespace ntn::spectral
