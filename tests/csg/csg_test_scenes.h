#pragma once
// Scenes with exactly known volumes for the CSG, shotline, ray-grid and effects tests.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce::csgtest {

// Accel keeps a pointer to the scene: keep both in place.
struct World {
  Scene scene;
  Accel accel;
  explicit World(Scene s) : scene(std::move(s)), accel(scene) {}
};

inline std::unique_ptr<World> make_world(const std::vector<gen::Mesh>& meshes) {
  return std::make_unique<World>(gen::to_scene(meshes));
}

// Tessellated sphere (gen::blob without bumps): an icosphere, symmetric under x -> -x, y -> -y and
// z -> -z, so any half cut by a coordinate plane through its centre has exactly half its volume.
inline gen::Mesh sphere(double radius, Vec3d centre, std::string name, int subdivisions = 3) {
  gen::Mesh m = gen::translated(gen::scaled(gen::blob(subdivisions, 7, 0.0), radius), centre);
  m.name = std::move(name);
  return m;
}

// Exact volume of a closed, consistently outward-wound mesh (divergence theorem).
inline double mesh_volume(const gen::Mesh& m) {
  double v = 0;
  for (const Tri& t : m.triangles)
    v += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]]));
  return v / 6.0;
}

// Exact centroid of such a mesh: signed tetrahedra from the origin.
inline Vec3d mesh_centroid(const gen::Mesh& m) {
  Vec3d c{};
  double v = 0;
  for (const Tri& t : m.triangles) {
    const Vec3d a = m.vertices[t[0]], b = m.vertices[t[1]], d = m.vertices[t[2]];
    const double w = dot(a, cross(b, d)) / 6.0;
    v += w;
    c = c + (a + b + d) * (w / 4.0);
  }
  return c * (1.0 / v);
}

}  // namespace pierce::csgtest
