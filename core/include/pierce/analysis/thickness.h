#pragma once
// Wall-thickness maps on the solids of a scene, per vertex or per face.
//
//  - ray: from the sample point along the inward normal, the distance to where the ray leaves
//    the solid it started in (exact kernels; other solids' hits are ignored, so a touching
//    neighbour or a coincident face of another solid neither shortens nor lengthens it);
//  - cone: k rays in a cone around the inward normal, aggregated as the shape diameter
//    function of Shapira et al. 2008 (rays farther than one standard deviation from the median
//    dropped, the rest averaged with weights 1/angle to the axis) or as their median;
//  - sphere: diameter of the largest ball inside the solid touching the sample point
//    (shrinking-ball iteration on closest-point queries, started from the ray thickness). The
//    triangles through the sample point are left out of the queries (a ball tangent at a mesh
//    vertex always cuts its tilted neighbours), so at sharp convex edges and corners the ball is
//    bounded only by the faces away from the point: the method is meant for curved walls.
//
// Open meshes: a ray that finds no exit (or none within max_distance) gives NaN with status
// no_exit, never a number.
//
// CAD input (ThicknessOptions::exact covers the geometry, see exact_surface.h): every sample
// starts on the exact B-rep face, at the projection of the mesh sample onto the face of its
// triangle, and is traced along the face's exact inward normal there. A vertex on an edge
// between faces is sampled once per face whose inward normal enters the material there (each
// sample a millionth of its triangle into its face, so that its ray does not run along the
// neighbouring face) and keeps the smaller thickness (brep_faces says how many); at an acute
// edge, where each face's ray would leave at once, once along the mean of the faces' normals.
// The exit found on the mesh is refined on the exact face of the triangle it crosses (Newton
// steps from the triangle's UV); where that gives no answer inside the face's trim, where the
// ray meets the face at a glancing angle, or where the mesh has no exit in a closed solid, the
// whole B-rep is intersected and decides (ExactSurfaces::exact_exit). So ray and cone rays
// measure the B-rep, not the tessellation (the sphere method's ball is still shrunk against the
// mesh, from the mesh sample along the exact normal). A sample that starts on a folded triangle, first
// meets or leaves through one, or finds no exit in a closed solid (max_distance infinite)
// where the B-rep has none either, or whose projection fails, gets status `tessellation` and
// no thickness: it is an artefact of the mesh, counted per solid and left out of the
// statistics. Meshes (STL, OBJ, OFF, PLY) are measured on the mesh alone: none of this applies.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pierce/analysis/exact_surface.h"
#include "pierce/progress.h"
#include "pierce/analysis/statistics.h"
#include "pierce/kernel.h"
#include "pierce/origin_offsets.h"
#include "pierce/analysis/thickness_regions.h"
#include "pierce/analysis/tie_distance.h"
#include "pierce/enum_names.h"

