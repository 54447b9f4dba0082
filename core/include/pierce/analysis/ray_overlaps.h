#pragma once
// Overlap diagnostics along rays, from exact hit streams:
//  - Gribble et al.'s coplanar statistic: the share of rays (among those that hit anything)
//    meeting two or more crossings at exactly equal t, and within a distance epsilon;
//  - solid-solid interference (BRL-CAD's OVERLAP report): walking each ray's crossings in
//    leave-before-enter order and tracking which solids the ray is inside, every interval
//    inside two solids at once is an overlap of that pair (line-of-sight depth, entry point).
//    A solid leaving where another enters (a shared face) is a coplanar contact, not an overlap.
//    Crossings of one solid at the same place (within the tie tolerance) change its inside depth
//    by the sign of enters minus leaves: duplicated faces count once; a face duplicated with
//    opposite winding cancels (its solid has winding number 0 there).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "pierce/progress.h"
#include "pierce/kernel.h"

namespace pierce::analysis {

struct RayOverlapOptions {
  KernelKind kernel = kDefaultKernel;  // any exact kernel gives the same result
  double epsilon_rel = 1e-5;              // Gribble's epsilon, relative to the scene diagonal
  // Crossings closer together than this (relative, see tie_distance.h) happen at
  // the same place: a solid leaving and another entering there touch rather than overlap.
  double tie_tolerance_rel = 1e-6;
  bool keep_intervals = true;  // keep every ray's overlap interval, not only per-pair summaries
};

struct CoplanarRayStats {
  std::size_t rays = 0, rays_hitting = 0, rays_equal_t = 0, rays_within_eps = 0;
  double epsilon = 0;  // absolute distance used
  double share_equal() const { return rays_hitting ? double(rays_equal_t) / double(rays_hitting) : 0.0; }
  double share_within_eps() const { return rays_hitting ? double(rays_within_eps) / double(rays_hitting) : 0.0; }
};

struct Interference {
  std::uint32_t ray = 0, a = 0, b = 0;  // a < b
  double t_enter = 0, t_exit = 0;
  double depth = 0;  // line-of-sight length inside both
  Vec3d entry, exit;
};

struct InterferencePair {
  std::uint32_t a = 0, b = 0;
  std::size_t count = 0;  // intervals
  double max_depth = 0;
  Vec3d max_depth_entry;
  std::uint32_t max_depth_ray = 0;
  // Largest depth seen along rays parallel to each axis (NaN: no such ray saw this pair). The
  // smallest of them estimates how far the solids interpenetrate.
  std::array<double, 3> axis_max_depth{};
  double penetration = 0;  // min over axes seen of axis_max_depth; NaN when no axis ray saw it
};

struct ContactPair {
  std::uint32_t a = 0, b = 0;
  std::size_t count = 0;  // rays crossing from one into the other at a shared surface
  Vec3d where;            // first such crossing (lowest ray index)
};

struct RayOverlapReport {
  CoplanarRayStats coplanar;
  std::vector<Interference> intervals;  // when kept: sorted by ray, then t_enter, a, b
  std::vector<InterferencePair> interferences;  // sorted by (a, b)
  std::vector<ContactPair> contacts;            // sorted by (a, b)
  std::size_t rays_ending_inside = 0;  // rays that ended inside a solid (open mesh or short ray)
  // Per-triangle counters, triangle (g, p) at index tri_offset[g] + p.
  std::vector<std::size_t> tri_offset;
  std::vector<std::uint32_t> coplanar_hits;      // crossings with another crossing within epsilon
  std::vector<std::uint32_t> interference_hits;  // crossings that open or close an interference
  bool completed = true;
};

// Throws std::invalid_argument for a non-exact kernel or negative tolerances.
RayOverlapReport analyse_ray_overlaps(const Accel& accel, const std::vector<Ray>& rays,
                                      const RayOverlapOptions& opts = {}, const Progress& progress = {});

inline constexpr int kAllAxes[] = {0, 1, 2};

// n x n parallel rays along each listed axis (0 = x, 1 = y, 2 = z) through the cell centres of
// the bounds enlarged by 1%, starting outside them. Deterministic.
std::vector<Ray> axis_grid_rays(const BBoxd& bounds, int n, std::span<const int> axes = kAllAxes);

// The cross-section area of one cell of axis_grid_rays(bounds, n) along `axis`: the volume a unit
// length of such a ray stands for. 0 for empty bounds or n <= 0.
double axis_grid_cell_area(const BBoxd& bounds, int n, int axis);

}  // namespace pierce::analysis
