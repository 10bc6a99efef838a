// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// A persistent team of threads for the windowed trial executor of the trial-move engine
// (tapmc_sphere_mover.cpp): created once, it runs one job on every member at a time, the caller
// being member 0. Between jobs of one block of trials the members spin (a job lasts
// microseconds: waking a sleeping thread would cost more), yielding the core after a while so
// that more threads than cores still make progress; between blocks they sleep.
#ifndef TAPMC_THREAD_TEAM_H
#define TAPMC_THREAD_TEAM_H

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace tapmc {

// Cores this process may run on (its CPU affinity; the hardware's count where that is unknown).
int available_cores();

// One step of a busy wait: a pause instruction, and after `limit` of them a yield of the core.
void spin_pause(int &spins, int limit);

class ThreadTeam {
 public:
  explicit ThreadTeam(int size);  // size >= 1 members, size - 1 of them new threads
  ~ThreadTeam();
  ThreadTeam(const ThreadTeam &) = delete;
  ThreadTeam &operator=(const ThreadTeam &) = delete;

  int size() const { return size_; }
  // Pauses of a busy wait before a yield: defaults::kSpinsBeforeYield, or
  // kSpinsBeforeYieldOversubscribed when the team has more members than the process has cores.
  int spins_before_yield() const { return spins_before_yield_; }

  // Members spin for the next job while awake, and sleep while not.
  void wake();
  void sleep();

  // Runs job(member) on every member (this thread is member 0) and returns when all have
  // returned; everything the members wrote is then visible here. Jobs must not throw.
  template <class Job>
  void run(Job &job)
  {
    run_erased([](void *context, int member) { (*static_cast<Job *>(context))(member); }, &job);
  }

 private:
  using JobFunction = void (*)(void *, int);
  void run_erased(JobFunction function, void *context);
  void member_loop(int member);

  int size_;
  int spins_before_yield_;
  std::vector<std::thread> threads_;
  JobFunction function_ = nullptr;  // written before generation_ is released
  void *context_ = nullptr;
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<std::uint64_t> finished_{0};
  std::uint64_t finished_target_ = 0;  // member 0 only
  std::atomic<bool> awake_{false}, stop_{false};
  std::mutex mutex_;
  std::condition_variable wake_up_;
};

}  // namespace tapmc

#endif
