#include "ntn/spectral/peaks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "ntn/spectral/error.hpp"

namespace ntn::spectral {

namespace {

// [first, last] lines of the band, clipped to the spectrum.
std::pair<std::size_t, std::size_t> band_lines(const Spectrum& s, const PeakOptions& o) {
  if (s.values.size() < 3 || !(s.grid.df() > 0)) throw Error("find_peaks: an empty spectrum");
  if (!(o.f_min <= o.f_max))
    throw Error("find_peaks: the band's lower edge is above its upper edge");
  const double df = s.grid.df();
  const double last = static_cast<double>(s.values.size() - 1);
  const double lo = std::clamp(std::ceil(std::max(o.f_min, 0.0) / df), 0.0, last + 1);
  const double hi = std::clamp(std::floor(std::min(o.f_max, last * df) / df), 0.0, last);
  if (lo > hi) throw Error("find_peaks: no spectral line in the band");
  return {static_cast<std::size_t>(lo), static_cast<std::size_t>(hi)};
}

}  // namespace

namespace {

// Lines on the two sides of the maximum k with values in [level, v[k]]: the mean of the two
// counts (so that one noisy line on one side does not cut a fit short), at least 1.
std::size_t half_width(const std::vector<double>& v, std::size_t k, double level) {
  std::size_t left = 0;
  while (left < k && v[k - left - 1] >= level && v[k - left - 1] <= v[k])
    ++left;
  std::size_t right = 0;
  while (k + right + 1 < v.size() && v[k + right + 1] >= level && v[k + right + 1] <= v[k])
    ++right;
  return std::max<std::size_t>(1, (left + right) / 2);
}

// Least squares y = c0 + c1 x + c2 x^2 to y = log v on x = -h..h about k. With the x symmetric
// the odd moments vanish: c1 = T1/S2, c2 = (S0 T2 - S2 T0)/(S0 S4 - S2^2), c0 = (T0 - c2 S2)/S0.
// For h = 1, the parabola through the three values. False when a value is not positive or the
// fit does not curve down.
bool fit_log_parabola(const std::vector<double>& v, std::size_t k, std::size_t h, double& c0,
                      double& c1, double& c2) {
  if (k < h || k + h >= v.size()) return false;
  double s0 = 0, s2 = 0, s4 = 0, t0 = 0, t1 = 0, t2 = 0;
  for (std::size_t j = k - h; j <= k + h; ++j) {
    if (!(v[j] > 0)) return false;
    const double x = static_cast<double>(j) - static_cast<double>(k);
    const double y = std::log(v[j]);
    s0 += 1;
    s2 += x * x;
    s4 += x * x * x * x;
    t0 += y;
    t1 += x * y;
    t2 += x * x * y;
  }
  c1 = t1 / s2;
  c2 = (s0 * t2 - s2 * t0) / (s0 * s4 - s2 * s2);
  c0 = (t0 - c2 * s2) / s0;
  return c2 < 0;
}

}  // namespace

Peak interpolate_peak(const Spectrum& s, std::size_t k) {
  const std::vector<double>& v = s.values;
  if (k < 1 || k + 1 >= v.size())
    throw Error("interpolate_peak: line " + std::to_string(k) + " has no neighbour on both sides");
  Peak p;
  p.line = k;
  p.frequency = s.grid.frequency(k);
  p.value = v[k];
  const bool power = s.scale == Scale::kPower;
  // Frequency: the vertex of the fit over the half-power band.
  const std::size_t h = half_width(v, k, (power ? 0.5 : 1 / std::sqrt(2.0)) * v[k]);
  double c0 = 0, c1 = 0, c2 = 0;
  if (!fit_log_parabola(v, k, h, c0, c1, c2)) return p;
  const double offset = -c1 / (2 * c2);
  if (!(std::abs(offset) <= static_cast<double>(h))) return p;
  // Value: the fit over the lines within 1 dB (0.8 in power) at that offset. Over the whole
  // half-power band a log-parabola would read a Lorentzian's top 3 % low (and so widen its
  // half-power band by 3 %); within 1 dB it reads it within 0.3 %.
  const std::size_t h1 = half_width(v, k, (power ? 0.8 : std::sqrt(0.8)) * v[k]);
  if (h1 != h && !fit_log_parabola(v, k, h1, c0, c1, c2)) return p;
  p.frequency = (static_cast<double>(k) + offset) * s.grid.df();
  p.value = std::exp(c0 + offset * (c1 + c2 * offset));
  return p;
}

std::vector<Peak> find_peaks(const Spectrum& s, const PeakOptions& o) {
  const auto [lo, hi] = band_lines(s, o);
  const std::vector<double>& v = s.values;
  double band_max = 0;
  for (std::size_t k = lo; k <= hi; ++k)
    band_max = std::max(band_max, v[k]);

  std::vector<Peak> peaks;
  const std::size_t first = std::max<std::size_t>(lo, 1);
  const std::size_t last = std::min(hi, v.size() - 2);
  for (std::size_t k = first; k <= last && first <= last; ++k) {
    if (!(v[k - 1] < v[k] && v[k] >= v[k + 1])) continue;
    if (v[k] < o.relative_threshold * band_max) continue;
    // Bases: the lowest value on each side before a higher value or the band edge.
    double left = v[k];
    for (std::size_t j = k; j-- > lo && v[j] <= v[k];)
      left = std::min(left, v[j]);
    double right = v[k];
    for (std::size_t j = k + 1; j <= hi && v[j] <= v[k]; ++j)
      right = std::min(right, v[j]);
    const double base = std::max(left, right);
    const double prominence = base > 0 ? v[k] / base : std::numeric_limits<double>::infinity();
    if (prominence < o.min_prominence) continue;
    Peak p = interpolate_peak(s, k);
    p.prominence = prominence;
    peaks.push_back(p);
  }
  if (o.max_peaks != 0 && peaks.size() > o.max_peaks) {
    std::stable_sort(peaks.begin(), peaks.end(),
                     [](const Peak& x, const Peak& y) { return x.value > y.value; });
    peaks.resize(o.max_peaks);
    std::sort(peaks.begin(), peaks.end(),
              [](const Peak& x, const Peak& y) { return x.line < y.line; });
  }
  return peaks;
}

std::optional<HalfPower> half_power(const Spectrum& s, const Peak& peak) {
  const std::vector<double>& v = s.values;
  const std::size_t k = peak.line;
  if (k >= v.size() || !(peak.value > 0)) return std::nullopt;
  const double level = s.scale == Scale::kPower ? 0.5 * peak.value : peak.value / std::sqrt(2.0);
  const double df = s.grid.df();
  if (!(v[k] >= level)) return std::nullopt;

  std::optional<double> f_low;
  for (std::size_t j = k; j > 0; --j) {
    if (v[j - 1] > v[k]) break;  // a higher neighbour: no crossing of this peak's own
    if (v[j - 1] < level) {
      f_low = df * (static_cast<double>(j - 1) + (level - v[j - 1]) / (v[j] - v[j - 1]));
      break;
    }
  }
  std::optional<double> f_high;
  for (std::size_t j = k; j + 1 < v.size(); ++j) {
    if (v[j + 1] > v[k]) break;
    if (v[j + 1] < level) {
      f_high = df * (static_cast<double>(j) + (v[j] - level) / (v[j] - v[j + 1]));
      break;
    }
  }
  if (!f_low || !f_high || !(*f_high > *f_low) || !(peak.frequency > 0)) return std::nullopt;
  HalfPower h;
  h.f_low = *f_low;
  h.f_high = *f_high;
  h.damping = (h.f_high - h.f_low) / (2 * peak.frequency);
  h.resolution_ratio = s.grid.enbw_hz / (h.f_high - h.f_low);
  return h;
}

}  // namespace ntn::spectral
