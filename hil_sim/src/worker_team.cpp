#include "ntn/hil/worker_team.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cstring>

namespace ntn::hil {
namespace {

inline void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Waits until `a` differs from `old`: spins, then gives the CPU away a few times (a team larger
// than the CPUs it has must let the awaited worker run), then sleeps on the atomic.
template <class T>
T wait_change(const std::atomic<T>& a, T old, int spin) {
  for (int i = 0; i < spin; ++i) {
    const T now = a.load(std::memory_order_acquire);
    if (now != old) return now;
    pause();
  }
  for (int i = 0; i < 64; ++i) {
    const T now = a.load(std::memory_order_acquire);
    if (now != old) return now;
    std::this_thread::yield();
  }
  for (;;) {
    a.wait(old, std::memory_order_acquire);
    const T now = a.load(std::memory_order_acquire);
    if (now != old) return now;
  }
}

}  // namespace

WorkerTeam::WorkerTeam(const WorkerTeamOptions& options)
    : size_(std::clamp(options.size, 1, ntn::kMaxTeam)), spin_(std::max(options.spin, 0)) {
  threads_.reserve(static_cast<std::size_t>(size_ - 1));
  const int cpus = static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
  if (size_ > cpus) {
    // Every phase ends when its last worker does: a worker waiting for a CPU stalls the step for
    // a scheduler slice, many times per step (measured: several times slower than one worker).
    warnings_.push_back(std::to_string(size_) + " workers on " + std::to_string(cpus) +
                        " CPUs: each phase of the step waits for a worker that has no CPU; "
                        "expect a much slower step than with --threads " +
                        std::to_string(cpus));
  }
  for (int k = 1; k < size_; ++k) {
    threads_.emplace_back([this, k] { work(k); });
    if (options.first_cpu < 0) continue;
    const int cpu = (options.first_cpu + k) % cpus;
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(cpu), &set);
    if (const int e = pthread_setaffinity_np(threads_.back().native_handle(), sizeof set, &set);
        e != 0) {
      warnings_.push_back("cannot pin worker " + std::to_string(k) + " to CPU " +
                          std::to_string(cpu) + " (" + std::strerror(e) + "): running unpinned");
    }
  }
}

WorkerTeam::~WorkerTeam() {
  stop_.store(true, std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& t : threads_)
    t.join();
}

void WorkerTeam::run(void* self, void (*job)(void*, int), void* arg) {
  auto& t = *static_cast<WorkerTeam*>(self);
  if (t.size_ == 1) {
    job(arg, 0);
    return;
  }
  t.job_ = job, t.arg_ = arg;
  t.done_.store(0, std::memory_order_relaxed);
  t.generation_.fetch_add(1, std::memory_order_release);  // publishes job_, arg_, done_ = 0
  t.generation_.notify_all();
  job(arg, 0);
  int done = t.done_.load(std::memory_order_acquire);
  while (done != t.size_ - 1)
    done = wait_change(t.done_, done, t.spin_);
}

void WorkerTeam::work(int k) {
  std::uint32_t seen = 0;
  for (;;) {
    seen = wait_change(generation_, seen, spin_);
    if (stop_.load(std::memory_order_relaxed)) return;
    job_(arg_, k);
    done_.fetch_add(1, std::memory_order_release);
    done_.notify_one();
  }
}

}  // namespace ntn::hil
