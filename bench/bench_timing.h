#pragma once
// The benchmarks' clocks, written once: wall time since a start, and this thread's CPU time.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

namespace pierce::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The middle of the values (the upper one of the two middles for an even count).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// CPU time of this thread: on a shared, loaded machine far steadier than wall time.
inline double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace pierce::bench
