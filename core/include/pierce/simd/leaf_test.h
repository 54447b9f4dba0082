#pragma once
// The triangle test of a leaf block's eight lanes at the SIMD levels. A lane whose edge functions
// are non-zero and finite has exact signs already and is finished in SIMD (det, t, the clamp into
// the triangle's slab interval, the range); only lanes with a zero or non-finite edge function (or
// an overflowed t) go to the exact scalar test (triangle.h). The lanes finished here are bit for
// bit the scalar arithmetic of slab.h and triangle.h: the same operations in the same order (the
// project builds with -ffp-contract=off, so nothing is fused), min/max with the scalar code's NaN
// behaviour, ordered compares; a rejected lane is one the scalar test rejects too.
#include <immintrin.h>

#include <cstdint>
#include <limits>

#include "pierce/simd/node_test.h"
#include "pierce/simd/ray_setup.h"
#include "pierce/simd/target.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

// A leaf block's test: lanes for the exact scalar test, and lanes finished in SIMD (a hit within the
// range the block was tested against; BlockHits holds their t, det and edge functions).
struct LeafLanes {
  std::uint32_t exact, hit;
};
template <typename T>
struct BlockHits {
  alignas(32) T t[kBlockLanes], det[kBlockLanes], e[3][kBlockLanes];
};

// The hit record of lane l finished in SIMD, as finish_intersect makes it (the signs were those of
// the values, so nothing was fixed).
template <typename T>
inline TriangleHit<T> lane_hit(const BlockHits<T>& h, int l, SumOrder so) {
  return input_frame_hit(h.t[l], h.det[l], h.e[0][l], h.e[1][l], h.e[2][l], so);
}

// Corner c's coordinates along the axis at `offset` (SimdRay's kx_offset, ky_offset or kz_offset),
// eight lanes.
inline const float* block_axis(const TriBlock<float>& b, int c, std::uint32_t offset) {
  return reinterpret_cast<const float*>(reinterpret_cast<const char*>(b.v[c]) + offset);
}

// The edge functions U, V, W of triangle.h for the eight lanes, in the same operations, and the
// corners' kz coordinates relative to the origin.
__attribute__((target(PIERCE_AVX2_TARGET))) inline void SimdRay::edges(const TriBlock<float>& b, __m256 e[3],
                                                               __m256 z[3]) const {
  __m256 px[3], py[3];
  for (int c = 0; c < 3; ++c) {
    z[c] = _mm256_sub_ps(_mm256_load_ps(block_axis(b, c, kz_offset)), okz);
    px[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(block_axis(b, c, kx_offset)), okx), _mm256_mul_ps(sx, z[c]));
    py[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(block_axis(b, c, ky_offset)), oky), _mm256_mul_ps(sy, z[c]));
  }
  // U = cx*by - cy*bx, V = ax*cy - ay*cx, W = bx*ay - by*ax
  e[0] = _mm256_sub_ps(_mm256_mul_ps(px[2], py[1]), _mm256_mul_ps(py[2], px[1]));
  e[1] = _mm256_sub_ps(_mm256_mul_ps(px[0], py[2]), _mm256_mul_ps(py[0], px[2]));
  e[2] = _mm256_sub_ps(_mm256_mul_ps(px[1], py[0]), _mm256_mul_ps(py[1], px[0]));
}

