#pragma once
// A ray as the SIMD levels read it (SimdRay): the broadcasts and per-axis choices that the node
// test (node_test.h) and the leaf test (leaf_test.h) take from the ray, made once per ray
// (prepare_simd_ray) or once per traversal (SimdRay::assign), and kept in registers by the loop.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <limits>

#include "pierce/simd/target.h"
#include "pierce/slab.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

// Octant of a direction: bit a set where component a is negative (WideNode::order's index).
template <typename T>
inline int octant(const TraversalRay<T>& r) {
  return (r.dir.x < 0 ? 1 : 0) | (r.dir.y < 0 ? 2 : 0) | (r.dir.z < 0 ? 4 : 0);
}

struct LeafLanes;
template <typename T>
struct BlockHits;

// What both SIMD levels precompute from the ray.
struct SimdRay {
  __m256 org[3], inv[3];
  __m256 pad;
  __m256 okx, oky, okz, sx, sy;  // triangle test: origin in the shear frame's axes, shear constants
  __m256 swap_mask[3];  // all bits set where inv[a] < 0 (slab() swaps the planes)
  // The fused node test's offsets (node_offsets()): fma(near plane, inv, near_c) is at most slab()'s
  // entry distance, fma(far plane, inv, far_c) at least widen() of its exit distance.
  __m256 near_c[3], far_c[3];
  float sz;
  std::uint32_t near_offset[3], far_offset[3];  // byte offsets of the near and far planes in a WideNode
  bool zero[3];
  bool any_zero;  // a direction component is zero: the slab test's parallel-axis path
  bool fused;     // the node test runs on fused multiply-adds (fused_slabs(); every inv and offset finite)
  int oct;
  // Byte offsets of the shear frame's axes kx, ky, kz within one corner of a TriBlock (v[k]): three
  // offsets serve all three corners, which keeps the leaf test's address registers few.
  std::uint32_t kx_offset, ky_offset, kz_offset;

  SimdRay() = default;  // filled by assign() or prepare_simd_ray()
  __attribute__((target(PIERCE_AVX2_TARGET))) SimdRay(const TraversalRay<float>& r, double scene_max_abs) {
    assign(r, scene_max_abs);
  }

  // The constructor's work, in place.
  __attribute__((target(PIERCE_AVX2_TARGET))) void assign(const TraversalRay<float>& r, double scene_max_abs) {
    fill(_mm_setr_ps(r.org[0], r.org[1], r.org[2], 0.0f), _mm_setr_ps(r.inv[0], r.inv[1], r.inv[2], 1.0f),
         int(r.zero[0]) | int(r.zero[1]) << 1 | int(r.zero[2]) << 2, r.kx, r.ky, r.kz, _mm_setr_ps(r.sx, r.sy, 0, 0),
         r.sz, r.pad, octant(r), scene_max_abs);
  }

  // Everything from the ray's values in registers (lanes 0-2: axes x, y, z): org and inv as in
  // TraversalRay, bit a of zero_bits its zero[a], sxy = (sx, sy, ...), and its kx, ky, kz, sz,
  // pad and octant. assign() passes a TraversalRay's fields; prepare_simd_ray() the values it
  // computed them from.
  __attribute__((target(PIERCE_AVX2_TARGET))) void fill(__m128 o, __m128 v, int zero_bits, int kx, int ky, int kz,
                                                         __m128 sxy, float sz_, float pad_, int octant_,
                                                         double scene_max_abs) {
    const __m256 o8 = _mm256_castps128_ps256(o), v8 = _mm256_castps128_ps256(v);
    // slab(): t0 from lo, t1 from hi, swapped where inv < 0 (arithmetic, not a branch: random
    // directions would mispredict it).
    const __m128 negative = _mm_cmplt_ps(v, _mm_setzero_ps());
    const __m256 negative8 = _mm256_castps128_ps256(negative);
    const auto swapped_bits = std::uint32_t(_mm_movemask_ps(negative));
    for (int a = 0; a < 3; ++a) {
      const __m256i lane = _mm256_set1_epi32(a);
      org[a] = _mm256_permutevar8x32_ps(o8, lane);
      inv[a] = _mm256_permutevar8x32_ps(v8, lane);
      swap_mask[a] = _mm256_permutevar8x32_ps(negative8, lane);
      zero[a] = (zero_bits >> a & 1) != 0;
      const auto lo = std::uint32_t(offsetof(WideNode<float>, lo) + sizeof(float) * kWideArity * std::size_t(a));
      const auto hi = std::uint32_t(offsetof(WideNode<float>, hi) + sizeof(float) * kWideArity * std::size_t(a));
      const std::uint32_t swapped = swapped_bits >> a & 1;
      near_offset[a] = lo + swapped * (hi - lo);
      far_offset[a] = hi - swapped * (hi - lo);
    }
    any_zero = (zero_bits & 7) != 0;
    pad = _mm256_set1_ps(pad_);
    constexpr auto kAxisBytes = std::uint32_t(sizeof(float) * kBlockLanes);
    kx_offset = std::uint32_t(kx) * kAxisBytes, ky_offset = std::uint32_t(ky) * kAxisBytes;
    kz_offset = std::uint32_t(kz) * kAxisBytes;
    okx = _mm256_permutevar8x32_ps(o8, _mm256_set1_epi32(kx));
    oky = _mm256_permutevar8x32_ps(o8, _mm256_set1_epi32(ky));
    okz = _mm256_permutevar8x32_ps(o8, _mm256_set1_epi32(kz));
    sx = _mm256_broadcastss_ps(sxy);
    sy = _mm256_permutevar8x32_ps(_mm256_castps128_ps256(sxy), _mm256_set1_epi32(1));
    sz = sz_;
    oct = octant_;
    node_offsets(o, v, pad_, scene_max_abs);
  }

