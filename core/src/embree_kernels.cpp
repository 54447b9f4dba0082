#include "pierce/kernels/embree_kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pierce/kernels/bvh_common.h"

namespace pierce {

using detail::embree_representable;
using detail::empty_range;

namespace detail {

void embree_exact_intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* q = reinterpret_cast<EmbreeQuery*>(args->context);
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);  // rtcIntersect1: N == 1
  const Triangle<float>& tri = (*q->tris)[args->primID];
  if (q->counters) ++q->counters->prim_tests;
  using Mode = EmbreeQuery::Mode;
  const bool full = q->mode == Mode::closest_n && q->hits->size() == q->n;
  float hi = q->hi;
  if (q->mode == Mode::restart && q->best.valid()) hi = float(q->best.t);
  if (full) hi = float(q->hits->front().t);
  TriangleHit<float> th;
  if (!intersect(q->ray, tri.v0, tri.v1, tri.v2, q->lo, hi, th)) return;
  if (q->counters) ++q->counters->valid_hits;
  const HitKey key = order_key(tri, th);
  if (q->have_last && !q->order.less(q->last, key)) return;
  auto before = [q](const Hit& a, const Hit& b) { return q->order.less(a, b); };
  switch (q->mode) {
    case Mode::restart:
      if (q->best.valid() && !q->order.less(key, q->best)) return;
      q->best = make_hit(tri, th);
      rh->ray.tfar = q->embree_far(q->best.t);
      rh->hit.geomID = 0;
      rh->hit.primID = args->primID;
      return;
    case Mode::all:
      q->hits->push_back(make_hit(tri, th));
      return;
    case Mode::closest_n:
      if (full) {
        if (!q->order.less(key, q->hits->front())) return;
        std::pop_heap(q->hits->begin(), q->hits->end(), before);
        q->hits->pop_back();
      }
      q->hits->push_back(make_hit(tri, th));
      std::push_heap(q->hits->begin(), q->hits->end(), before);
      if (q->hits->size() == q->n) rh->ray.tfar = q->embree_far(q->hits->front().t);
      return;
  }
}

}  // namespace detail

EmbreeExactBase::EmbreeExactBase(const EmbreeAccel& acc, HitOrder order, EmbreeQuery::Mode mode, bool count)
    : acc_(&acc), scene_(acc.exact()), count_(count) {
  q_.mode = mode;
  q_.order = order;
  q_.tris = &acc.tris();
}

bool EmbreeExactBase::setup(const Ray& ray) {
  q_.ray.assign(ray, acc_->scene_max_abs());
  q_.have_last = false;
  q_.best = Hit{};
  live_ = false;
  if (q_.tris->empty() || !q_.ray.valid() || empty_range(ray)) return false;
  // Where the ray meets the (padded) scene box, in double: the Embree origin is moved there
  // so Embree's single-precision box test works near the scene, whatever the user's origin.
  const BBoxd& b = acc_->scene().bounds();
  const double pad = double(acc_->box_pad());
  double te = ray.tmin, tx = ray.tmax;
  for (int a = 0; a < 3; ++a) {
    const double lo = b.lo[a] - pad, hi = b.hi[a] + pad;
    if (ray.dir[a] == 0.0) {
      if (ray.org[a] < lo || ray.org[a] > hi) return false;
      continue;
    }
    double t0 = (lo - ray.org[a]) / ray.dir[a], t1 = (hi - ray.org[a]) / ray.dir[a];
    if (t0 > t1) std::swap(t0, t1);
    te = std::max(te, t0), tx = std::min(tx, t1);
  }
  if (te > tx + q_.slack(tx)) return false;
  const double dmax = max_abs(ray.dir);
  const double span_t = acc_->scene().scale() / dmax;
  q_.t_base = te - (std::ldexp(span_t, -12) + q_.slack(te));
  org_ = ray.org + ray.dir * q_.t_base;
  // Embree sees the direction scaled by a power of two to magnitude ~1 (exact), so that any
  // float direction is within its range; its t is scaled back in embree_near/far.
  q_.t_scale = std::ldexp(1.0, std::ilogb(dmax));
  dir_ = ray.dir * (1.0 / q_.t_scale);
  // Rebased origins lie near the scene; a scene beyond Embree's range cannot be traced by it.
  if (!embree_representable(org_)) return false;
  live_ = true;
  return true;
}

