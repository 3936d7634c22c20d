// What every hysteretic hinge law shares (a `plastic` direction's force law, DESIGN §7): the
// history it keeps in State, the data the step reads, and the bound on its values.
//
// A law is one header in this folder with a struct of the same small interface, listed once in
// table.hpp:
//   kRule      its HysteresisRule value (HysteresisSpec::rule)
//   kName      its name in reports and plots
//   kEnum      the enum value's name, for the header the model compiler emits
//   kSummary   how `ntn-model info` counts its directions
//   kAccount   the energy books' account of its work (hysteretic, or breaking)
//   kSlip      a rigid-plastic direction may take it (the slip stage's laws, slip.hpp)
//   kBreaks    update() returns true the step it breaks (State::first_slip records when)
//   kEnvelope  it has a monotonic envelope to draw (envelope())
//   check(spec, k, c)           the kernel's rule for its values: a fault the compiler words at
//                               the key, or none
//   make(spec, k, data)         the step's data of a direction of elastic stiffness k
//   update(data, d, dp, dissipated, peak, x)
//                               its history brought to deformation d, once per step
// Every law's tangent is at most its elastic stiffness k, so the stable step uses k.
// The history of a direction is State::plastic (d_p: the force is k (d - d_p)),
// State::dissipated (the plastic work integral f dd_p), State::plastic_peak and the law's own
// values in State::law_state (LawState).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "ntn/model_spec.hpp"

namespace ntn {

// The bound on a hinge law's values (forces, moments, deformations, stiffnesses, mu, cohesion,
// acceptance limits): each must be below it, so that the law's products (mu N + c, k d, H d_p)
// stay finite. The model compiler refuses a value at or above it at its key.
inline constexpr double kLawValueLimit = 1e300;
constexpr bool law_value_ok(double v) {
  return v < kLawValueLimit;
}

// The most history values a law keeps of its own (State::law_state, by slot).
inline constexpr std::size_t kLawStateSize = 9;
using LawState = std::array<double, kLawStateSize>;

// Where the energy books put a law's work (hil/energy.hpp).
enum class LawAccount : std::uint8_t { kHysteretic, kBreaking };

// One sense's envelope as magnitudes: points B, C, D, E and the slope after each (B-C, C-D,
// D-E; 0 past E, unused).
struct Envelope {
  std::array<double, 4> d{};
  std::array<double, 4> f{};
  std::array<double, 4> slope{};
};

// What the step needs of one hysteretic direction (Model::hystereses).
struct HysteresisData {
  HysteresisRule rule = HysteresisRule::kBilinear;  // first: the step reads rule to inv_kH
  double k = 0;                                     // N/m or N m/rad, elastic stiffness
  double yield_pos = 0;                             // N or N m
  double yield_neg = 0;                             // N or N m, as a magnitude
  double H = 0;                                     // kinematic hardening modulus b k / (1 - b)
  double inv_kH = 0;                                // 1 / (k + H)
  std::array<double, 3> limits{};                   // io, ls, cp on the peak |d_p| (0, 0, 0: none)
  Envelope pos, neg;  // the backbone of each sense (kKinematic, kPeakOriented)
  int normal = -1;    // friction, fixed_if (slip.hpp): the direction whose force N sets the
                      // limit, or -1
  double mu = 0;
  double cohesion = 0;
  int fixed_if = 0;   // -1 (+1): held while N < 0 (N > 0), free otherwise (slip.hpp)
  int circle = -1;    // friction circle: the other direction of the pair, or -1 (slip.hpp)
  LawParameters p{};  // a law's derived values, its own names for them (imk.hpp)
};

// Performance level of a direction whose largest plastic deformation so far is `peak`: 0 below
// yield (no plastic deformation), 1 within IO (peak <= io), 2 within LS, 3 within CP, 4 beyond
// CP; without limits 0 or 1 (yielded).
constexpr int performance_level(const std::array<double, 3>& limits, double peak) {
  if (!(peak > 0)) return 0;
  int level = 1;
  if (limits[0] > 0) {
    for (const double lim : limits)
      level += peak > lim ? 1 : 0;
  }
  return level;
}

}  // namespace ntn