  // The fused node test's offsets, per axis a with o = org[a], v = inv[a] (floats), and
  // y = (R + |o|) |v|, R the largest |coordinate| any box holds:
  //   near_c <= -o v - E and far_c >= -o v + F, with E = 3u y and F = (k + 5u) y + pad (plus room
  //   for the rounding of these constants; u = 2^-24, k = 2^-20, widen()'s factor).
  // Why fma(P, v, near_c) <= slab()'s (P - o) * v for a plane P with |P| <= R: the exact value
  // P v + near_c lies below fl(P - o) v, since fl(P - o) differs from P - o by at most u |P - o|
  // and |P - o| |v| <= y; rounding is monotone, so the rounded results keep the order. Likewise
  // fma(Q, v, far_c) >= widen((Q - o) * v), whose roundings add at most (k + 3u) y + pad (a
  // little more for subnormals, the 2^-140 terms). max/min over the axes and widen() are monotone,
  // so the node's [tn, wf] contains slab()'s widened interval for it, which contains that of every
  // box inside it, a triangle's own among them: "triangle hit => every enclosing box hit" holds.
  // The constants come from exact products (o v of two floats is exact in double) and double sums
  // (relative error 2^-53, inside the margins). Overflow to infinity only widens. With a zero or an
  // infinite inv (a direction component near 0), or an offset beyond the float range, the test runs
  // slab() and widen() themselves (slabs()).
  // org_f, inv_f: the ray's origin and inv in lanes 0-2 (lane 3 is not used).
  __attribute__((target(PIERCE_AVX2_TARGET))) void node_offsets(__m128 org_f, __m128 inv_f, float pad_,
                                                                double scene_max_abs) {
    constexpr double u = 0x1p-24, k = 0x1p-20, tiny = 0x1p-140;
    // A box's coordinates are its triangles' float corners: each within half an ulp of the scene's.
    const double reach = scene_max_abs * (1.0 + 0x1p-23);
    const __m256d abs_mask = _mm256_set1_pd(-0.0);
    const __m256d o = _mm256_cvtps_pd(org_f);
    const __m256d v = _mm256_cvtps_pd(inv_f);
    const __m256d y = _mm256_mul_pd(_mm256_add_pd(_mm256_set1_pd(reach), _mm256_andnot_pd(abs_mask, o)),
                                    _mm256_andnot_pd(abs_mask, v));
    const __m256d minus_ov = _mm256_xor_pd(_mm256_mul_pd(o, v), abs_mask);
    const __m256d e = _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(3 * u), y), _mm256_set1_pd(tiny));
    const __m256d f = _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(k + 5 * u), y),
                                    _mm256_set1_pd(double(pad_) * (1.0 + 0x1p-20) + tiny));
    alignas(16) float nc[4], fc[4];
    _mm_store_ps(nc, _mm256_cvtpd_ps(_mm256_sub_pd(minus_ov, e)));
    _mm_store_ps(fc, _mm256_cvtpd_ps(_mm256_add_pd(minus_ov, f)));
    for (int a = 0; a < 3; ++a) near_c[a] = _mm256_set1_ps(nc[a]), far_c[a] = _mm256_set1_ps(fc[a]);
    const __m128 abs_f = _mm_set1_ps(-0.0f), inf_f = _mm_set1_ps(std::numeric_limits<float>::infinity());
    const __m128 finite = _mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(abs_f, inv_f), inf_f),
                                     _mm_and_ps(_mm_cmplt_ps(_mm_andnot_ps(abs_f, _mm_load_ps(nc)), inf_f),
                                                _mm_cmplt_ps(_mm_andnot_ps(abs_f, _mm_load_ps(fc)), inf_f)));
    fused = !any_zero && (_mm_movemask_ps(finite) & 7) == 7;
  }

  // The node test (node_test.h): entry distances and widened exit distances of a node's eight boxes.
  __attribute__((target(PIERCE_AVX2_TARGET))) void fused_slabs(const WideNode<float>& n, __m256& tn, __m256& wf) const;
  __attribute__((target(PIERCE_AVX2_TARGET))) void slabs(const WideNode<float>& n, __m256& tn, __m256& wf,
                                                         __m256& outside) const;

  // The leaf test (leaf_test.h) of a block's eight lanes.
  __attribute__((target(PIERCE_AVX2_TARGET))) LeafLanes tri_test(const TriBlock<float>& b, float lo, float hi,
                                                                 BlockHits<float>& out) const;
  __attribute__((target(PIERCE_AVX2_TARGET))) void edges(const TriBlock<float>& b, __m256 e[3], __m256 z[3]) const;
  __attribute__((target(PIERCE_AVX2_TARGET))) __m256 finish(const TriBlock<float>& b, const __m256 e[3],
                                                            const __m256 z[3], float lo, float hi,
                                                            BlockHits<float>& out, __m256& overflow) const;
};

