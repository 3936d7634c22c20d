#include "ntn/hil/clock.hpp"

#include <fcntl.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <time.h>
#include <unistd.h>

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

RealTimeState apply_real_time(const RealTimeOptions& options) {
  RealTimeState st;
  if (options.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      st.memory_locked = true;
    } else {
      st.warnings.push_back(std::string("mlockall not permitted (") + std::strerror(errno) +
                            "): pages may fault during the run (--no-mlock: not asked for)");
    }
  }
  if (options.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(options.cpu), &set);
    if (sched_setaffinity(0, sizeof set, &set) == 0) {
      st.cpu = options.cpu;
    } else {
      st.warnings.push_back("cannot pin to CPU " + std::to_string(options.cpu) + " (" +
                            std::strerror(errno) + "): running unpinned");
    }
  }
  if (options.timer_slack_ns >= 0) {
    if (prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(options.timer_slack_ns), 0, 0, 0) !=
        0) {
      st.warnings.push_back("timer slack " + std::to_string(options.timer_slack_ns) +
                            " ns not set (" + std::strerror(errno) + ")");
    }
  }
  if (options.cpu_latency_us >= 0) {
    // Held while the file is open: it is left open until the process ends.
    const int fd = ::open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
    const std::int32_t us = options.cpu_latency_us;
    if (fd >= 0 && ::write(fd, &us, sizeof us) == static_cast<ssize_t>(sizeof us)) {
      st.cpu_latency_us = options.cpu_latency_us;
    } else {
      st.warnings.push_back("CPU latency " + std::to_string(options.cpu_latency_us) +
                            " us not set (/dev/cpu_dma_latency: " + std::strerror(errno) +
                            "): an idle CPU may wake up later (--cpu-latency -1: not asked for)");
      if (fd >= 0) ::close(fd);
    }
  }
  if (options.fifo) {
    sched_param p{};
    p.sched_priority = options.priority;
    if (sched_setscheduler(0, SCHED_FIFO, &p) == 0) {
      st.fifo = true;
      st.priority = options.priority;
    } else {
      st.warnings.push_back(std::string("SCHED_FIFO not permitted (") + std::strerror(errno) +
                            "): running at normal priority, woken up later (--no-fifo: not "
                            "asked for)");
    }
  }
  // Read back last: a SCHED_FIFO thread has no slack (0 on recent kernels).
  const int slack = prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
  st.timer_slack_ns = slack >= 0 ? slack : -1;
  return st;
}

std::string RealTimeState::describe() const {
  std::string s =
      fifo ? "SCHED_FIFO " + std::to_string(priority) : std::string("normal scheduling");
  s += memory_locked ? ", memory locked" : ", memory not locked";
  if (timer_slack_ns >= 0) s += ", timer slack " + std::to_string(timer_slack_ns) + " ns";
  if (cpu_latency_us >= 0) s += ", CPU latency " + std::to_string(cpu_latency_us) + " us";
  if (cpu >= 0) s += ", CPU " + std::to_string(cpu);
  return s;
}

}  // namespace ntn::hil
