#pragma once
// Ray-grid quantities (BRL-CAD gqa): volume, centroid and surface crossings of every solid (and of
// CSG regions), overlaps and gaps between solids, from grids of parallel rays along x, y and z.
//
// A pass with grid size n shoots, along each axis, n x n rays, one per cell of the scene bounds'
// cross-section, at a seeded random point of its cell (stratified sampling: with rays through the
// cell centres, a face parallel to the rays between cell boundaries gives a first-order error that
// nested passes and the three axes repeat alike, so the convergence test below could not see it).
// Each ray's partitions give, per solid, the length inside it; a solid's volume along that axis is
// the sum of lengths times the cell area (exact along the ray), its first moment (cell centre across,
// interval midpoint along) gives the centroid. The estimate is the mean of the three axes; its
// standard error is estimated from the differences between neighbouring cells (cells 2a and 2a+1 of
// a row; an overestimate where a face passes between them). Passes double n (halve the spacing)
// until, for every solid and region, the volume changed by at most `tolerance` (relative) since the
// previous pass, the three axes agree within `tolerance`, 3 standard errors are within `tolerance`,
// and the centroid moved by at most `tolerance` times the scene diagonal; or until max_n, which is
// then reported as not converged. Converged thus means within the tolerance with high probability.
//
// Overlaps: maximal intervals of a ray inside both solids of a pair, reported per pair from the last
// pass with their count, largest line-of-sight depth, where it starts, the largest depth seen along
// each axis (the smallest of these is how far the solids interpenetrate) and the overlap volume.
// Gaps: air between a partition and the next one along a ray when different solids bound it
// (a solid's own concavity is not a gap), reported per pair of solids like overlaps. Touching
// solids share their faces exactly, so they give neither.
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "pierce/analysis/csg.h"
#include "pierce/kernel.h"

namespace pierce::analysis {

struct GqaOptions {
  double tolerance = 1e-3;  // relative, > 0
  int start_n = 0;          // first grid size; 0 = chosen so the thinnest solid spans >= 4 cells
  int max_n = 1024;         // no pass beyond this grid size
  KernelKind kernel = kDefaultKernel;  // any exact kernel gives the same result
  std::vector<CsgExpr> regions;           // CSG expressions measured like solids
  // Partitions and gaps shorter than tie_distance(scene, tie_tolerance_rel) (tie_distance.h) are
  // float noise between touching solids and are snapped away (snap_partitions).
  double tie_tolerance_rel = 1e-6;
  double gap_min = 0;  // gaps no longer than this are not reported (absolute length)
  double gap_max = std::numeric_limits<double>::infinity();  // nor longer than this
  // Shift each pass's and each axis's ray lattice by a seeded random sub-cell offset (see above).
  bool jitter = true;
  std::uint64_t seed = 1;
};

struct GqaQuantities {
  std::string name;                 // solid name, or the region's expression
  std::vector<std::uint32_t> geoms;  // the solid's id, or every solid a region names
  double volume = 0;
  Vec3d centroid;                     // NaN when the volume is 0
  std::array<double, 3> axis_volume{};  // estimate from the rays along x, y, z
  std::uint64_t crossings = 0;          // surface crossings by the last pass's rays
  double change = 0;                    // relative change of the volume since the previous pass
  double std_error = 0;                 // estimated standard error of volume (jittered grids; 0 otherwise)
};

struct GqaPair {
  std::uint32_t a = 0, b = 0;  // geometry ids, a < b
  std::uint64_t count = 0;     // intervals (overlaps) or air intervals (gaps) in the last pass
  double max_depth = 0;        // longest interval (line of sight)
  Vec3d at;                    // where that interval starts
  // Longest interval along each axis's rays (0: none along it); for overlaps the smallest of the
  // axes that saw the pair estimates the interpenetration depth.
  std::array<double, 3> axis_max_depth{};
  double penetration = 0;  // min of axis_max_depth over the axes that saw the pair
  double volume = 0;       // overlaps: volume inside both (mean over axes); gaps: 0
};

struct GqaPass {
  int n = 0;
  std::uint64_t rays = 0;
  double seconds = 0;
  double worst_change = 0;  // largest relative criterion value after this pass (inf on the first)
  std::string worst;        // name of the solid or region it belongs to
};

struct GqaResult {
  std::vector<GqaQuantities> solids;   // one per geometry, in id order
  std::vector<GqaQuantities> regions;  // one per options.regions entry
  std::vector<GqaPair> overlaps;       // sorted by (a, b)
  std::vector<GqaPair> gaps;           // sorted by (a, b)
  std::vector<GqaPass> passes;
  int n = 0;  // grid size of the last pass
  double tolerance = 0;
  std::uint64_t seed = 0;  // GqaOptions::seed (0 when not jittered)
  bool converged = false;
  bool completed = true;  // false if cancelled (results are then from the last finished pass)
  std::uint64_t unmatched_leaves = 0, unclosed = 0;  // bad-mesh events in the last pass
};

// Called with the pass's grid size and the rays done out of the pass's total; false cancels.
using GqaProgress = std::function<bool(int n, std::size_t done, std::size_t total)>;

// Throws std::invalid_argument for bad options (tolerance <= 0, max_n < 1, a non-exact kernel).
GqaResult run_gqa(const Accel& accel, const GqaOptions& opts = {}, const GqaProgress& progress = {});

// The grid size run_gqa starts from when start_n is 0.
int gqa_auto_start_n(const Scene& scene, int max_n);

}  // namespace pierce::analysis
