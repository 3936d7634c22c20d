// Frequency of a sampled oscillation from its zero crossings, each located by linear
// interpolation between the two samples around it.
#pragma once

namespace ntn_test {

class ZeroCrossings {
 public:
  explicit ZeroCrossings(double first_sample) : prev_(first_sample) {}

  // The next sample, taken at time t (the previous one at t - dt).
  void add(double u, double t, double dt) {
    if (prev_ != 0 && (prev_ < 0) != (u < 0)) {
      const double tc = t - dt * u / (u - prev_);
      if (count_ == 0) first_ = tc;
      last_ = tc;
      ++count_;
    }
    prev_ = u;
  }

  int count() const { return count_; }
  // rad/s: successive crossings are half a period apart.
  double omega() const {
    constexpr double kPi = 3.14159265358979323846;
    return kPi * (count_ - 1) / (last_ - first_);
  }

 private:
  double prev_ = 0, first_ = 0, last_ = 0;
  int count_ = 0;
};

}  // namespace ntn_test
