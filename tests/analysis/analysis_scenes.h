#pragma once
// Scenes with known thickness and overlap answers for the analysis tests.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "../common/test_world.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce::test {

using gen::flipped;
using gen::icosphere;
using gen::merged;

// One closed mesh: outer sphere radius 1, inner sphere radius `inner` facing inward.
inline gen::Mesh hollow_sphere(int subdivisions, double inner = 0.95) {
  return gen::hollow_sphere(subdivisions, subdivisions, inner);
}

// The mesh with three vertices of its own per triangle, as STL stores it (nothing welded).
inline gen::Mesh triangle_soup(const gen::Mesh& m) {
  gen::Mesh soup;
  for (const Tri& t : m.triangles) {
    const auto base = std::uint32_t(soup.vertices.size());
    for (auto v : t) soup.vertices.push_back(m.vertices[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  return soup;
}

inline double max_edge_length(const gen::Mesh& m) {
  double e = 0;
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) e = std::max(e, length(m.vertices[t[k]] - m.vertices[t[(k + 1) % 3]]));
  return e;
}

}  // namespace pierce::test
