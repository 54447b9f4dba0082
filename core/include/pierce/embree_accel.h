#pragma once
// Embree 3 scenes over a Pierce scene:
//  - `exact`: one user geometry whose primitives are Pierce's triangles, intersected by
//    Pierce's watertight test. Embree builds and traverses the BVH; the kernels' filters
//    rank hits in the total order. Boxes are padded and rays rebased so Embree's
//    non-robust box test never culls a box holding a hit Pierce's test reports.
//  - `native`: Embree's own triangles (Möller-Trumbore, not watertight), used by the
//    epsilon baseline and as the first-hit speed reference.
#include <embree3/rtcore.h>

#include <functional>
#include <memory>
#include <mutex>

#include "pierce/bvh.h"
#include "pierce/ray.h"
#include "pierce/scene.h"

namespace pierce {

// What attach_native_triangles does with the triangles Pierce finds degenerate (Geometry::degenerate).
// `leave_out` gives them an index past the vertex buffer, which Embree's build skips as invalid, so
// no hit on them needs a lookup per hit (the epsilon kernel); `keep` passes them on as a plain
// Embree user would (the bench's reference code).
enum class DegenerateTriangles { keep, leave_out };

// Adds `scene`'s triangles to `target` as Embree's own triangle geometries (float vertices), one
// per Pierce geometry, attached in order so that Embree's geometry and primitive ids are Pierce's.
// Does not commit `target`.
void attach_native_triangles(RTCDevice device, RTCScene target, const Scene& scene, DegenerateTriangles degenerate);

// An Embree query from `org` along `dir` over [tnear, tfar] (floats, as Embree takes them), every
// field set: mask all ones (Debian's Embree is built with ray masks), no hit yet. Inline: it is
// part of every epsilon query and of the bench's plain-Embree rows, which must not pay a call.
inline RTCRayHit native_rayhit(Vec3d org, Vec3d dir, float tnear, float tfar) {
  RTCRayHit rh;
  rh.ray.org_x = float(org.x), rh.ray.org_y = float(org.y), rh.ray.org_z = float(org.z);
  rh.ray.dir_x = float(dir.x), rh.ray.dir_y = float(dir.y), rh.ray.dir_z = float(dir.z);
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}
// The same for `ray`, from tnear to ray.tmax.
inline RTCRayHit native_rayhit(const Ray& ray, float tnear) {
  return native_rayhit(ray.org, ray.dir, tnear, float(ray.tmax));
}

// Each scene is built when first asked for (thread-safe), so a kernel builds only what it uses: the
// epsilon kernel neither the exact scene nor the float BVH whose triangles that scene holds.
// Kernels ask once, when they are made, and keep the handle.
class EmbreeAccel {
 public:
  // Gives the float BVH's triangle array, which must outlive this object; called once, when the
  // exact scene is first asked for.
  using TriangleSource = std::function<const HugePageVector<Triangle<float>>&()>;
  EmbreeAccel(const Scene& scene, TriangleSource tris);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  RTCScene exact() const;
  RTCScene native() const;
  const Scene& scene() const { return *scene_; }
  // The exact scene's primitives (building that scene if it is not built yet).
  const HugePageVector<Triangle<float>>& tris() const;
  double scene_max_abs() const { return max_abs_; }
  float box_pad() const { return pad_; }

 private:
  void build_exact() const;
  void build_native() const;
  void committed(RTCScene scene, const char* what) const;

  const Scene* scene_;
  TriangleSource tris_source_;
  double max_abs_ = 0;
  float pad_ = 0;
  RTCDevice device_ = nullptr;
  mutable std::once_flag exact_once_, native_once_;
  mutable const HugePageVector<Triangle<float>>* tris_ = nullptr;
  mutable RTCScene exact_ = nullptr;
  mutable RTCScene native_ = nullptr;
  mutable void* bounds_data_ = nullptr;
};

}  // namespace pierce