// finish_intersect<true> for every lane, in the same operations (min and max with std::min's
// and std::max's operand order, so signed zeros come out alike): all bits set in the lanes that
// hit within [lo, hi]. `overflow` gets the lanes whose t overflowed (the scalar test's other
// formula).
__attribute__((target(PIERCE_AVX2_TARGET))) inline __m256 SimdRay::finish(const TriBlock<float>& b, const __m256 e[3],
                                                                   const __m256 z[3], float lo, float hi,
                                                                   BlockHits<float>& out, __m256& overflow) const {
  const __m256 zero_v = _mm256_setzero_ps();
  const __m256 inf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  const __m256 abs_mask = _mm256_set1_ps(-0.0f);
  const __m256 det = _mm256_add_ps(_mm256_add_ps(e[0], e[1]), e[2]);
  const __m256 szv = _mm256_set1_ps(sz);
  const __m256 tnum = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(e[0], _mm256_mul_ps(szv, z[0])),
                                                  _mm256_mul_ps(e[1], _mm256_mul_ps(szv, z[1]))),
                                    _mm256_mul_ps(e[2], _mm256_mul_ps(szv, z[2])));
  const __m256 t = _mm256_div_ps(tnum, det);
  overflow = _mm256_cmp_ps(_mm256_andnot_ps(abs_mask, t), inf, _CMP_NLT_UQ);  // not finite
  // slab() of the triangle's box.
  __m256 tn = _mm256_set1_ps(-std::numeric_limits<float>::infinity()), tf = inf, outside = zero_v;
  for (int a = 0; a < 3; ++a) {
    const __m256 v0 = _mm256_load_ps(b.v[0][a]), v1 = _mm256_load_ps(b.v[1][a]), v2 = _mm256_load_ps(b.v[2][a]);
    const __m256 L = _mm256_min_ps(v2, _mm256_min_ps(v1, v0));
    const __m256 H = _mm256_max_ps(v2, _mm256_max_ps(v1, v0));
    if (zero[a]) {
      outside = _mm256_or_ps(outside, _mm256_or_ps(_mm256_cmp_ps(org[a], L, _CMP_LT_OQ),
                                                   _mm256_cmp_ps(org[a], H, _CMP_GT_OQ)));
      continue;
    }
    // slab()'s swap where inv < 0, as a blend of the planes: a branch on the direction's sign
    // is mispredicted at each new ray.
    const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_blendv_ps(L, H, swap_mask[a]), org[a]), inv[a]);
    const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_blendv_ps(H, L, swap_mask[a]), org[a]), inv[a]);
    tn = _mm256_max_ps(t0, tn);
    tf = _mm256_min_ps(t1, tf);
  }
  const __m256 wf = widen(tf, pad);
  const __m256 t_hi = _mm256_blendv_ps(tn, tf, _mm256_cmp_ps(tf, tn, _CMP_GT_OQ));
  __m256 tc = _mm256_blendv_ps(t, t_hi, _mm256_cmp_ps(t, t_hi, _CMP_GT_OQ));
  tc = _mm256_blendv_ps(tc, tn, _mm256_cmp_ps(t, tn, _CMP_LT_OQ));
  __m256 ok = _mm256_andnot_ps(outside, _mm256_cmp_ps(det, zero_v, _CMP_NEQ_UQ));
  ok = _mm256_andnot_ps(_mm256_cmp_ps(tn, wf, _CMP_GT_OQ), ok);
  ok = _mm256_and_ps(ok, _mm256_and_ps(_mm256_cmp_ps(tc, _mm256_set1_ps(lo), _CMP_GE_OQ),
                                       _mm256_cmp_ps(tc, _mm256_set1_ps(hi), _CMP_LE_OQ)));
  ok = _mm256_and_ps(ok, _mm256_cmp_ps(_mm256_andnot_ps(abs_mask, tc), inf, _CMP_LT_OQ));
  _mm256_store_ps(out.t, tc);
  _mm256_store_ps(out.det, det);
  for (int k = 0; k < 3; ++k) _mm256_store_ps(out.e[k], e[k]);
  return _mm256_andnot_ps(overflow, ok);
}

// The block's test (ScalarOps::tri_test, with lanes finished here). `inside`: lanes with edge
// functions non-zero, finite and of one sign; `exact`: lanes with a zero or non-finite one
// (decided by the exact scalar test).
__attribute__((target(PIERCE_AVX2_TARGET))) inline LeafLanes SimdRay::tri_test(const TriBlock<float>& b, float lo,
                                                                      float hi, BlockHits<float>& out) const {
  __m256 e[3], z[3];
  edges(b, e, z);
  const __m256 zero = _mm256_setzero_ps();
  const __m256 sum = _mm256_add_ps(_mm256_add_ps(e[0], e[1]), e[2]);
  const __m256 finite = _mm256_cmp_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), sum),
                                      _mm256_set1_ps(std::numeric_limits<float>::infinity()), _CMP_LT_OQ);
  const __m256 any_zero = _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(e[0], zero, _CMP_EQ_OQ),
                                                    _mm256_cmp_ps(e[1], zero, _CMP_EQ_OQ)),
                                      _mm256_cmp_ps(e[2], zero, _CMP_EQ_OQ));
  // Sign bits that differ from e[0]'s. Outside the exact lanes every edge function is finite and
  // non-zero (a finite sum has no infinite or NaN term), so "all three of one sign" is "no sign
  // bit differs", as the ordered compares > 0 and < 0 would decide it.
  const __m256 sign_differs = _mm256_or_ps(_mm256_xor_ps(e[0], e[1]), _mm256_xor_ps(e[0], e[2]));
  const std::uint32_t exact =
      b.valid & (std::uint32_t(_mm256_movemask_ps(any_zero)) | ~std::uint32_t(_mm256_movemask_ps(finite)));
  const std::uint32_t inside = b.valid & ~std::uint32_t(_mm256_movemask_ps(sign_differs)) & ~exact;
  if (inside == 0) return {exact, 0};
  __m256 overflow;
  const auto hit = std::uint32_t(_mm256_movemask_ps(finish(b, e, z, lo, hi, out, overflow)));
  return {exact | (inside & std::uint32_t(_mm256_movemask_ps(overflow))), inside & hit};
}

}  // namespace pierce::simd
