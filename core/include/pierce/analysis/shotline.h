#pragma once
// Shotlines (BRL-CAD nirt): along each ray, the partitions it passes through (or the intervals of
// a CSG expression), the gaps between them and the overlaps, with entry/exit points, line-of-sight
// length, obliquity and normal thickness.
#include <cstdint>
#include <vector>

#include "pierce/analysis/csg.h"
#include "pierce/progress.h"
#include "pierce/kernel.h"

namespace pierce::analysis {

enum class ShotKind : std::uint8_t {
  solid,    // a partition inside exactly one solid
  overlap,  // a partition inside two or more solids
  region,   // an interval of the CSG expression
  gap,      // air between two consecutive solid/overlap/region rows of the same ray
};
std::string_view shot_kind_name(ShotKind k);

struct ShotRow {
  std::uint32_t ray = 0;
  ShotKind kind = ShotKind::solid;
  std::vector<std::uint32_t> solids;  // geometry ids (solid, overlap); gap: the solids before and
                                      // after it; region: every solid the expression names
  double t_in = 0, t_out = 0;
  Vec3d in_point, out_point;
  double los = 0;  // line-of-sight length |out_point - in_point|
  // Degrees between the ray and the surface normal where the row begins / ends, in [0, 90]. NaN
  // for gaps and where the row is cut by the ray's start or end (no surface there).
  double obliquity_in = 0, obliquity_out = 0;
  double normal_thickness = 0;  // los * cos(obliquity_in); NaN when obliquity_in is
  std::uint32_t in_geom = kInvalidId, out_geom = kInvalidId;  // solids whose surfaces bound it
};

struct ShotOptions {
  KernelKind kernel = kDefaultKernel;  // any exact kernel gives the same rows
  const CsgExpr* csg = nullptr;           // regions instead of solid partitions when set
  // Partitions and gaps shorter than tie_distance(scene, tie_tolerance_rel) (tie_distance.h) are
  // float noise between touching solids and are snapped away (snap_partitions).
  double tie_tolerance_rel = 1e-6;
};

struct ShotResult {
  std::vector<ShotRow> rows;  // by ray, then t_in (an overlap row follows the region it lies in)
  std::size_t rays = 0, rays_hitting = 0;
  std::uint64_t unmatched_leaves = 0, unclosed = 0;  // bad-mesh events, see ray_partitions.h
  bool completed = true;
};

// Each ray is traced as a full line and cut to its [tmin, tmax]: a ray starting inside a solid
// gives a first row starting at the ray's origin (obliquity_in NaN). Throws std::invalid_argument
// for a non-exact kernel.
ShotResult shoot(const Accel& accel, const std::vector<Ray>& rays, const ShotOptions& opts = {},
                 const Progress& progress = {});

}  // namespace pierce::analysis
