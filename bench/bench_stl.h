#pragma once
// A generated mesh written as a binary STL, so that benches load it as a user's file would be.
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

#include "pierce/generators.h"

namespace pierce::bench {

inline void write_binary_stl(const gen::Mesh& m, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  char header[80] = "pierce bench mesh";
  out.write(header, sizeof header);
  const auto n = std::uint32_t(m.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const Tri& t : m.triangles) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) rec[3 + 3 * k + a] = float(m.vertices[t[k]][a]);
    out.write(reinterpret_cast<const char*>(rec), sizeof rec);
    const std::uint16_t attr = 0;
    out.write(reinterpret_cast<const char*>(&attr), 2);
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace pierce::bench
