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

// Reverses every triangle's winding.
inline gen::Mesh flipped(gen::Mesh m) {
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// Appends b's vertices and triangles to a (one geometry).
inline gen::Mesh merged(gen::Mesh a, const gen::Mesh& b) {
  const auto base = std::uint32_t(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Tri t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return a;
}

// Unit icosphere (vertices on the sphere) of the given subdivision level.
inline gen::Mesh icosphere(int subdivisions, double radius = 1.0, Vec3d centre = {}) {
  gen::Mesh m = gen::blob(subdivisions, 7, 0.0);
  m.name = "sphere";
  return gen::translated(gen::scaled(m, radius), centre);
}

// One closed mesh: outer sphere radius 1, inner sphere radius `inner` facing inward.
inline gen::Mesh hollow_sphere(int subdivisions, double inner = 0.95) {
  gen::Mesh m = merged(icosphere(subdivisions), flipped(icosphere(subdivisions, inner)));
  m.name = "hollow_sphere";
  return m;
}

inline double max_edge_length(const gen::Mesh& m) {
  double e = 0;
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) e = std::max(e, length(m.vertices[t[k]] - m.vertices[t[(k + 1) % 3]]));
  return e;
}

}  // namespace pierce::test
