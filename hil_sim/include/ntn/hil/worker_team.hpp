// The workers of the multi-core step (kernel/include/ntn/team.hpp): threads made once, before the
// run, each pinned to a CPU where the system permits it, that wait for a job, run their part of
// it and say they are done. WorkerTeam::team() is the kernel's ntn::Team. The caller's thread is
// worker 0; workers 1 .. size - 1 are threads.
//
// Hand-over without locks and without allocation: a job is published by bumping an atomic
// generation; a worker spins on it for a while (a step's phases follow each other within
// microseconds), then yields the CPU a few times, then sleeps in std::atomic::wait (a futex)
// until the next job; the caller waits on the count of finished workers the same way. Release and
// acquire order the job's data.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "ntn/team.hpp"

namespace ntn::hil {

struct WorkerTeamOptions {
  int size = 1;        // workers, the caller's thread included (1..ntn::kMaxTeam)
  int first_cpu = -1;  // >= 0: pin worker k > 0 to CPU (first_cpu + k) mod CPUs; -1: unpinned
  // Pause instructions a waiting thread spins (tens of ns each) before it yields, then sleeps.
  int spin = 1 << 10;
};

class WorkerTeam {
 public:
  explicit WorkerTeam(const WorkerTeamOptions& options);
  ~WorkerTeam();
  WorkerTeam(const WorkerTeam&) = delete;
  WorkerTeam& operator=(const WorkerTeam&) = delete;

  int size() const { return size_; }
  ntn::Team team() { return ntn::Team{size_, &WorkerTeam::run, this}; }
  // What did not go as asked (a CPU the system would not pin a worker to): for the report.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  static void run(void* self, void (*job)(void*, int), void* arg);
  void work(int k);

  int size_ = 1;
  int spin_ = 0;
  void (*job_)(void*, int) = nullptr;
  void* arg_ = nullptr;
  alignas(64) std::atomic<std::uint32_t> generation_{0};
  alignas(64) std::atomic<int> done_{0};
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
  std::vector<std::string> warnings_;
};

}  // namespace ntn::hil
