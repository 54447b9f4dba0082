#pragma once
// Scenes with exactly known volumes for the CSG, shotline, ray-grid and effects tests.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../common/test_world.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce::csgtest {

using test::make_world;
using test::World;

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

// Rotation about the axis (1, 2, 3) by 0.7 rad: no face stays axis-aligned.
inline Vec3d rotated(Vec3d p) {
  const Vec3d k = Vec3d{1, 2, 3} * (1.0 / std::sqrt(14.0));
  const double c = std::cos(0.7), s = std::sin(0.7);
  return p * c + cross(k, p) * s + k * (dot(k, p) * (1 - c));
}

// Length of the ray segment [tmin, tmax] inside the box (slab clipping), times |dir|.
inline double chord(const Ray& r, Vec3d lo, Vec3d hi) {
  double t0 = r.tmin, t1 = r.tmax;
  for (std::size_t a = 0; a < 3; ++a) {
    if (r.dir[a] == 0) {
      if (r.org[a] < lo[a] || r.org[a] > hi[a]) return 0;
      continue;
    }
    double ta = (lo[a] - r.org[a]) / r.dir[a], tb = (hi[a] - r.org[a]) / r.dir[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t1 > t0 ? (t1 - t0) * length(r.dir) : 0.0;
}

// Beer-Lambert transmission through gen::stacked_plates(plates, 1, thickness) with attenuation
// mu_even in the even plates and mu_odd in the odd ones, analytically.
inline double plate_stack_transmission(const Ray& r, int plates, double thickness, double mu_even, double mu_odd) {
  double tau = 0;
  for (int i = 0; i < plates; ++i)
    tau += (i % 2 ? mu_odd : mu_even) * chord(r, {0, 0, i * thickness}, {1, 1, (i + 1) * thickness});
  return std::exp(-tau);
}

}  // namespace pierce::csgtest
