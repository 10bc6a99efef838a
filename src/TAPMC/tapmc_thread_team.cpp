// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// The persistent thread team of the windowed trial executor (tapmc_thread_team.h).
#include "tapmc_thread_team.h"

#include "tapmc_defaults.h"

#if defined(__linux__)
#include <sched.h>
#endif

namespace tapmc {

int available_cores()
{
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int count = CPU_COUNT(&set);
    if (count > 0) return count;
  }
#endif
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware > 0 ? static_cast<int>(hardware) : 1;
}

void spin_pause(int &spins, int limit)
{
  if (++spins < limit) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
    return;
  }
  spins = 0;
  std::this_thread::yield();
}

ThreadTeam::ThreadTeam(int size) : size_(size < 1 ? 1 : size)
{
  spins_before_yield_ = size_ > available_cores() ? defaults::kSpinsBeforeYieldOversubscribed
                                                  : defaults::kSpinsBeforeYield;
  threads_.reserve(static_cast<std::size_t>(size_ - 1));
  for (int member = 1; member < size_; ++member)
    threads_.emplace_back([this, member] { member_loop(member); });
}

ThreadTeam::~ThreadTeam()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_up_.notify_all();
  for (std::thread &t : threads_) t.join();
}

void ThreadTeam::wake()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    awake_.store(true, std::memory_order_release);
  }
  wake_up_.notify_all();
}

void ThreadTeam::sleep()
{
  std::lock_guard<std::mutex> lock(mutex_);
  awake_.store(false, std::memory_order_release);
}

void ThreadTeam::run_erased(JobFunction function, void *context)
{
  if (size_ == 1) {
    function(context, 0);
    return;
  }
  if (!awake_.load(std::memory_order_acquire)) wake();
  function_ = function;
  context_ = context;
  finished_target_ += static_cast<std::uint64_t>(size_ - 1);
  generation_.fetch_add(1, std::memory_order_release);
  function(context, 0);
  int spins = 0;
  while (finished_.load(std::memory_order_acquire) < finished_target_) spin_pause(spins, spins_before_yield_);
}

void ThreadTeam::member_loop(int member)
{
  std::uint64_t seen = 0;
  for (;;) {
    int spins = 0;
    while (generation_.load(std::memory_order_acquire) == seen) {
      if (awake_.load(std::memory_order_acquire)) {
        spin_pause(spins, spins_before_yield_);
        continue;
      }
      std::unique_lock<std::mutex> lock(mutex_);
      wake_up_.wait(lock, [&] {
        return awake_.load(std::memory_order_acquire) ||
               generation_.load(std::memory_order_acquire) != seen;
      });
    }
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_acquire)) return;
    function_(context_, member);
    finished_.fetch_add(1, std::memory_order_release);
  }
}

}  // namespace tapmc
