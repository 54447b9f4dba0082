#pragma once
// The benchmarks' clocks, written once: wall time since a start, and this thread's CPU time.
#include <chrono>
#include <ctime>

namespace pierce::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU time of this thread: on a shared, loaded machine far steadier than wall time.
inline double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace pierce::bench
