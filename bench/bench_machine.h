#pragma once
// What machine a bench ran on, printed above its tables so recorded numbers carry their context.
#include <cstdio>
#include <fstream>
#include <string>

#include "pierce/simd/simd_level.h"

namespace pierce::bench {

// The CPU's model name and the SIMD level the kernels run (guests of one model differ in it).
inline std::string cpu_model() {
  const std::string simd = " (SIMD " + std::string(simd_level_name(simd_level())) + ")";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1)) + simd;
    }
  return "unknown" + simd;
}

inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  if (in >> a >> b >> c) return a + " " + b + " " + c;
  return "unknown";
}

// The share of the machine's CPU time that the hypervisor gave to other guests (steal) since
// construction. On a shared VM this is what the load average does not show: a run at 33 % steal
// reads every row slower, and its ratios noisier, on an otherwise idle guest.
class StealMeter {
 public:
  StealMeter() : start_(read()) {}
  // Percent, or "unknown" where /proc/stat cannot be read.
  std::string percent() const {
    const Times now = read();
    if (now.total <= start_.total) return "unknown";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f %%", 100.0 * double(now.steal - start_.steal) / double(now.total - start_.total));
    return buf;
  }

 private:
  struct Times {
    unsigned long long steal = 0, total = 0;
  };
  // The first line of /proc/stat: cpu user nice system idle iowait irq softirq steal ...
  static Times read() {
    std::ifstream in("/proc/stat");
    std::string cpu;
    unsigned long long v[8] = {};
    if (!(in >> cpu) || cpu != "cpu") return {};
    for (auto& x : v)
      if (!(in >> x)) return {};
    Times t;
    for (auto x : v) t.total += x;
    t.steal = v[7];
    return t;
  }
  Times start_;
};

// The closing line of a bench's output: the load average now and the CPU time stolen since
// `steal` was made, so a reader can tell whether the run was quiet.
inline void print_run_end(const StealMeter& steal) {
  std::printf("load average at end: %s; CPU time stolen by the hypervisor: %s\n", load_average().c_str(),
              steal.percent().c_str());
}

}  // namespace pierce::bench
