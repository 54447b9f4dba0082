#pragma once
// Origin offsets (Zoet, "Accelerating ray tracing with origin offsets"): hemispheres on each
// triangle, on both sides of its plane, each guaranteed to hold no other geometry. A ray that
// starts on a triangle inside one of its hemispheres can start its traversal where it leaves
// the hemisphere: set ray.tmin = max(ray.tmin, safe_offset(...)). The traversal then skips the
// leaf it starts in, often several levels above it, and no hit is lost (below).
//
// Sets (hemispheres per triangle and side): center (1, the centroid), vertex (3, the corners),
// median (3, halfway between each corner and the centroid), median_center (4), polygon (2: the
// centroid and the largest centroid hemisphere of the exactly coplanar, edge-connected patch the
// triangle belongs to, radii found with the whole patch left out), random (4 random points,
// seeded by the triangle's ids). Each hemisphere is 16 bytes (float centre and radius); with
// the triangle's plane (16 bytes, so a query reads one contiguous block and not the scene) the
// center set takes 48 bytes per triangle.
//
// The bound (docs/EXACTNESS.md, "Origin offsets"). All geometry is the float-rounded input,
// as the float BVH holds it. Let S be the scene's largest |coordinate|, E its bounding-box
// diagonal, (n, w) the plane of the origin triangle p as stored (unit normal and n.v0 rounded to
// float), sigma = +-1 the side, s(x) = sigma * (n.x - w) and H = {x : s(x) >= -h} with
// h = 2^-18 (S + E) (the closed half-space, widened by a slab). A hemisphere at c has radius
//     r <= min over triangles q != p of dist(c, q  intersected with  H) - 2^-40 (S + E),
// so coplanar neighbours, duplicated and coincident faces and touching faces count (a face
// through c gives r = 0), the distance to a clipped triangle is computed in double and the
// subtraction covers its rounding; r is stored rounded down to float. The query shrinks the
// ball by 2 mu, mu = 2^-16 E + 2^-21 (S + max|o| + r): one mu covers the rounding of the ray to
// the kernel's precision (origin, direction) and the double kernels' unrounded vertices, the
// other covers the kernel's rounding of a hit's t. It returns the exit distance from the shrunk
// ball (times 1 - 2^-30), only if the ray starts inside that ball and s(o) >= -h + 2^-21 (S +
// max|o| + r), so the kernel's ray stays in H up to the exit (also for the polygon set's shared
// hemisphere, measured from a coplanar neighbour's float plane). Every hit other than on p then has
// an exact t beyond the offset by at least mu/|dir|, and a kernel t >= the offset; since
// TraversalRay rounds tmin up to the next representable value and compares with >=, a hit at
// exactly t == offset is kept. The one assumption is that the kernel's t is within mu of the
// exact t: true except for rays that almost graze the hit triangle, which the exact class of
// docs/EXACTNESS.md already leaves open at any tmin.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "pierce/wide_bvh.h"
#include "pierce/hit.h"
#include "pierce/scene.h"

namespace pierce {

enum class HemisphereSet : std::uint8_t { center, vertex, median, median_center, polygon, random };

inline constexpr HemisphereSet kAllHemisphereSets[] = {HemisphereSet::center,        HemisphereSet::vertex,
                                                       HemisphereSet::median,        HemisphereSet::median_center,
                                                       HemisphereSet::polygon,       HemisphereSet::random};

std::string_view hemisphere_set_name(HemisphereSet s);
std::optional<HemisphereSet> parse_hemisphere_set(std::string_view name);
// Hemispheres per triangle and side.
int hemispheres_per_side(HemisphereSet s);

struct Hemisphere {
  Vec3f center;
  float radius = 0;  // 0: no offset from this hemisphere
};
static_assert(sizeof(Hemisphere) == 16);

struct OriginOffsetOptions {
  std::uint64_t seed = 1;  // random set
  bool parallel = true;    // build with TBB
};

class OriginOffsets {
 public:
  HemisphereSet kind() const { return kind_; }
  int per_side() const { return per_side_; }
  const Scene& scene() const { return *scene_; }
  bool empty() const { return spheres_.empty(); }
  // side 0: the side the normal (v1-v0)x(v2-v0) points to; 1: the other one.
  std::span<const Hemisphere> hemispheres(std::uint32_t geom, std::uint32_t prim, int side) const;
  // The patch (polygon set) or triangle (other sets) whose hits before the offset may be
  // skipped: two triangles with the same surface_id; kInvalidId outside the scene.
  std::uint32_t surface_id(std::uint32_t geom, std::uint32_t prim) const;
  // The triangle's plane as the build used it: unit normal in `center`, offset n.v0 in `radius`.
  const Hemisphere* plane(std::uint32_t geom, std::uint32_t prim) const {
    if (geom + 1 >= first_.size() || prim >= first_[geom + 1] - first_[geom] || spheres_.empty()) return nullptr;
    return spheres_.data() + (first_[geom] + prim) * stride();
  }
  std::size_t memory_bytes() const {
    return spheres_.size() * sizeof(Hemisphere) + first_.size() * sizeof(std::size_t) +
           patch_.size() * sizeof(std::uint32_t);
  }
  std::size_t triangle_count() const { return first_.empty() ? 0 : first_.back(); }

  // Build constants (see the bound above).
  double slab() const { return slab_; }
  double extent() const { return extent_; }
  double max_abs() const { return max_abs_; }

 private:
  friend OriginOffsets build_origin_offsets(const Scene&, const WideBvhf&, HemisphereSet, const OriginOffsetOptions&);
  const Scene* scene_ = nullptr;
  HemisphereSet kind_ = HemisphereSet::center;
  int per_side_ = 1;
  std::vector<std::size_t> first_;    // per geometry: index of its first triangle; last = total
  // Per triangle: its plane, then per_side hemispheres on side 0, then on side 1.
  std::vector<Hemisphere> spheres_;
  std::size_t stride() const { return 1 + 2 * std::size_t(per_side_); }
  std::size_t slot(std::size_t tri, int side, int k) const {
    return tri * stride() + 1 + std::size_t(side != 0) * std::size_t(per_side_) + std::size_t(k);
  }
  std::vector<std::uint32_t> patch_;  // polygon set: patch id per triangle
  double slab_ = 0, extent_ = 0, max_abs_ = 0;
};

// Hemispheres of `kind` on both sides of every triangle of `scene`, radii found with a
// closest-point traversal of `bvh` (the float wide BVH built from the same scene, e.g.
// Accel::wide()). Degenerate triangles get radius 0. The scene must outlive the result.
OriginOffsets build_origin_offsets(const Scene& scene, const WideBvhf& bvh, HemisphereSet kind,
                                   const OriginOffsetOptions& opts = {});

// For a ray starting on triangle (geom, prim) at `origin`: the largest t such that no hit
// other than on that triangle (its patch, for the polygon set) can have t < the returned
// value, for every exact kernel. 0 when the ray lies in the triangle's plane, the origin is
// inside none of the hemispheres on the side `dir` points to, or the ids are out of range.
double safe_offset(const OriginOffsets& offsets, std::uint32_t geom, std::uint32_t prim, const Vec3d& origin,
                   const Vec3d& dir);

}  // namespace pierce
