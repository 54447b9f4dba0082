#pragma once
// Kernels on Embree's BVH and traversal (rtcIntersect1), all exact through Pierce's
// triangle test in a user geometry:
//  - embree-restart: closest hit after the last one in the total order, per next();
//  - embree-filter: all hits gathered by the filter (AGGW15), sorted, duplicates removed;
//  - embree-nodecull: N closest with the filter shrinking tfar once N are held (GWA16).
// And the inexact baseline on Embree's native triangles:
//  - epsilon: closest hit, then relaunch from t + epsilon.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pierce/embree_accel.h"
#include "pierce/kernel_options.h"
#include "pierce/embree_query.h"

namespace pierce {

namespace detail {
// Embree asserts (and its math breaks down) beyond this magnitude of ray coordinates.
inline constexpr double kEmbreeLarge = 1.8e18;
inline bool embree_representable(const Vec3d& v) { return all_finite(v) && max_abs(v) < kEmbreeLarge; }
// No t satisfies tmin <= t <= tmax.
inline bool empty_range(const Ray& r) { return !(r.tmin <= r.tmax); }
}  // namespace detail

// Shared ray setup: rebasing and the Embree-frame ray for a query.
class EmbreeExactBase {
 protected:
  EmbreeExactBase(const EmbreeAccel& acc, HitOrder order, EmbreeQuery::Mode mode, bool count);
  // Prepares q_ for `ray`; false if the ray cannot meet the scene.
  bool setup(const Ray& ray);
  // Runs one rtcIntersect1 over Pierce-frame range [lo, hi].
  void trace(double lo, double hi);

  const EmbreeAccel* acc_;
  RTCScene scene_;  // acc_->exact(), asked for once
  EmbreeQuery q_;
  Vec3d org_, dir_;
  bool live_ = false;
  bool count_ = false;

 public:
  Counters counters;  // kept only when constructed with count = true
};

// The constructors of the exact Embree kernels: the query mode is the kernel's.
template <EmbreeQuery::Mode M>
class EmbreeExactKernel : public EmbreeExactBase {
 public:
  EmbreeExactKernel(const EmbreeAccel& acc, const KernelOptions& o) : EmbreeExactBase(acc, o.order, M, o.count) {}
};

class EmbreeRestartKernel : public EmbreeExactKernel<EmbreeQuery::Mode::restart> {
 public:
  using EmbreeExactKernel::EmbreeExactKernel;
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);
};

class EmbreeFilterKernel : public EmbreeExactKernel<EmbreeQuery::Mode::all> {
 public:
  using EmbreeExactKernel::EmbreeExactKernel;
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);

 private:
  std::vector<Hit> hits_;
  std::size_t pos_ = 0;
};

class EmbreeNodeCullKernel : public EmbreeExactKernel<EmbreeQuery::Mode::closest_n> {
 public:
  using EmbreeExactKernel::EmbreeExactKernel;
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);

 private:
  void collect();
  std::vector<Hit> batch_;
  std::size_t pos_ = 0;
  bool exhausted_ = true;
};

// Inexact baseline: what a rendering kernel does. epsilon = epsilon_rel * scene diagonal.
// begin() and next() are inline so that HitIterator::collect runs a query as one function, with
// Embree's float ray made once per ray, as plain Embree code does (the bench compares the two).
class EpsilonKernel {
 public:
  explicit EpsilonKernel(const EmbreeAccel& acc, const KernelOptions& o = {});

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    query_ = native_rayhit(ray, float(std::max(0.0, ray.tmin)));
    dir_ = ray.dir;
    relaunch_ = false;
    // Rays Embree cannot take (its ray.valid(): finite, |coordinates| < 1.8e18, no NaN range)
    // get no hits; so do empty ranges.
    const RTCRay& r = query_.ray;
    const Vec3f org(r.org_x, r.org_y, r.org_z), dir(r.dir_x, r.dir_y, r.dir_z);
    done_ = !detail::embree_representable(Vec3d(org)) || !detail::embree_representable(Vec3d(dir)) ||
            max_abs(dir) == 0.f || detail::empty_range(ray) || std::isnan(r.tfar);
  }

  bool next(Hit& out) {
    if (done_) return false;
    RTCRayHit rh = query_;
    // The relaunch point after the last hit, worked out only when a next hit is asked for (a
    // caller that wants one hit never pays for it).
    if (relaunch_)
      rh.ray.tnear =
          std::max(float(double(last_t_) + eps_), std::nextafter(last_t_, std::numeric_limits<float>::infinity()));
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(scene_, &ctx, &rh);
    if (count_) ++counters.traversal_steps;
    const float t = rh.ray.tfar;
    // No hit, or a distance beyond float range (tiny direction): not representable. Degenerate
    // triangles are not in the native scene (DegenerateTriangles::leave_out), so every hit counts.
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || !std::isfinite(t)) {
      done_ = true;
      return false;
    }
    last_t_ = t;
    relaunch_ = true;
    out.t = t;  // every field of the record is set
    out.geom = rh.hit.geomID;
    out.prim = rh.hit.primID;
    out.u = rh.hit.u;
    out.v = rh.hit.v;
    // Embree's geometric normal is (v1-v0)x(v2-v0) as Hit::ng, computed in its own rounding: no
    // reading of the scene's vertices per hit (this is the inexact baseline, measured for speed).
    out.ng = Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    out.enter = dot(Vec3d(out.ng), dir_) < 0.0;
    return true;
  }

  Counters counters;  // kept only when constructed with count = true

 private:
  RTCScene scene_;  // the accel's native(), asked for once
  double eps_;
  bool count_;
  RTCRayHit query_;  // the ray as Embree takes it, from the ray's tmin (no hit yet)
  Vec3d dir_;        // the ray's direction, for Hit::enter
  float last_t_ = 0;       // the last hit's t
  bool relaunch_ = false;  // a hit was returned: the next query starts beyond last_t_
  bool done_ = true;
};

// Embree's own first hit on native triangles (the speed reference; not exact).
bool embree_first_hit(const EmbreeAccel& acc, const Ray& ray, Hit& out);

}  // namespace pierce
