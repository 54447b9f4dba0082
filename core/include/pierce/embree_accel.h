#pragma once
// Embree 3 scenes over a Pierce scene:
//  - `exact`: one user geometry whose primitives are Pierce's triangles, intersected by
//    Pierce's watertight test. Embree builds and traverses the BVH; the kernels' filters
//    rank hits in the total order. Boxes are padded and rays rebased so Embree's
//    non-robust box test never culls a box holding a hit Pierce's test reports.
//  - `native`: Embree's own triangles (Möller-Trumbore, not watertight), used by the
//    epsilon baseline and as the first-hit speed reference.
#include <embree3/rtcore.h>

#include <memory>

#include "pierce/bvh.h"
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

class EmbreeAccel {
 public:
  // `tris` must outlive this object (it is the float BVH's triangle array).
  EmbreeAccel(const Scene& scene, const HugePageVector<Triangle<float>>& tris);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  RTCScene exact() const { return exact_; }
  RTCScene native() const { return native_; }
  const Scene& scene() const { return *scene_; }
  const HugePageVector<Triangle<float>>& tris() const { return *tris_; }
  double scene_max_abs() const { return max_abs_; }
  float box_pad() const { return pad_; }

 private:
  const Scene* scene_;
  const HugePageVector<Triangle<float>>* tris_;
  double max_abs_ = 0;
  float pad_ = 0;
  RTCDevice device_ = nullptr;
  RTCScene exact_ = nullptr;
  RTCScene native_ = nullptr;
  void* bounds_data_ = nullptr;
};

}  // namespace pierce
