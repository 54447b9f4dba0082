#pragma once
// The hard-case corpus: seeded, parameterised scenes and rays where ray tracers typically
// miss or repeat hits (coplanar and touching faces, rays through shared edges and vertices,
// grazing rays, slivers, extreme scales and offsets, deep stacks, segments that start or end
// exactly on a surface).
//
// Rays are built in the "exact class" of docs/EXACTNESS.md unless a case says otherwise:
// vertices, origins and directions are representable in float, every direction's largest
// component is +-1 and the others are small dyadic fractions (or zero), and origins sit on
// dyadic points, so the kernels' sheared vertex coordinates are exact and their answers must
// equal the exact oracle bit for bit. Cases with float_exact == false are built to show where
// single precision is not enough: the input is not representable in float, and only the
// double kernels are claimed exact on them against the input geometry.
#include <cstdint>
#include <string>
#include <vector>

#include "pierce/generators.h"
#include "pierce/ray.h"
#include "pierce/scene.h"

namespace pierce::hard {

struct Case {
  std::string family;  // row of the exactness report
  std::string name;    // this variant's parameters
  Scene scene;
  std::vector<Ray> rays;
  bool float_exact = true;  // scene and rays representable in float: float kernels claimed exact
};

struct Options {
  std::uint64_t seed = 1;
  int rays_per_case = 48;   // approximate; each case picks its targets at random from its candidates
  int deep_layers = 10000;  // depth-complexity family
  int deep_rays = 8;
};

// Families (each returns one or more cases of the same family name).
std::vector<Case> coplanar_duplicates(const Options& o);   // same and opposite winding
std::vector<Case> coplanar_overlaps(const Options& o);     // partially overlapping coplanar triangles
std::vector<Case> touching_plates(const Options& o);       // stacked plates sharing faces, armour-like
std::vector<Case> t_junctions(const Options& o);
std::vector<Case> closed_edges_vertices(const Options& o); // cube grids, voxel block, high-valence fans
std::vector<Case> grazing(const Options& o);               // rays in a triangle's plane
std::vector<Case> near_coplanar(const Options& o);         // surfaces 1 ulp apart (float and double)
std::vector<Case> slivers(const Options& o);               // slivers and zero-area triangles
std::vector<Case> scaled_translated(const Options& o);     // 1e-6 .. 1e6, offsets up to 1e6
std::vector<Case> deep_stack(const Options& o);            // o.deep_layers layers
std::vector<Case> segment_ends(const Options& o);          // rays starting / ending exactly on a surface
std::vector<Case> double_rounding(const Options& o);       // edges within one double rounding of the ray
std::vector<Case> invalid_rays(const Options& o);          // NaN/Inf/zero directions, empty ranges, empty scene

// Every family, in report order.
std::vector<Case> corpus(const Options& o = {});

// A random scene in the exact class, for property tests and fuzzing: closed boxes, plates and
// loose triangles on a 1/16 grid in [0, 4]^3 (touching, overlapping, coplanar, duplicated, some
// degenerate), and `rays` rays through its vertices, edge midpoints and grid points, axis-aligned
// or dyadic-tilted, some with tmin/tmax exactly on a face.
Case random_dyadic(std::uint64_t seed, int objects, int rays);

// ---- Building blocks (also used by the property tests) ----

// Directions whose kernel shear is exact: component `axis` is +-1, the others are multiples
// of 1/4 in (-1, 1).
Vec3d dyadic_direction(std::uint64_t& state, int axis, int sign);

// A ray through `target` along `dir`, starting far enough back to be outside `bounds`
// (origin = target - s * dir with s a power of two, so the origin is exact when `target` and
// `dir` are dyadic with few bits). tmin = 0, tmax = +inf.
Ray ray_through(const Vec3d& target, const Vec3d& dir, const BBoxd& bounds);

// Candidate ray targets of a mesh set: vertices, edge midpoints, triangle centroids.
std::vector<Vec3d> targets_of(const std::vector<gen::Mesh>& meshes);

// Rays through randomly chosen targets: axis-aligned both ways and dyadic tilted directions.
// With `require_float`, targets/origins not representable in float are skipped.
std::vector<Ray> rays_through_targets(const std::vector<Vec3d>& targets, const BBoxd& bounds, int count,
                                      std::uint64_t seed, bool tilted = true, bool require_float = true);

}  // namespace pierce::hard
