#pragma once
// The benchmark's scenes and rays, built with pierce::gen and a fixed seed so every run and
// every kernel sees exactly the same triangles and rays.
#include <cstdint>
#include <string>
#include <vector>

#include "pierce/ray.h"
#include "pierce/scene.h"

namespace pierce::bench {

struct SceneSize {
  int plate_layers = 64;
  std::size_t soup_triangles = 100000;
  double soup_triangle_size = 0.05;
  int blob_subdivisions = 6;
};

struct BenchScene {
  std::string name;         // plates | hairball | blob
  std::string description;  // one line: what it is and how its rays are made
  Scene scene;
  std::vector<Ray> rays;
  // Exact number of hits of every ray when the construction determines it (plates), else -1.
  long expected_hits_per_ray = -1;
  bool closed = false;  // closed surfaces and rays from outside: every ray has an even number of hits
};

// `layers` touching plates stacked along z (each plate [0,1]^2 x [i/layers, (i+1)/layers]),
// rays from below and above along z, half exactly axis-aligned, half tilted by up to 0.05
// in x and y; origins keep every ray inside the stack, so each meets all 2*layers faces.
BenchScene plates_scene(int layers, std::size_t ray_count, std::uint64_t seed);

// gen::random_soup in [0,1]^3; random rays through the scene bounds.
BenchScene hairball_scene(std::size_t triangles, double size, std::size_t ray_count, std::uint64_t seed);

// gen::blob (closed, 20 * 4^subdivisions triangles); random rays through the scene bounds.
BenchScene blob_scene(int subdivisions, std::size_t ray_count, std::uint64_t seed);

// gen::hollow_sphere(outer, inner): a closed shell of wall 0.05 (outer subdivision 8 and inner 7:
// 1.64 M triangles); random rays through the bounds.
BenchScene shell_scene(int outer_subdivisions, int inner_subdivisions, std::size_t ray_count, std::uint64_t seed);

// A model file the user brings (STL, OBJ, OFF, PLY; one geometry per file or group); random rays
// through the bounds. `closed` if every geometry is a closed surface.
BenchScene mesh_scene(const std::string& path, std::size_t ray_count, std::uint64_t seed);

// Rays through uniformly random points of `bounds` in uniformly random directions, starting
// one bounds diagonal before that point (outside the box), tmin = 0, tmax = infinity.
std::vector<Ray> random_rays_through(const BBoxd& bounds, std::size_t count, std::uint64_t seed);

}  // namespace pierce::bench
