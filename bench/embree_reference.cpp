#include "embree_reference.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "pierce/embree_accel.h"

namespace pierce::bench {

namespace {

// The context an Embree user extends to hand data to a filter (Embree passes it back).
struct FilterContext {
  RTCIntersectContext ctx;
  std::vector<Hit>* hits = nullptr;  // all hits: every candidate is recorded and rejected
  Hit after;                         // restart: only hits after this one are accepted
};

Hit candidate(const RTCFilterFunctionNArguments* args) {
  Hit h;
  h.t = RTCRayN_tfar(args->ray, args->N, 0);
  h.geom = RTCHitN_geomID(args->hit, args->N, 0);
  h.prim = RTCHitN_primID(args->hit, args->N, 0);
  h.u = RTCHitN_u(args->hit, args->N, 0);
  h.v = RTCHitN_v(args->hit, args->N, 0);
  return h;
}

void record_and_reject(const RTCFilterFunctionNArguments* args) {
  if (args->valid[0] == 0) return;
  const auto* c = reinterpret_cast<const FilterContext*>(args->context);
  c->hits->push_back(candidate(args));
  args->valid[0] = 0;
}

bool lex_less(const Hit& a, const Hit& b) {
  if (a.t != b.t) return a.t < b.t;
  if (a.geom != b.geom) return a.geom < b.geom;
  return a.prim < b.prim;
}

void accept_after(const RTCFilterFunctionNArguments* args) {
  if (args->valid[0] == 0) return;
  const auto* c = reinterpret_cast<const FilterContext*>(args->context);
  if (!lex_less(c->after, candidate(args))) args->valid[0] = 0;
}

bool monitor(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<long long>*>(user)->fetch_add(bytes);
  return true;
}

Hit to_hit(const RTCRayHit& rh) {
  Hit h;
  h.t = rh.ray.tfar;
  h.geom = rh.hit.geomID;
  h.prim = rh.hit.primID;
  h.u = rh.hit.u;
  h.v = rh.hit.v;
  h.ng = Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  h.enter = false;
  return h;
}

RTCSceneFlags flags_for(ReferenceUse use) {
  switch (use) {
    case ReferenceUse::first_hit:
      return RTC_SCENE_FLAG_NONE;
    case ReferenceUse::robust_first_hit:
      return RTC_SCENE_FLAG_ROBUST;
    case ReferenceUse::filters:
      return RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
  }
  return RTC_SCENE_FLAG_NONE;
}

}  // namespace

EmbreeReference::EmbreeReference(const Scene& scene, ReferenceUse use) : use_(use) {
  device_ = rtcNewDevice("threads=0");
  if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
  rtcSetDeviceMemoryMonitorFunction(device_, monitor, &bytes_);
  const auto t0 = std::chrono::steady_clock::now();
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, flags_for(use));
  attach_native_triangles(device_, scene_, scene, DegenerateTriangles::keep);  // as a plain Embree user would
  rtcCommitScene(scene_);
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (const RTCError err = rtcGetDeviceError(device_); err != RTC_ERROR_NONE)
    throw std::runtime_error("Embree error " + std::to_string(int(err)) + " building the reference scene");
}

EmbreeReference::~EmbreeReference() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool EmbreeReference::first_hit(const Ray& ray, Hit& out) const {
  RTCRayHit rh = native_rayhit(ray, float(std::max(0.0, ray.tmin)));
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(scene_, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  out = to_hit(rh);
  return true;
}

void EmbreeReference::all_hits(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) const {
  const std::size_t begin = out.size();
  FilterContext fc;
  rtcInitIntersectContext(&fc.ctx);
  fc.ctx.filter = record_and_reject;
  fc.hits = &out;
  RTCRayHit rh = native_rayhit(ray, float(std::max(0.0, ray.tmin)));
  rtcIntersect1(scene_, &fc.ctx, &rh);
  std::sort(out.begin() + std::ptrdiff_t(begin), out.end(), lex_less);
  // The same triangle reported twice (Embree may visit a primitive from two leaves).
  auto last = std::unique(out.begin() + std::ptrdiff_t(begin), out.end(),
                          [](const Hit& a, const Hit& b) { return a.geom == b.geom && a.prim == b.prim; });
  out.erase(last, out.end());
  if (max_hits != 0 && out.size() - begin > max_hits) out.resize(begin + max_hits);
}

void EmbreeReference::restart_hits(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) const {
  FilterContext fc;
  rtcInitIntersectContext(&fc.ctx);
  fc.ctx.filter = accept_after;
  fc.after.t = -std::numeric_limits<double>::infinity();
  fc.after.geom = fc.after.prim = 0;
  float tnear = float(std::max(0.0, ray.tmin));
  for (std::size_t n = 0; max_hits == 0 || n < max_hits; ++n) {
    RTCRayHit rh = native_rayhit(ray, tnear);
    rtcIntersect1(scene_, &fc.ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    out.push_back(to_hit(rh));
    fc.after = out.back();
    tnear = rh.ray.tfar;
  }
}

}  // namespace pierce::bench
