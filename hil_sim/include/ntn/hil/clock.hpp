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

// What a real-time run asks of the system. The defaults are what one needs: SCHED_FIFO (no normal
// thread preempts the loop), every page locked (no page fault in a frame), a timer slack of
// 1 ns (a normal thread's 50 us default would wake it up to 50 us late; a SCHED_FIFO thread has
// no slack, so it matters where FIFO is refused) and a CPU wake-up latency of 0 us (PM QoS,
// /dev/cpu_dma_latency, as cyclictest asks: an idle CPU in a deep sleep state takes tens of us
// to wake). Each can be turned off.
struct RealTimeOptions {
  bool fifo = true;                 // SCHED_FIFO at `priority`
  int priority = 80;                // 1..99
  bool lock_memory = true;          // mlockall(MCL_CURRENT | MCL_FUTURE)
  int cpu = -1;                     // pin to this CPU (sched_setaffinity); -1: leave
  std::int64_t timer_slack_ns = 1;  // PR_SET_TIMERSLACK; 0: the system's default; -1: leave
  int cpu_latency_us = 0;           // /dev/cpu_dma_latency while the process lives; -1: leave
};

// What was granted; threads made afterwards (the step's workers) inherit the scheduling policy
// and the timer slack.
struct RealTimeState {
  bool fifo = false;  // running under SCHED_FIFO at `priority`
  int priority = 0;
  bool memory_locked = false;
  int cpu = -1;                       // pinned to this CPU, or -1
  std::int64_t timer_slack_ns = -1;   // the thread's timer slack as read back, -1: unknown
  int cpu_latency_us = -1;            // the PM QoS request held (the file stays open), -1: none
  std::vector<std::string> warnings;  // one line for each request refused
  // "SCHED_FIFO 80, memory locked, timer slack 1 ns, CPU latency 0 us, CPU 2" ("normal
  // scheduling", "memory not locked" where refused or not asked for).
  std::string describe() const;
};

// Applies the options; each one that is not permitted here falls back with one warning line,
// never an error: a monitoring run should still run on a desktop.
RealTimeState apply_real_time(const RealTimeOptions& options);

}  // namespace ntn::hil
