// Intensity measures of a sampled ground-motion record: the peak ground acceleration
// and the pseudo-spectral acceleration of a damped linear oscillator, computed exactly for the
// record as the kernel sees it (linear between samples: the piecewise-exact recurrence of Nigam
// and Jennings, 1969).
#pragma once

#include <span>

namespace ntn::ida {

// max |a_k| over the samples (the samples' unit); 0 for an empty record, NaN if a sample is NaN.
double peak_ground_acceleration(std::span<const double> ag);

// Pseudo-spectral acceleration Sa = omega^2 max_k |u(k dt)| of the oscillator
// u'' + 2 zeta omega u' + omega^2 u = -ag(t), omega = 2 pi / period, at rest at t = 0, with ag
// linear between the samples ag[k] at t = k dt, over the record (t <= (n - 1) dt); the samples'
// unit. Exact for that input up to rounding: the step's transition matrix is evaluated once.
// The peak is taken at the samples' instants only: one between two samples is missed by about
// (omega dt)^2 / 8 of it at most (u ~ cos(omega t) near a peak). 0 for fewer than two samples.
// Requires finite period > 0, 0 <= zeta < 1, finite dt > 0 and finite samples (otherwise NaN).
double pseudo_spectral_acceleration(std::span<const double> ag, double dt, double period,
                                    double zeta);

}  // namespace ntn::ida
