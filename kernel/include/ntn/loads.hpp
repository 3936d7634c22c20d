// External loads P_n (DESIGN §5): nodal loads x time functions, gravity, base excitation, inputs.
#pragma once

#include <span>

#include "ntn/model_spec.hpp"

namespace ntn {

// Piecewise-linear factor at time t; the end values hold outside the points.
inline double time_function_value(std::span<const TimePoint> points, const TimeFunctionSpec& tf,
                                  double t) {
  if (tf.count <= 0) return 1.0;
  const TimePoint* p = points.data() + tf.first;
  if (t <= p[0].t) return p[0].value;
  if (t >= p[tf.count - 1].t) return p[tf.count - 1].value;
  int lo = 0, hi = tf.count - 1;  // invariant: p[lo].t <= t < p[hi].t
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    if (p[mid].t <= t) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double s = (t - p[lo].t) / (p[hi].t - p[lo].t);
  return p[lo].value + s * (p[hi].value - p[lo].value);
}

inline double load_factor(std::span<const TimePoint> points,
                          std::span<const TimeFunctionSpec> functions, int function, double t) {
  if (function == kConstant) return 1.0;
  return time_function_value(points, functions[static_cast<std::size_t>(function)], t);
}

}  // namespace ntn
