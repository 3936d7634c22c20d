// Data windows for spectral estimation, in their periodic (DFT-even) form, and the figures that
// scale a windowed spectrum: coherent gain, equivalent noise bandwidth, scalloping loss.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace ntn::spectral {

// w[n] = sum_j (-1)^j a_j cos(2 pi j n / L), n = 0..L-1 (Harris 1978, periodic form):
//   rectangular  a = {1}
//   Hann         a = {0.5, 0.5}
//   Hamming      a = {0.54, 0.46}
//   Blackman     a = {0.42, 0.5, 0.08}
//   flat-top     a = {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368}
//                (the five-term flat-top of D'Antona & Ferrero 2006, as in MATLAB flattopwin)
enum class Window : std::uint8_t { kRectangular, kHann, kHamming, kBlackman, kFlatTop };

std::string_view to_string(Window window);
// "rectangular" (or "boxcar"), "hann", "hamming", "blackman", "flattop" (or "flat-top");
// throws Error naming the accepted names otherwise.
Window parse_window(std::string_view name);

// The periodic window of `length` samples (length >= 1).
std::vector<double> make_window(Window window, std::size_t length);

struct WindowProperties {
  double coherent_gain = 0;    // sum(w) / L: a bin-centred tone of amplitude a reads a * this
  double power_gain = 0;       // sum(w^2) / L
  double enbw_bins = 0;        // equivalent noise bandwidth L sum(w^2) / sum(w)^2, in bins
  double scalloping_loss = 0;  // 1 - |W(1/2 bin)| / W(0): worst amplitude loss between bins
};

WindowProperties window_properties(std::span<const double> w);

// |W(delta)| / W(0), W the DTFT of w, delta in bins of length L: the amplitude a tone `delta`
// bins from a line reads on that line, relative to a tone on it.
double window_response(std::span<const double> w, double delta_bins);

}  // namespace ntn::spectral
