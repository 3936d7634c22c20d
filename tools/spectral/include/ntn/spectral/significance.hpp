// Is a spectral peak more than noise? A line of a Welch-averaged PSD of noise is its smooth
// spectrum S times chi^2_nu / nu, nu the equivalent degrees of freedom of the average (Percival
// and Walden 1993, "Spectral Analysis for Physical Applications", eq. 292b: nu = 2 K^2 / (K + 2
// sum_j (K - j) rho_j^2), rho_j the window's overlap correlation at a shift of j steps). Against
// the local floor (the median of the lines around the peak, away from the peak itself), the
// largest of M lines of noise exceeds t = q(p^(1/M)) / q(0.5) with probability 1 - p, q the
// chi^2_nu / nu quantile: a peak below that threshold may be noise at the false-alarm
// probability asked for.
#pragma once

#include <cstddef>

#include "ntn/spectral/spectrum.hpp"

namespace ntn::spectral {

// nu of a line of the grid's averaged spectrum (2 for one segment).
double welch_dof(const Grid& grid);

// The median of the spectrum's lines with frequencies in [f_k / 1.5, 1.5 f_k] farther than
// `exclude` lines from line k (the peak and its own skirts); 0 when no line qualifies.
double local_floor(const Spectrum& spectrum, std::size_t k, std::size_t exclude);

// The ratio to the local floor that the largest of `lines` independent lines of noise with `dof`
// degrees of freedom exceeds with probability `false_alarm` (in (0, 1)).
double noise_threshold(double dof, double lines, double false_alarm);

}  // namespace ntn::spectral