void EmbreeExactBase::trace(double lo, double hi) {
  RTCRayHit rh = native_rayhit(org_, dir_, q_.embree_near(lo),
                               std::isinf(hi) ? std::numeric_limits<float>::infinity() : q_.embree_far(hi));
  q_.lo = float(lo);
  q_.hi = float(hi);
  // Pointers into this object are set per query, not once: kernels are values and may have moved.
  q_.counters = count_ ? &counters : nullptr;
  rtcInitIntersectContext(&q_.ctx);
  rtcIntersect1(scene_, &q_.ctx, &rh);
  if (count_) ++counters.traversal_steps;
}

void EmbreeRestartKernel::begin(const Ray& ray, std::size_t) { setup(ray); }

bool EmbreeRestartKernel::next(Hit& out) {
  if (!live_) return false;
  q_.best = Hit{};
  const double lo = q_.have_last ? std::max(double(q_.ray.tmin), q_.last.t) : double(q_.ray.tmin);
  trace(lo, q_.ray.tmax);
  if (!q_.best.valid()) {
    live_ = false;
    return false;
  }
  out = q_.last = q_.best;
  q_.have_last = true;
  return true;
}

void EmbreeFilterKernel::begin(const Ray& ray, std::size_t) {
  hits_.clear();
  pos_ = 0;
  if (!setup(ray)) return;
  q_.hits = &hits_;
  trace(q_.ray.tmin, q_.ray.tmax);
  sort_hits(hits_.begin(), hits_.end(), q_.order);
  // Embree may offer a primitive twice (e.g. spatial-split builds): keep one.
  hits_.erase(std::unique(hits_.begin(), hits_.end(), same_hit), hits_.end());
}

bool EmbreeFilterKernel::next(Hit& out) {
  if (pos_ >= hits_.size()) return false;
  out = hits_[pos_++];
  return true;
}

void EmbreeNodeCullKernel::begin(const Ray& ray, std::size_t max_hits) {
  batch_.clear();
  pos_ = 0;
  exhausted_ = !setup(ray);
  q_.n = max_hits == 0 ? std::numeric_limits<std::size_t>::max() : max_hits;
}

void EmbreeNodeCullKernel::collect() {
  batch_.clear();
  pos_ = 0;
  const double lo = q_.have_last ? std::max(double(q_.ray.tmin), q_.last.t) : double(q_.ray.tmin);
  q_.hits = &batch_;
  trace(lo, q_.ray.tmax);
  std::sort_heap(batch_.begin(), batch_.end(), q_.order);
}

bool EmbreeNodeCullKernel::next(Hit& out) {
  if (pos_ == batch_.size()) {
    if (exhausted_) return false;
    collect();
    if (batch_.size() < q_.n) exhausted_ = true;
    if (batch_.empty()) return false;
  }
  out = q_.last = batch_[pos_++];
  q_.have_last = true;
  return true;
}

EpsilonKernel::EpsilonKernel(const EmbreeAccel& acc, const KernelOptions& o)
    : scene_(acc.native()), eps_(o.epsilon_rel * acc.scene().scale()), count_(o.count) {}

bool embree_first_hit(const EmbreeAccel& acc, const Ray& ray, Hit& out) {
  // `epsilon`'s first query: one place decides which rays Embree can take (a zero direction or a
  // NaN range among them) and fills the record.
  EpsilonKernel first(acc);
  first.begin(ray);
  return first.next(out);
}

}  // namespace pierce
