#include "ntn/hil/clock.hpp"

#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <cerrno>
#include <cstring>

namespace ntn::hil {

std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::int64_t RealClock::wait_until(std::int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline_ns / 1'000'000'000);
  ts.tv_nsec = static_cast<long>(deadline_ns % 1'000'000'000);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
  return monotonic_ns();
}

std::vector<std::string> apply_real_time(const RealTimeOptions& options) {
  std::vector<std::string> warnings;
  if (options.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    warnings.push_back(std::string("mlockall not permitted (") + std::strerror(errno) +
                       "): pages may fault during the run");
  }
  if (options.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(options.cpu), &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) {
      warnings.push_back("cannot pin to CPU " + std::to_string(options.cpu) + " (" +
                         std::strerror(errno) + "): running unpinned");
    }
  }
  if (options.fifo) {
    sched_param p{};
    p.sched_priority = options.priority;
    if (sched_setscheduler(0, SCHED_FIFO, &p) != 0) {
      warnings.push_back(std::string("SCHED_FIFO not permitted (") + std::strerror(errno) +
                         "): running at normal priority");
    }
  }
  return warnings;
}

}  // namespace ntn::hil
