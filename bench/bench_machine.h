#pragma once
// What machine a bench ran on, printed above its tables so recorded numbers carry their context.
#include <fstream>
#include <string>

namespace pierce::bench {

inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  if (in >> a >> b >> c) return a + " " + b + " " + c;
  return "unknown";
}

}  // namespace pierce::bench
