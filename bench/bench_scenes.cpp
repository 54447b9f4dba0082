#include "bench_scenes.h"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

#include "pierce/analysis/mesh_report.h"
#include "pierce/generators.h"
#include "pierce/io/mesh_io.h"

namespace pierce::bench {

std::vector<Ray> random_rays_through(const BBoxd& bounds, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Vec3d lo = bounds.lo, ext = bounds.extent();
  const double diagonal = length(ext);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    const Vec3d p{lo.x + U(rng) * ext.x, lo.y + U(rng) * ext.y, lo.z + U(rng) * ext.z};
    const double z = 2.0 * U(rng) - 1.0, phi = 2.0 * std::numbers::pi * U(rng);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    r.dir = {s * std::cos(phi), s * std::sin(phi), z};
    r.org = p - r.dir * diagonal;
  }
  return rays;
}

BenchScene plates_scene(int layers, std::size_t ray_count, std::uint64_t seed) {
  BenchScene b;
  b.name = "plates";
  const double thickness = 1.0 / layers;  // layers is a power of two in practice: faces land exactly
  b.scene = gen::to_scene(gen::stacked_plates(layers, 1.0, thickness));
  b.description = std::to_string(layers) + " touching plates [0,1]^2 x " + std::to_string(thickness) +
                  " stacked along z; rays along +-z, half axis-aligned, half tilted <= 0.05";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> inner(0.1, 0.9), tilt(-0.05, 0.05);
  b.rays.resize(ray_count);
  for (std::size_t i = 0; i < ray_count; ++i) {
    Ray& r = b.rays[i];
    const bool up = (i & 1) == 0, tilted = (i & 2) != 0;
    // Start 0.25 outside the stack: a tilt of 0.05 moves a ray by at most 0.0625 in x or y
    // over the 1.5 it travels to the far side, so it never leaves through a side face.
    r.org = {inner(rng), inner(rng), up ? -0.25 : 1.25};
    r.dir = {0.0, 0.0, up ? 1.0 : -1.0};
    if (tilted) r.dir.x = tilt(rng), r.dir.y = tilt(rng);
  }
  b.expected_hits_per_ray = 2L * layers;
  return b;
}

BenchScene hairball_scene(std::size_t triangles, double size, std::size_t ray_count, std::uint64_t seed) {
  BenchScene b;
  b.name = "hairball";
  b.scene = gen::to_scene({gen::random_soup(triangles, size, seed)});
  b.description = "gen::random_soup: " + std::to_string(triangles) + " random triangles of size " +
                  std::to_string(size) + " in [0,1]^3; random rays through the bounds";
  b.rays = random_rays_through(b.scene.bounds(), ray_count, seed + 1);
  return b;
}

BenchScene blob_scene(int subdivisions, std::size_t ray_count, std::uint64_t seed) {
  BenchScene b;
  b.name = "blob";
  b.scene = gen::to_scene({gen::blob(subdivisions)});
  b.description = "gen::blob(" + std::to_string(subdivisions) +
                  "): closed organic mesh (displaced subdivided icosahedron); random rays through the bounds";
  b.rays = random_rays_through(b.scene.bounds(), ray_count, seed + 2);
  b.closed = true;
  return b;
}

BenchScene shell_scene(int outer_subdivisions, int inner_subdivisions, std::size_t ray_count, std::uint64_t seed) {
  BenchScene b;
  b.name = "shell";
  b.scene = gen::to_scene({gen::hollow_sphere(outer_subdivisions, inner_subdivisions, 0.95)});
  b.description = "gen::hollow_sphere(" + std::to_string(outer_subdivisions) + ", " +
                  std::to_string(inner_subdivisions) + "): closed shell, wall 0.05; random rays through the bounds";
  b.rays = random_rays_through(b.scene.bounds(), ray_count, seed + 3);
  b.closed = true;
  return b;
}

BenchScene mesh_scene(const std::string& path, std::size_t ray_count, std::uint64_t seed) {
  BenchScene b;
  b.name = std::filesystem::path(path).filename().string();
  add_model_files(b.scene, {path});
  b.closed = true;
  for (const analysis::SolidReport& s : analysis::mesh_report(b.scene)) b.closed = b.closed && s.closed;
  b.description = path + (b.closed ? " (closed)" : " (open)") + "; random rays through the bounds";
  b.rays = random_rays_through(b.scene.bounds(), ray_count, seed + 4);
  return b;
}

}  // namespace pierce::bench
