#pragma once
// A ray prepared once for traversal in precision T: reciprocal direction for slab tests,
// shear constants for the watertight triangle test (Woop, Benthin, Wald 2013), and the
// absolute padding used to keep box and triangle decisions consistent.
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pierce/ray.h"
#include "pierce/vec3.h"

namespace pierce {

template <typename T>
struct TraversalRay;

namespace detail {
// TraversalRay::make's lookup tables: the largest axis by (ax > ay) * 4 + (ax > az) * 2 + (ay > az),
// and kx, ky by kz * 2 + swap. Static, so a shared library reads them directly, not through the GOT
// as it would the static members of a class template.
static constexpr int kLargestAxis[8] = {2, 1, 2, 1, 2, 2, 0, 0};
static constexpr int kShearX[6] = {1, 2, 2, 0, 0, 1}, kShearY[6] = {2, 1, 0, 2, 1, 0};

// org, dir, zero and inv of tr, for TraversalRay::make (defined below it).
template <typename T>
void prepare_axes(const Ray& r, TraversalRay<T>& tr, T d[3], T inv[3], bool& finite);
}  // namespace detail

template <typename T>
struct TraversalRay {
  Vec3<T> org, dir, inv;
  bool zero[3] = {false, false, false};  // direction component exactly zero
  int kx = 0, ky = 1, kz = 2;
  T sx = 0, sy = 0, sz = 1;
  T tmin = 0, tmax = 0;
  T pad = 0;  // absolute slack in t for "does the ray meet this box at all"
  bool ok = false;  // valid(), decided once in make()

  // scene_max_abs: largest |coordinate| in the scene, for the padding.
  static TraversalRay make(const Ray& r, double scene_max_abs) {
    TraversalRay tr;
    tr.assign(r, scene_max_abs);
    return tr;
  }

  // make(), in place: a kernel prepares its ray member without building a copy on the stack, whose
  // wide loads over the fields just written in narrow stores would stall on store forwarding.
  void assign(const Ray& r, double scene_max_abs) {
    TraversalRay& tr = *this;
    T d[3], inv[3];
    bool finite;  // origin and direction finite in T
    detail::prepare_axes(r, tr, d, inv, finite);
    const T ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
    // kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2), looked up rather than branched on
    // (random directions would mispredict it).
    tr.kz = detail::kLargestAxis[(ax > ay) * 4 + (ax > az) * 2 + (ay > az)];
    // kx, ky follow kz cyclically, swapped where dir[kz] < 0 to keep the winding, so det's sign is
    // the facing: kx = (kz + 1 + swap) % 3, ky = (kz + 2 - swap) % 3, by kz * 2 + swap.
    const int pick = tr.kz * 2 + (d[tr.kz] < T(0));
    tr.kx = detail::kShearX[pick];
    tr.ky = detail::kShearY[pick];
    const T dz = d[tr.kz];
    tr.sx = d[tr.kx] / dz;
    tr.sy = d[tr.ky] / dz;
    tr.sz = inv[tr.kz];  // 1 / dz, the same division (dz, the largest component, is non-zero on a valid ray)
    tr.set_range(r);
    tr.pad = pad_for(r, scene_max_abs);
    tr.ok = !(tr.zero[0] & tr.zero[1] & tr.zero[2]) & finite;
  }

  // tmin and tmax of `r`, rounded inwards: hit distances are values of T, so t >= tmin holds for
  // the caller's double tmin exactly when it holds for the next T up (and likewise for tmax).
  void set_range(const Ray& r) {
    tmin = T(r.tmin);
    tmax = T(r.tmax);
    if (double(tmin) < r.tmin) tmin = std::nextafter(tmin, std::numeric_limits<T>::infinity());
    if (double(tmax) > r.tmax) tmax = std::nextafter(tmax, -std::numeric_limits<T>::infinity());
  }

  // 2^-20 of the t-span of the scene as seen from r's origin: far above the rounding of the
  // triangle test's projection, far below anything that costs traversal work.
  static T pad_for(const Ray& r, double scene_max_abs) {
    const double dmax = std::max({std::abs(r.dir.x), std::abs(r.dir.y), std::abs(r.dir.z)});
    return T((max_abs(r.org) + scene_max_abs) / (dmax > 0 ? dmax : 1.0) * 0x1p-20);
  }

  bool valid() const { return ok; }

  // Monotone widening of a box's far distance: every decision "does the ray meet box B"
  // uses tn(B) <= widen(tf(B)); monotone in tf, so a box containing another never fails
  // where the inner one passes.
  T widen(T tf) const {
    constexpr T k = T(1) / T(1 << 20);
    const T scaled = tf >= T(0) ? tf * (T(1) + k) : tf * (T(1) - k);
    return scaled + pad;
  }
};

namespace detail {

// org, dir, zero and inv of tr (inv 0 where the component is 0), the direction and its inverse
// as arrays, and whether origin and direction are finite in T.
template <typename T>
void prepare_axes(const Ray& r, TraversalRay<T>& tr, T d[3], T inv[3], bool& finite) {
#if defined(__SSE2__)
  if constexpr (std::is_same_v<T, float>) {
    // The same conversions, divisions and tests as the scalar loop below, four lanes at a time
    // (lane 3 is padding), in fewer instructions per ray: 181 against 202 in callgrind on
    // `pierce_bench_kernels --scene blob --columns 1`.
    const auto load = [](const Vec3d& v) {
      return _mm_movelh_ps(_mm_cvtpd_ps(_mm_loadu_pd(&v.x)), _mm_cvtpd_ps(_mm_load_sd(&v.z)));
    };
    const __m128 o = load(r.org), dv = load(r.dir), one = _mm_set1_ps(1.0f);
    const __m128 is_zero = _mm_cmpeq_ps(dv, _mm_setzero_ps());
    // Divides by 1 where the component is zero, so no division by zero is made.
    const __m128 q = _mm_div_ps(one, _mm_or_ps(_mm_and_ps(is_zero, one), _mm_andnot_ps(is_zero, dv)));
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)),
                 big = _mm_set1_ps(std::numeric_limits<float>::max());
    const __m128 in_range = _mm_and_ps(_mm_cmple_ps(_mm_and_ps(o, abs_mask), big),
                                       _mm_cmple_ps(_mm_and_ps(dv, abs_mask), big));
    finite = (_mm_movemask_ps(in_range) & 7) == 7;
    const int zero_bits = _mm_movemask_ps(is_zero);
    alignas(16) float ob[4], db[4], ib[4];
    _mm_store_ps(ob, o);
    _mm_store_ps(db, dv);
    _mm_store_ps(ib, _mm_andnot_ps(is_zero, q));
    for (int a = 0; a < 3; ++a) d[a] = db[a], inv[a] = ib[a], tr.zero[a] = (zero_bits >> a & 1) != 0;
    tr.org = {ob[0], ob[1], ob[2]};
    tr.dir = {d[0], d[1], d[2]};
    tr.inv = {inv[0], inv[1], inv[2]};
    return;
  }
#endif
  tr.org = Vec3<T>(r.org);
  tr.dir = Vec3<T>(r.dir);
  for (int a = 0; a < 3; ++a) {
    d[a] = tr.dir[std::size_t(a)];
    tr.zero[a] = d[a] == T(0);
    inv[a] = tr.zero[a] ? T(0) : T(1) / d[a];
  }
  tr.inv = {inv[0], inv[1], inv[2]};
  finite = all_finite(tr.org) && all_finite(tr.dir);
}

}  // namespace detail

}  // namespace pierce
