#pragma once
// Plain Embree 3 code, written the way an Embree user writes it, as the bench's reference rows:
// one device, one scene of native triangles from the mesh (float vertex and index buffers, one
// Embree geometry per Pierce geometry), rtcIntersect1 with an RTCIntersectContext. Nothing of
// Pierce's BVH, triangle test or rebasing is used. Not exact: each row's wrong rays are counted
// against the exact kernels.
#include <embree3/rtcore.h>

#include <atomic>
#include <cstddef>
#include <vector>

#include "pierce/hit.h"
#include "pierce/ray.h"
#include "pierce/scene.h"

namespace pierce::bench {

class EmbreeReference {
 public:
  // robust: RTC_SCENE_FLAG_ROBUST (Embree's watertight mode).
  EmbreeReference(const Scene& scene, bool robust);
  ~EmbreeReference();
  EmbreeReference(const EmbreeReference&) = delete;
  EmbreeReference& operator=(const EmbreeReference&) = delete;

  double build_seconds() const { return build_seconds_; }
  // Bytes Embree allocated for the scene (its memory monitor), geometry buffers included.
  std::size_t bytes() const { return std::size_t(bytes_.load()); }

  // rtcIntersect1: the closest hit.
  bool first_hit(const Ray& ray, Hit& out) const;
  // Every hit through an intersection filter that records and rejects it, then sorted by
  // (t, geomID, primID) with repeated (geomID, primID) removed; at most max_hits (0 = all) kept.
  void all_hits(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) const;
  // Lexicographic restart: rtcIntersect1 from the last hit's t with a filter rejecting every hit
  // not after it in (t, geomID, primID), until max_hits (0 = all) or no more.
  void restart_hits(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) const;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double build_seconds_ = 0;
  std::atomic<long long> bytes_{0};
};

}  // namespace pierce::bench
