#pragma once
// Scenes with known thickness and overlap answers for the analysis tests.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
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

// Closed box [lo, hi] with each face split into a k x k grid of quads (2 k^2 triangles per face),
// wound outward: touching gen::box, it shares a face tessellated differently.
inline gen::Mesh gridded_box(Vec3d lo, Vec3d hi, int k, std::string name) {
  gen::Mesh m;
  m.name = std::move(name);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      // (u, v, axis) is right-handed; the +side face keeps that winding, the -side one reverses it.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto base = std::uint32_t(m.vertices.size());
      for (int i = 0; i <= k; ++i)
        for (int j = 0; j <= k; ++j) {
          Vec3d p;
          p[axis] = side ? hi[axis] : lo[axis];
          p[u] = lo[u] + (hi[u] - lo[u]) * i / k;
          p[v] = lo[v] + (hi[v] - lo[v]) * j / k;
          m.vertices.push_back(p);
        }
      auto at = [&](int i, int j) { return base + std::uint32_t(i * (k + 1) + j); };
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
          const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if (side) {
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
          } else {
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({a, d, c});
          }
        }
    }
  return m;
}

inline double max_edge_length(const gen::Mesh& m) {
  double e = 0;
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) e = std::max(e, length(m.vertices[t[k]] - m.vertices[t[(k + 1) % 3]]));
  return e;
}

}  // namespace pierce::test
