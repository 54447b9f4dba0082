#pragma once
// Synthetic scenes with known answers, for tests, benchmarks and the bundled samples.
// Each returns meshes (one geometry each) with consistent outward (CCW) winding where the
// description says "closed".
#include <cstdint>
#include <string>
#include <vector>

#include "pierce/scene.h"

namespace pierce::gen {

struct Mesh {
  std::string name;
  std::vector<Vec3d> vertices;
  std::vector<Tri> triangles;
};

// Closed axis-aligned box [lo, hi], 12 triangles.
Mesh box(Vec3d lo, Vec3d hi, std::string name = "box");

// `layers` closed plates stacked along z, plate i spanning z in [i*thickness, (i+1)*thickness]
// and [0, size]^2 in x, y: touching plates share their faces exactly (coplanar, opposite
// winding). A ray along z through the interior meets 2*layers surfaces.
std::vector<Mesh> stacked_plates(int layers, double size = 1.0, double thickness = 0.1);

// A closed grid of n^3 unit cubes as separate geometries, each cube split into 12 triangles
// with alternating diagonals so rays through integer coordinates hit edges and vertices.
std::vector<Mesh> cube_grid(int n);

// A single closed mesh: an n x n x n voxel block, outer surface only, with grid vertices
// of high valence and shared edges along integer lines.
Mesh voxel_block(int n);

// Random triangle soup in [0,1]^3 ("hairball"): triangles of edge length ~ size.
Mesh random_soup(std::size_t count, double size, std::uint64_t seed);

// Closed "organic" mesh: a subdivided icosahedron displaced by smooth noise.
Mesh blob(int subdivisions, std::uint64_t seed = 7, double bumpiness = 0.25);

// One geometry made of k copies of the same triangle set (duplicated coplanar faces):
// same winding if flip == false, alternating otherwise.
Mesh duplicated(const Mesh& m, int copies, bool alternate_winding);

Mesh translated(Mesh m, Vec3d offset);
Mesh scaled(Mesh m, double factor);
// Every triangle's winding reversed.
Mesh flipped(Mesh m);
// b's vertices and triangles appended to a (one geometry).
Mesh merged(Mesh a, const Mesh& b);

// Icosphere (gen::blob without bumps, vertices on the sphere): 20 * 4^subdivisions triangles.
Mesh icosphere(int subdivisions, double radius = 1.0, Vec3d centre = {});
// One closed shell: an outer icosphere of radius 1 and an inner one of radius `inner`, facing
// inward, so the wall is 1 - inner thick (less the tessellation's sag).
Mesh hollow_sphere(int outer_subdivisions, int inner_subdivisions, double inner = 0.95);

Scene to_scene(const std::vector<Mesh>& meshes);

// OBJ text with one `o` group per mesh (what the CLI's OBJ loader reads back).
std::string to_obj(const std::vector<Mesh>& meshes);

}  // namespace pierce::gen
