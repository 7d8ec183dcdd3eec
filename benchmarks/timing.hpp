#pragma once
// Timing shared by the benchmarks: CPU time of the calling thread (it excludes the time the thread
// waits for a core on a shared machine) and wall time of one piece of work.
#include <chrono>
#include <ctime>

namespace krug::bench {

// CPU time of the calling thread (ns).
inline double thread_cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
}

struct Timing {
  double cpu_ns = 0.0;
  double wall_ns = 0.0;
  Timing& operator+=(const Timing& o) {
    cpu_ns += o.cpu_ns;
    wall_ns += o.wall_ns;
    return *this;
  }
};

// CPU and wall time of `run()`.
template <class Run>
Timing time_it(Run&& run) {
  const double cpu0 = thread_cpu_ns();
  const auto wall0 = std::chrono::steady_clock::now();
  run();
  const auto wall1 = std::chrono::steady_clock::now();
  const double cpu1 = thread_cpu_ns();
  return {cpu1 - cpu0, std::chrono::duration<double, std::nano>(wall1 - wall0).count()};
}

}  // namespace krug::bench