// A ray's TraversalRay and SimdRay, once per ray rather than once per traversal, for both SIMD
// levels (they read the same SimdRay). The same values as TraversalRay::assign() followed by
// SimdRay::assign() (the same conversions, divisions and comparisons, in the same rounding;
// kernels.PreparedRay checks every field bit for bit), but computed in registers: the axes of the
// origin, direction and inverse are lanes of one vector each, and the SimdRay's broadcasts are
// permutes of them, not loads of the fields just stored.
__attribute__((target(PIERCE_AVX2_TARGET))) inline void prepare_simd_ray(const Ray& r, double scene_max_abs,
                                                                       TraversalRay<float>& tr, SimdRay& sr) {
  static_assert(sizeof(Vec3d) == 3 * sizeof(double) && offsetof(Ray, dir) == sizeof(Vec3d) &&
                    offsetof(Ray, tmin) == 2 * sizeof(Vec3d),
                "a Ray's axes are read four doubles at a time");
  // Lane 3 (the next field of the Ray) is replaced: 0 in the origin, 1 in the direction.
  const __m128 o = _mm256_cvtpd_ps(_mm256_blend_pd(_mm256_loadu_pd(&r.org.x), _mm256_setzero_pd(), 8));
  const __m128 d = _mm256_cvtpd_ps(_mm256_blend_pd(_mm256_loadu_pd(&r.dir.x), _mm256_set1_pd(1.0), 8));
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  const __m128 is_zero = _mm_cmpeq_ps(d, zero);
  // 1 / d, 0 where d is 0 (dividing by 1 there, so no division by zero is made).
  const __m128 v = _mm_andnot_ps(is_zero, _mm_div_ps(one, _mm_blendv_ps(d, one, is_zero)));
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)),
               big = _mm_set1_ps(std::numeric_limits<float>::max());
  const __m128 a = _mm_and_ps(d, abs_mask);
  const bool finite = (_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(_mm_and_ps(o, abs_mask), big), _mm_cmple_ps(a, big))) &
                       7) == 7;
  const int zero_bits = _mm_movemask_ps(is_zero) & 7;
  // kz as assign() looks it up: (ax > ay) * 4 + (ax > az) * 2 + (ay > az). Lanes of a > (ay, az, ax)
  // and of a > (az, ax, ay).
  const int gt_next = _mm_movemask_ps(_mm_cmpgt_ps(a, _mm_permute_ps(a, _MM_SHUFFLE(3, 0, 2, 1))));
  const int gt_prev = _mm_movemask_ps(_mm_cmpgt_ps(a, _mm_permute_ps(a, _MM_SHUFFLE(3, 1, 0, 2))));
  const int kz = detail::kLargestAxis[(gt_next & 1) * 4 + (gt_prev & 1) * 2 + (gt_next >> 1 & 1)];
  const int negative_bits = _mm_movemask_ps(_mm_cmplt_ps(d, zero));
  const int pick = kz * 2 + (negative_bits >> kz & 1);
  const int kx = detail::kShearX[pick], ky = detail::kShearY[pick];
  // (d[kx], d[ky]) / d[kz], and 1 / d[kz] (the same division as inv's).
  const __m128 sxy = _mm_div_ps(_mm_permutevar_ps(d, _mm_setr_epi32(kx, ky, kz, kz)), _mm_permutevar_ps(d, _mm_set1_epi32(kz)));
  const float sz = _mm_cvtss_f32(_mm_permutevar_ps(v, _mm_set1_epi32(kz)));
  const auto store3 = [](Vec3<float>& out, __m128 x) {
    _mm_storel_pi(reinterpret_cast<__m64*>(&out.x), x);
    _mm_store_ss(&out.z, _mm_movehl_ps(x, x));
  };
  store3(tr.org, o);
  store3(tr.dir, d);
  store3(tr.inv, v);
  for (int k = 0; k < 3; ++k) tr.zero[k] = (zero_bits >> k & 1) != 0;
  tr.kx = kx, tr.ky = ky, tr.kz = kz;
  tr.sx = _mm_cvtss_f32(sxy);
  tr.sy = _mm_cvtss_f32(_mm_movehdup_ps(sxy));
  tr.sz = sz;
  tr.set_range(r);
  const float pad = TraversalRay<float>::pad_for(r, scene_max_abs);
  tr.pad = pad;
  tr.ok = zero_bits != 7 && finite;
  sr.fill(o, v, zero_bits, kx, ky, kz, sxy, sz, pad, negative_bits & 7, scene_max_abs);
}

}  // namespace pierce::simd
