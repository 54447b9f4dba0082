#pragma once
// compute_thickness in three stages (internal to pierce_core): sampling (thickness_sampling.cpp)
// builds the samples and the result's rows, tracing (thickness_trace.cpp) measures each sample
// with the chosen method, statistics (thickness_stats.cpp) fills the per-solid summaries.
#include <cstdint>
#include <utility>
#include <vector>

#include "pierce/analysis/thickness.h"

namespace pierce::analysis::detail {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One point to measure: where, along which inward direction, and which triangles pass
// through it (skipped by the sphere method's closest-point queries). Kept small (28 bytes), as
// there is one per vertex or triangle: a mesh sample starts at its result row's point along
// minus its row's normal, and only CAD samples carry their points (SampleSet::cad).
struct Sample {
  std::uint32_t geom;
  std::uint32_t out_index;  // position in the result arrays
  std::uint32_t exclude_begin = 0, exclude_end = 0;  // range in SampleSet::exclude
  std::uint32_t prim = kInvalidId;  // face samples: the triangle the point lies on
  std::uint32_t cad = kInvalidId;   // CAD input: its CadSample; kInvalidId for a mesh sample
  ThicknessStatus preset = ThicknessStatus::ok;  // not ok: known without tracing

  bool is_cad() const { return cad != kInvalidId; }  // tessellation statuses apply
};

// Where a CAD sample starts (ThicknessOptions::exact or tessellation_flags covers the geometry).
struct CadSample {
  Vec3d point, inward;  // on the exact face, along its exact inward normal
  Vec3d mesh_point;     // the mesh sample `point` was projected from: mesh rays start here
  std::uint32_t face = kInvalidId;  // exact input: the B-rep face `point` lies on
  bool exact = false;   // exits are refined on the exact faces
  bool closed = false;  // the geometry's mesh is closed: a ray must find an exit
};

struct SampleSet {
  std::vector<Sample> samples;
  std::vector<CadSample> cad;
  std::vector<std::uint32_t> exclude;
  // Result slots filled by copying another slot's result (welded duplicates of a vertex).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;  // (to, from)
  std::vector<std::pair<std::size_t, std::size_t>> ranges;      // result range per sampled solid
  std::vector<std::uint32_t> solids;                            // the sampled solids
  // Per sampled solid when `ranges` is (compute_thickness): weld_by_position of its vertices.
  std::vector<std::vector<std::uint32_t>> welds;

  void add_cad(Sample s, const CadSample& c) {
    s.cad = std::uint32_t(cad.size());
    cad.push_back(c);
    samples.push_back(s);
  }
};

// Validates the options (throws std::invalid_argument).
void check_options(const Accel& accel, const ThicknessOptions& o);

// The solids to sample, the result's rows (NaN thickness; status ok or no_normal) and the
// samples, per vertex or per face; CAD samples projected onto the exact faces.
SampleSet build_samples(const Scene& scene, const ThicknessOptions& opts, ThicknessResult& res);

// One sample per point (thickness_at): projected onto its solid's triangles, then like a CAD or
// mesh face sample.
SampleSet build_point_samples(const Scene& scene, const ThicknessOptions& opts, const std::vector<std::uint32_t>& solids,
                              const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                              ThicknessResult& res);

// ray_exit_distance, also giving the triangle the ray leaves through (kInvalidId where it does
// not leave).
double ray_exit(HitIterator& it, std::uint32_t geom, Vec3d point, Vec3d dir, double max_distance, double tie,
                double offset, std::uint32_t& exit_triangle);

// Measures every sample (in parallel, progress per sample) and writes each result slot's
// thickness and status (CAD: the smallest of a slot's samples, with its point and normal).
// False if cancelled.
bool trace_samples(const Accel& accel, const ThicknessOptions& opts, const SampleSet& set, ThicknessResult& res,
                   const Progress& progress);

// Copies, thin flags and the per-solid statistics.
void finish_statistics(const Scene& scene, const ThicknessOptions& opts, const SampleSet& set, ThicknessResult& res);

// Stage 4 (thickness_regions.cpp): the per-sample region ids and the thin and thick regions of a
// compute_thickness result (ranges per solid), when a threshold is set; otherwise every id -1.
void find_regions(const Accel& accel, const ThicknessOptions& opts, const SampleSet& set, ThicknessResult& res);

// Whether geometry g is CAD input for these options, and its folded-triangle flags (empty: none).
bool is_cad(const ThicknessOptions& opts, std::uint32_t g);
std::span<const std::uint8_t> folded_flags(const ThicknessOptions& opts, std::uint32_t g);

}  // namespace pierce::analysis::detail
