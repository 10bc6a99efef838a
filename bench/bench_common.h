// TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
// What every benchmark in bench/ prints and measures the same way: the CPU, wall time, medians.
#ifndef TAPMC_BENCH_COMMON_H
#define TAPMC_BENCH_COMMON_H

#include <algorithm>
#include <chrono>
#include <fstream>
#include <string>
#include <time.h>
#include <vector>

namespace tapmc_bench {

inline double seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU time of the calling thread, s: on a shared machine a rate per CPU second does not count
// the time other processes held the core.
inline double thread_cpu_seconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// The CPU model from /proc/cpuinfo, printed with every result.
inline std::string cpu_model()
{
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace tapmc_bench

#endif
