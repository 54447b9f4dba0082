#pragma once
// Scenes with known thickness and overlap answers for the analysis tests.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce::test {

// Accel keeps pointers into the scene: keep both in place.
struct World {
  Scene scene;
  Accel accel;
  explicit World(Scene s) : scene(std::move(s)), accel(scene) {}
  World(const World&) = delete;
  World& operator=(const World&) = delete;
};

inline std::unique_ptr<World> make_world(const std::vector<gen::Mesh>& meshes) {
  return std::make_unique<World>(gen::to_scene(meshes));
}

using gen::flipped;
using gen::icosphere;
using gen::merged;

// One closed mesh: outer sphere radius 1, inner sphere radius `inner` facing inward.
inline gen::Mesh hollow_sphere(int subdivisions, double inner = 0.95) {
  return gen::hollow_sphere(subdivisions, subdivisions, inner);
}

inline double max_edge_length(const gen::Mesh& m) {
  double e = 0;
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) e = std::max(e, length(m.vertices[t[k]] - m.vertices[t[(k + 1) % 3]]));
  return e;
}

}  // namespace pierce::test