namespace pierce::analysis {

enum class ThicknessMethod { ray, cone, sphere };
enum class SampleAt { vertex, face };
enum class ConeAggregate { shapira, median };
// Origin offsets for rays from face samples: never change a result, only the work.
enum class OffsetMode { off, on };

constexpr EnumTable<ThicknessMethod, 3> enum_table(ThicknessMethod) {
  using enum ThicknessMethod;
  return {"thickness method", {{ray, "ray"}, {cone, "cone"}, {sphere, "sphere"}}};
}
constexpr EnumTable<SampleAt, 2> enum_table(SampleAt) {
  using enum SampleAt;
  return {"sampling", {{vertex, "vertex"}, {face, "face"}}};
}
constexpr EnumTable<ConeAggregate, 2> enum_table(ConeAggregate) {
  using enum ConeAggregate;
  return {"cone aggregate", {{shapira, "shapira"}, {median, "median"}}};
}
constexpr EnumTable<OffsetMode, 2> enum_table(OffsetMode) {
  using enum OffsetMode;
  return {"origin offset mode", {{off, "off"}, {on, "on"}}};
}

struct ThicknessOptions {
  ThicknessMethod method = ThicknessMethod::ray;
  SampleAt per = SampleAt::vertex;
  double max_distance = std::numeric_limits<double>::infinity();  // search no farther than this
  double min_thickness = 0;     // thin flag: finite thickness < min_thickness (strictly)
  // Thick regions: finite thickness > max_thickness (strictly); infinite: none. Must not be
  // below min_thickness when both are set, so that no sample is both thin and thick.
  double max_thickness = std::numeric_limits<double>::infinity();
  int cone_rays = 30;           // cone: rays per sample, including the axis
  double cone_angle_deg = 120;  // cone: full opening angle
  ConeAggregate cone_aggregate = ConeAggregate::shapira;
  int sphere_max_iterations = 100;
  // Crossings closer than this to the sample point (relative to the scene's size, see
  // tie_distance()) belong to the surface the ray starts on and are skipped; crossings of the
  // same solid closer together than this are treated as simultaneous.
  double tie_tolerance_rel = 1e-6;
  KernelKind kernel = kDefaultKernel;  // any exact kernel gives the same result
  // Ray and cone rays from face samples start where they leave an empty hemisphere on their
  // triangle (origin_offsets.h; vertex samples lie on every hemisphere's rim and gain nothing).
  // Off by default: building the hemispheres costs more than they save on every model measured
  // (docs/BENCHMARKS.md, "Origin offsets").
  OffsetMode origin_offsets = OffsetMode::off;
  HemisphereSet offset_set = HemisphereSet::center;
  std::vector<std::uint32_t> solids;      // geometries to sample (all when empty); the others
                                          // still take part as neighbours
  // Elements to sample (all of each sampled solid when empty): when given, one entry per
  // geometry of the scene, each empty (none) or of that geometry's vertex (per vertex) or
  // triangle (per face) count; element e of geometry g is measured when sample_mask[g][e] != 0.
  // The result lists the selected elements (and, per vertex, the first of each group of
  // coincident vertices a selected one copies its value from); the statistics cover those.
  // Used to split the samples of one scene between processes.
  std::vector<std::vector<std::uint8_t>> sample_mask;
  std::vector<double> percentiles = kDefaultPercentiles;
  int histogram_bins = 20;
  // The exact surfaces behind CAD geometries (not owned; must outlive the call), or null.
  const ExactSurfaces* exact = nullptr;
  // Triangles flagged as tessellation artefacts where no exact surfaces are at hand (e.g. the
  // `Folded` cell array of a CAD reader in VTK): empty, or one entry per geometry, each empty or
  // one per triangle (nonzero: folded). A geometry with flags is treated as CAD input for the
  // `tessellation` status (without B-rep projection or refinement).
  std::vector<std::vector<std::uint8_t>> tessellation_flags;
};

enum class ThicknessStatus : std::uint8_t {
  ok = 0,
  no_exit = 1,    // the ray (or most cone rays) left through a hole or went beyond max_distance
  no_normal = 2,  // degenerate face or vertex without a usable normal
  tessellation = 3,  // CAD input: an artefact of the tessellation (see above), no thickness
};
constexpr EnumTable<ThicknessStatus, 4> enum_table(ThicknessStatus) {
  using enum ThicknessStatus;
  return {"thickness status",
          {{ok, "ok"}, {no_exit, "no_exit"}, {no_normal, "no_normal"}, {tessellation, "tessellation"}}};
}

struct SolidThickness {
  std::uint32_t geom = 0;
  std::string name;
  std::size_t elements = 0, valid = 0, no_exit = 0, no_normal = 0, thin = 0;
  std::size_t tessellation = 0;  // excluded as tessellation artefacts (CAD input)
  std::size_t edge_samples = 0;  // CAD vertices on an edge: the smaller of several faces' samples
  bool exact = false;            // sampled on the exact B-rep (CAD input with exact surfaces)
  Summary summary;  // over the valid thicknesses
};

// One entry per sampled element, geometry by geometry in the order of `solids` (or of the
// scene), elements in the geometry's vertex or triangle order.
struct ThicknessResult {
  SampleAt per = SampleAt::vertex;
  std::vector<std::uint32_t> solid;    // geometry id
  std::vector<std::uint32_t> element;  // vertex or triangle index in its geometry
  std::vector<Vec3d> point;            // sample point (vertex, or triangle centroid)
  std::vector<Vec3d> normal;           // unit outward normal (zero where none)
  std::vector<double> thickness;       // NaN where there is none
  std::vector<std::uint8_t> thin;      // 1 where thickness < min_thickness
  std::vector<ThicknessStatus> status;
  // B-rep faces sampled at the element: 0 for meshes, 1 on a face, 2 or more for a CAD vertex on
  // an edge (the thickness, point and normal are those of its smallest sample). Empty when no
  // sampled geometry is covered by ThicknessOptions::exact.
  std::vector<std::uint8_t> brep_faces;
  // The triangle of its solid through which the sample's ray leaves: the ray method on a mesh
  // sample only (the one kind whose exit lies on a triangle of the mesh); kInvalidId elsewhere.
  // Regions join each flagged sample with the samples there; without it they look the exit
  // point's nearest triangle up.
  std::vector<std::uint32_t> exit_triangle;
  std::vector<SolidThickness> solids;  // per-solid statistics
  // Regions (thickness_regions.h; compute_thickness only, with a threshold set): thin ones
  // thinnest first, thick ones thickest first (ties by solid, then point). `region` holds one id
  // per sample, -1 for none: an id below thin_regions.size() indexes thin_regions, a larger one
  // indexes thick_regions at id - thin_regions.size().
  std::vector<std::int32_t> region;
  std::vector<ThicknessRegion> thin_regions, thick_regions;
  bool completed = true;               // false if cancelled (then the arrays are partial)

