// Clocks for the frame loop (DESIGN §8): real time on absolute deadlines, or virtual time that
// runs the same loop as fast as possible. Both give the loop the same frame sequence, so the
// same accepted inputs give the same outputs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ntn::hil {

// CLOCK_MONOTONIC now, in ns.
std::int64_t monotonic_ns();

class RealClock {
 public:
  // Sleeps until the absolute deadline (clock_nanosleep, TIMER_ABSTIME, CLOCK_MONOTONIC) and
  // returns the time of waking.
  std::int64_t wait_until(std::int64_t deadline_ns);
  std::int64_t now() const { return monotonic_ns(); }
  static constexpr bool kVirtual = false;
};

// Virtual time: waiting returns at once and "now" is whatever the caller last waited for, so
// latency is 0 and the loop runs as fast as the computation allows. Compute time is still
// measured on the monotonic clock.
class VirtualClock {
 public:
  std::int64_t wait_until(std::int64_t deadline_ns) {
    now_ = deadline_ns;
    return deadline_ns;
  }
  std::int64_t now() const { return now_; }
  static constexpr bool kVirtual = true;

 private:
  std::int64_t now_ = 0;
};

struct RealTimeOptions {
  bool fifo = false;         // SCHED_FIFO at `priority`
  int priority = 80;         // 1..99
  bool lock_memory = false;  // mlockall(MCL_CURRENT | MCL_FUTURE)
  int cpu = -1;              // pin to this CPU (sched_setaffinity); -1: leave
};

// Applies the options; each one that is not permitted here falls back with one warning line
// (returned), never an error: a monitoring run should still run on a desktop.
std::vector<std::string> apply_real_time(const RealTimeOptions& options);

}  // namespace ntn::hil
