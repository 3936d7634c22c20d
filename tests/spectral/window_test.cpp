// Windows: coherent gain, ENBW and scalloping loss against closed forms and Harris (1978), the
// window response, names.
#include <gtest/gtest.h>

#include <cmath>

#include "ntn/spectral/error.hpp"
#include "ntn/spectral/window.hpp"

namespace ntn::spectral {
namespace window_test {

struct Case {
  Window window;
  std::vector<double> a;     // cosine-sum coefficients (window.hpp)
  double harris_enbw;        // Harris 1978, Table 1 (bins), 0 when not listed
  double harris_scallop_db;  // Harris 1978, Table 1 (dB)
};

const std::vector<Case>& cases() {
  static const std::vector<Case> c{
      {Window::kRectangular, {1.0}, 1.00, 3.92},
      {Window::kHann, {0.5, 0.5}, 1.50, 1.42},
      {Window::kHamming, {0.54, 0.46}, 1.36, 1.78},
      {Window::kBlackman, {0.42, 0.5, 0.08}, 1.73, 1.10},
      {Window::kFlatTop, {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368}, 0, 0}};
  return c;
}

// For a periodic cosine sum of length L > 2 (terms - 1), sum cos(2 pi j n / L) over n is 0 for
// 0 < j < L and the cosines are orthogonal, so exactly:
//   coherent gain = a0,  power gain = a0^2 + (1/2) sum_{j>=1} a_j^2,  ENBW = power gain / a0^2.
// Tolerance 1e-12: rounding of L = 4096 cosines summed.
TEST(Window, GainsEqualTheCosineSumClosedForm) {
  for (const Case& c : cases()) {
    const auto w = make_window(c.window, 4096);
    const WindowProperties p = window_properties(w);
    double pg = c.a[0] * c.a[0];
    for (std::size_t j = 1; j < c.a.size(); ++j)
      pg += 0.5 * c.a[j] * c.a[j];
    EXPECT_NEAR(p.coherent_gain, c.a[0], 1e-12) << to_string(c.window);
    EXPECT_NEAR(p.power_gain, pg, 1e-12) << to_string(c.window);
    EXPECT_NEAR(p.enbw_bins, pg / (c.a[0] * c.a[0]), 1e-11) << to_string(c.window);
  }
}

// Harris's table rounds ENBW to 0.01 bin; his values are for long windows, so L = 4096.
// Tolerance: half the last digit plus 1e-3 for the finite length.
// Scalloping loss against its closed form for long windows: the transform of a cosine sum at
// half a line is a0 sinc(1/2) + sum_j (a_j / 2) (sinc(1/2 - j) + sinc(1/2 + j)), over a0, with
// sinc(x) = sin(pi x) / (pi x). This gives Harris's 3.92, 1.42 and 1.10 dB for rectangular, Hann
// and Blackman, and 1.75 dB for Hamming, where Harris's table prints 1.78. Tolerance 1e-4
// (finite L = 4096: the sinc form is the limit of the Dirichlet kernel, off by O(1/L^2)).
TEST(Window, EnbwMatchesHarris1978AndScallopingItsClosedForm) {
  const double pi = std::acos(-1.0);
  const auto sinc = [pi](double x) { return std::sin(pi * x) / (pi * x); };
  for (const Case& c : cases()) {
    const WindowProperties p = window_properties(make_window(c.window, 4096));
    if (c.harris_enbw != 0) {
      EXPECT_NEAR(p.enbw_bins, c.harris_enbw, 0.006) << to_string(c.window);
    }
    double r = c.a[0] * sinc(0.5);
    for (std::size_t j = 1; j < c.a.size(); ++j) {
      const double dj = static_cast<double>(j);
      r += 0.5 * c.a[j] * (sinc(0.5 - dj) + sinc(0.5 + dj));
    }
    r /= c.a[0];
    EXPECT_NEAR(1 - p.scalloping_loss, r, 1e-4) << to_string(c.window);
    if (c.harris_scallop_db != 0 && c.window != Window::kHamming) {
      EXPECT_NEAR(-20 * std::log10(1 - p.scalloping_loss), c.harris_scallop_db, 0.006)
          << to_string(c.window);
    }
  }
}

// The flat-top window is made for amplitudes: its worst-case scalloping loss is under 0.01 dB
// (D'Antona & Ferrero design the five terms for a flat main lobe), against 1.42 dB for Hann.
TEST(Window, FlatTopIsFlat) {
  const WindowProperties p = window_properties(make_window(Window::kFlatTop, 4096));
  EXPECT_LT(-20 * std::log10(1 - p.scalloping_loss), 0.01);
}

// The response is 1 on the line and, for the rectangular window, 0 on every other line (the DFT
// of a constant); between lines it falls as |sin(pi d) / (L sin(pi d / L))|. Tolerance 1e-12.
TEST(Window, ResponseOfTheRectangularWindowIsTheDirichletKernel) {
  const std::size_t l = 256;
  const auto w = make_window(Window::kRectangular, l);
  EXPECT_NEAR(window_response(w, 0), 1.0, 1e-15);
  EXPECT_NEAR(window_response(w, 3), 0.0, 1e-12);
  for (double d : {0.1, 0.25, 0.5, 1.7}) {
    const double pi = std::acos(-1.0);
    const double dirichlet = std::abs(
        std::sin(pi * d) / (static_cast<double>(l) * std::sin(pi * d / static_cast<double>(l))));
    EXPECT_NEAR(window_response(w, d), dirichlet, 1e-12) << d;
  }
}

TEST(Window, Names) {
  for (const Case& c : cases())
    EXPECT_EQ(parse_window(to_string(c.window)), c.window);
  EXPECT_EQ(parse_window("flat-top"), Window::kFlatTop);
  EXPECT_EQ(parse_window("boxcar"), Window::kRectangular);
  try {
    (void)parse_window("hanning");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown window 'hanning'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("blackman"), std::string::npos);
  }
  EXPECT_THROW((void)make_window(Window::kHann, 0), Error);
}

}  // namespace window_test
}  // namespace ntn::spectral
