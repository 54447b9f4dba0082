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

// What a reference scene is for, and so its flags, as an Embree user would set them: none for
// first hits, RTC_SCENE_FLAG_ROBUST (Embree's watertight mode) for robust first hits, and
// RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION where a filter in the context gathers hits.
enum class ReferenceUse { first_hit, robust_first_hit, filters };

class EmbreeReference {
 public:
  EmbreeReference(const Scene& scene, ReferenceUse use);
  ~EmbreeReference();
  EmbreeReference(const EmbreeReference&) = delete;
  EmbreeReference& operator=(const EmbreeReference&) = delete;

  ReferenceUse use() const { return use_; }
  double build_seconds() const { return build_seconds_; }
  // Bytes Embree allocated for the scene (its memory monitor), geometry buffers included.
  std::size_t bytes() const { return std::size_t(bytes_.load()); }

  // rtcIntersect1: the closest hit.
  bool first_hit(const Ray& ray, Hit& out) const;
  // The two below need a scene made for ReferenceUse::filters: elsewhere Embree ignores the filter.
  // Every hit through an intersection filter that records and rejects it, then sorted by
  // (t, geomID, primID) with repeated (geomID, primID) removed; at most max_hits (0 = all) kept.
  void all_hits(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) const;
  // Lexicographic restart: rtcIntersect1 from the last hit's t with a filter rejecting every hit
  // not after it in (t, geomID, primID), until max_hits (0 = all) or no more.
  void restart_hits(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) const;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  ReferenceUse use_;
  double build_seconds_ = 0;
  std::atomic<long long> bytes_{0};
};

}  // namespace pierce::bench