  std::size_t size() const { return thickness.size(); }
};

// Throws std::invalid_argument on bad options (negative distances, cone_rays < 1, angle outside
// (0, 180), a non-exact kernel, an unknown solid id).
ThicknessResult compute_thickness(const Accel& accel, const ThicknessOptions& opts = {},
                                  const Progress& progress = {});

inline std::string_view method_name(ThicknessMethod m) { return enum_name(m); }
inline std::string_view status_name(ThicknessStatus s) { return enum_name(s); }

// Ray thickness of one sample: from `point` along the unit inward direction `dir`, the
// distance to where the ray leaves geometry `geom` (NaN if it does not within max_distance).
// `tie` is tie_distance(). The iterator must use TieOrder::leave_before_enter.
// `offset`: a safe_offset() for this ray (0 for none); the search starts at max(tie, offset).
double ray_exit_distance(HitIterator& it, std::uint32_t geom, Vec3d point, Vec3d dir, double max_distance,
                         double tie, double offset = 0);
// Ray thickness at given surface points: for each i, the distance from rays[i].org along
// rays[i].dir (normalised here) to where the ray leaves solid geoms[i] (ray_exit_distance), NaN
// if it does not within max_distance. In parallel (parallel_for_items), one value per ray in ray
// order; `completed` is false if progress cancelled. Throws std::invalid_argument for a non-exact
// kernel, a geometry id not in the scene, or sizes that differ.
struct ThicknessAlong {
  std::vector<double> thickness;
  bool completed = true;
};
ThicknessAlong thickness_along(const Accel& accel, const std::vector<std::uint32_t>& geoms,
                               const std::vector<Ray>& rays, double max_distance, double tie_tolerance_rel = 1e-6,
                               KernelKind kernel = kDefaultKernel, const Progress& progress = {});

// One measured row of a compute_thickness result, for assembling a map measured in parts.
struct MeasuredSample {
  std::uint32_t solid = 0, element = 0;
  Vec3d point, normal;
  double thickness = 0;
  ThicknessStatus status = ThicknessStatus::ok;
  std::uint8_t brep_faces = 0;
  std::uint32_t exit_triangle = kInvalidId;
};

// What compute_thickness(accel, opts) returns, from rows already measured by compute_thickness
// calls whose sample masks together select the samples of `opts` (distributed runs: each
// process measures its part, then every process assembles the whole map). The samples' rows
// are taken from `measured` instead of traced; copies, thin flags, statistics and regions are
// computed as compute_thickness computes them. Throws std::invalid_argument when a sample of
// `opts` has no row in `measured`.
ThicknessResult assemble_thickness(const Accel& accel, const ThicknessOptions& opts,
                                   std::span<const MeasuredSample> measured);

// Thickness at given points (`pierce thickness --at`): each point is projected onto the boundary
// of its solid (the closest point of its triangles; on CAD input then onto the exact face) and
// measured there like a face sample with `opts` (method, max distance, exact surfaces...),
// along the given outward normal when one is given (nonzero) and the surface's otherwise.
// One entry per point, in input order; `element` is the triangle the point was projected onto.
// Throws std::invalid_argument for sizes that differ or a solid id not in the scene.
ThicknessResult thickness_at(const Accel& accel, const std::vector<std::uint32_t>& solids,
                             const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                             const ThicknessOptions& opts = {}, const Progress& progress = {});

// Whether compute_thickness uses origin offsets with these options.
bool uses_origin_offsets(const ThicknessOptions& opts);

// The cone method's aggregate of (length, angle to the axis) pairs, at least one: lengths
// farther than one standard deviation from the median are dropped; the rest are averaged with
// weights 1/angle (angles below min_angle/2 weigh as min_angle/2), or their median is taken.
double cone_aggregate(std::span<const std::pair<double, double>> length_angle, ConeAggregate how,
                      double min_angle);

}  // namespace pierce::analysis

