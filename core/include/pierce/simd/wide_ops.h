#pragma once
// The two SIMD operations of the wide-BVH traversal, at each instruction-set level:
//  - node_hits: slab test of a node's eight child boxes against [lo, hi]; the result (mask, entry
//    distances, child references) comes in the node's near-to-far order for the ray's octant;
//  - tri_candidates: lanes of a leaf block that the exact triangle test may accept.
// Both are bit-for-bit the scalar arithmetic of slab.h and triangle.h, lane by lane: the same
// operations in the same order (the project builds with -ffp-contract=off, so nothing is fused),
// min/max with the scalar code's NaN behaviour, ordered compares. So the box test keeps its
// monotonicity and widened far bound, and a rejected lane is one the scalar test rejects too.
//
// Intrinsics behind our own run-time dispatch (simd_level.h): the functions carry GCC target
// attributes, and only code reached after the CPU check runs them. Width 8 fits one AVX2 register
// of floats; AVX-512 (VL) adds mask registers, so compares need no movemask and blends.
#include <immintrin.h>

#include <cstdint>
#include <limits>

#include "pierce/slab.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

// The scalar path: every level reduces to this on CPUs without AVX2, and the double BVH uses it.
template <typename T>
struct ScalarOps {
  static std::uint32_t node_hits(const WideNode<T>& n, const TraversalRay<T>& r, T lo, T hi, int oct, T* tn,
                                 NodeRef* child) {
    const std::uint32_t order = n.order[oct], valid = order >> 24;
    std::uint32_t mask = 0;
    for (int k = 0; k < kWideArity; ++k) {
      const int s = WideNode<T>::slot_at_rank(order, k);
      if (!(valid >> s & 1)) continue;
      const Span<T> sp = slab(r, Vec3<T>(n.lo[0][s], n.lo[1][s], n.lo[2][s]), Vec3<T>(n.hi[0][s], n.hi[1][s], n.hi[2][s]));
      tn[k] = sp.tn;
      child[k] = n.child[s];
      if (box_overlaps(r, sp, lo, hi)) mask |= 1u << k;
    }
    return mask;
  }
  static std::uint32_t tri_candidates(const TriBlock<T>& b, const TraversalRay<T>&) { return b.valid; }
};

constexpr float kWidenUp = 1.0f + 1.0f / float(1 << 20);  // TraversalRay::widen's factors, exact in float
constexpr float kWidenDown = 1.0f - 1.0f / float(1 << 20);

// Lane k of the result: the slot ranked k-th in `order` (WideNode::order).
__attribute__((target("avx2"))) inline __m256i rank_slots(std::uint32_t order) {
  const __m256i shifts = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  return _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(order)), shifts), _mm256_set1_epi32(7));
}

struct Avx2Ops {
  __attribute__((target("avx2"))) static std::uint32_t node_hits(const WideNode<float>& n,
                                                                  const TraversalRay<float>& r, float lo, float hi,
                                                                  int oct, float* tn_out, NodeRef* child_out) {
    __m256 tn = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    __m256 tf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    __m256 outside = _mm256_setzero_ps();
    for (int a = 0; a < 3; ++a) {
      const __m256 L = _mm256_load_ps(n.lo[a]), H = _mm256_load_ps(n.hi[a]);
      const __m256 o = _mm256_set1_ps(r.org[a]);
      if (r.zero[a]) {  // parallel to the slabs: inside or a miss
        outside = _mm256_or_ps(outside, _mm256_or_ps(_mm256_cmp_ps(o, L, _CMP_LT_OQ), _mm256_cmp_ps(o, H, _CMP_GT_OQ)));
        continue;
      }
      const __m256 inv = _mm256_set1_ps(r.inv[a]);
      __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(L, o), inv);
      __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(H, o), inv);
      if (r.inv[a] < 0.0f) std::swap(t0, t1);
      tn = _mm256_max_ps(t0, tn);  // t0 > tn ? t0 : tn, as slab()
      tf = _mm256_min_ps(t1, tf);  // t1 < tf ? t1 : tf
    }
    const __m256 up = _mm256_mul_ps(tf, _mm256_set1_ps(kWidenUp));
    const __m256 down = _mm256_mul_ps(tf, _mm256_set1_ps(kWidenDown));
    const __m256 scaled = _mm256_blendv_ps(down, up, _mm256_cmp_ps(tf, _mm256_setzero_ps(), _CMP_GE_OQ));
    const __m256 wf = _mm256_add_ps(scaled, _mm256_set1_ps(r.pad));
    const __m256 ok = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(tn, wf, _CMP_LE_OQ),
                                                  _mm256_cmp_ps(tn, _mm256_set1_ps(hi), _CMP_LE_OQ)),
                                    _mm256_cmp_ps(wf, _mm256_set1_ps(lo), _CMP_GE_OQ));
    const std::uint32_t order = n.order[oct];
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i valid = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(order >> 24)), bits), bits);
    const __m256 pass = _mm256_and_ps(_mm256_andnot_ps(outside, ok), _mm256_castsi256_ps(valid));
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutevar8x32_ps(tn, rank));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), rank));
    return std::uint32_t(_mm256_movemask_ps(_mm256_permutevar8x32_ps(pass, rank)));
  }

  __attribute__((target("avx2"))) static std::uint32_t tri_candidates(const TriBlock<float>& b,
                                                                       const TraversalRay<float>& r) {
    const __m256 ox = _mm256_set1_ps(r.org[r.kx]), oy = _mm256_set1_ps(r.org[r.ky]), oz = _mm256_set1_ps(r.org[r.kz]);
    const __m256 sx = _mm256_set1_ps(r.sx), sy = _mm256_set1_ps(r.sy);
    __m256 px[3], py[3];
    for (int c = 0; c < 3; ++c) {
      const __m256 z = _mm256_sub_ps(_mm256_load_ps(b.v[c][r.kz]), oz);
      px[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(b.v[c][r.kx]), ox), _mm256_mul_ps(sx, z));
      py[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(b.v[c][r.ky]), oy), _mm256_mul_ps(sy, z));
    }
    // triangle.h: U = cx*by - cy*bx, V = ax*cy - ay*cx, W = bx*ay - by*ax
    const __m256 U = _mm256_sub_ps(_mm256_mul_ps(px[2], py[1]), _mm256_mul_ps(py[2], px[1]));
    const __m256 V = _mm256_sub_ps(_mm256_mul_ps(px[0], py[2]), _mm256_mul_ps(py[0], px[2]));
    const __m256 W = _mm256_sub_ps(_mm256_mul_ps(px[1], py[0]), _mm256_mul_ps(py[1], px[0]));
    const __m256 zero = _mm256_setzero_ps();
    const __m256 sum = _mm256_add_ps(_mm256_add_ps(U, V), W);
    const __m256 abs_sum = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), sum);
    const __m256 finite = _mm256_cmp_ps(abs_sum, _mm256_set1_ps(std::numeric_limits<float>::infinity()), _CMP_LT_OQ);
    const __m256 any_zero = _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(U, zero, _CMP_EQ_OQ), _mm256_cmp_ps(V, zero, _CMP_EQ_OQ)),
                                         _mm256_cmp_ps(W, zero, _CMP_EQ_OQ));
    const __m256 all_pos = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(U, zero, _CMP_GT_OQ), _mm256_cmp_ps(V, zero, _CMP_GT_OQ)),
                                         _mm256_cmp_ps(W, zero, _CMP_GT_OQ));
    const __m256 all_neg = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(U, zero, _CMP_LT_OQ), _mm256_cmp_ps(V, zero, _CMP_LT_OQ)),
                                         _mm256_cmp_ps(W, zero, _CMP_LT_OQ));
    // Exact path for zero or non-finite edge functions (decided there), inside for equal signs.
    const __m256 cand = _mm256_or_ps(_mm256_or_ps(any_zero, _mm256_andnot_ps(finite, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))),
                                     _mm256_or_ps(all_pos, all_neg));
    return std::uint32_t(_mm256_movemask_ps(cand)) & b.valid;
  }
};

#define PIERCE_AVX512_TARGET "avx2,avx512f,avx512vl,avx512bw,avx512dq,bmi,bmi2"

struct Avx512Ops {
  __attribute__((target(PIERCE_AVX512_TARGET))) static std::uint32_t node_hits(const WideNode<float>& n,
                                                                                const TraversalRay<float>& r,
                                                                                float lo, float hi, int oct,
                                                                                float* tn_out, NodeRef* child_out) {
    const std::uint32_t order = n.order[oct];
    __m256 tn = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    __m256 tf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    __mmask8 inside = __mmask8(order >> 24);
    for (int a = 0; a < 3; ++a) {
      const __m256 L = _mm256_load_ps(n.lo[a]), H = _mm256_load_ps(n.hi[a]);
      const __m256 o = _mm256_set1_ps(r.org[a]);
      if (r.zero[a]) {  // parallel to the slabs: inside, not (o < L or o > H)
        inside &= _mm256_mask_cmp_ps_mask(_mm256_cmp_ps_mask(o, L, _CMP_NLT_UQ), o, H, _CMP_NGT_UQ);
        continue;
      }
      const __m256 inv = _mm256_set1_ps(r.inv[a]);
      __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(L, o), inv);
      __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(H, o), inv);
      if (r.inv[a] < 0.0f) std::swap(t0, t1);
      tn = _mm256_max_ps(t0, tn);
      tf = _mm256_min_ps(t1, tf);
    }
    const __mmask8 non_negative = _mm256_cmp_ps_mask(tf, _mm256_setzero_ps(), _CMP_GE_OQ);
    const __m256 scaled = _mm256_mask_mul_ps(_mm256_mul_ps(tf, _mm256_set1_ps(kWidenDown)), non_negative, tf,
                                             _mm256_set1_ps(kWidenUp));
    const __m256 wf = _mm256_add_ps(scaled, _mm256_set1_ps(r.pad));
    __mmask8 ok = _mm256_mask_cmp_ps_mask(inside, tn, wf, _CMP_LE_OQ);
    ok = _mm256_mask_cmp_ps_mask(ok, tn, _mm256_set1_ps(hi), _CMP_LE_OQ);
    ok = _mm256_mask_cmp_ps_mask(ok, wf, _mm256_set1_ps(lo), _CMP_GE_OQ);
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutexvar_ps(rank, tn));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutexvar_epi32(rank, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child))));
    return _mm256_movepi32_mask(_mm256_permutexvar_epi32(rank, _mm256_movm_epi32(ok)));
  }

  __attribute__((target(PIERCE_AVX512_TARGET))) static std::uint32_t tri_candidates(const TriBlock<float>& b,
                                                                                     const TraversalRay<float>& r) {
    const __m256 ox = _mm256_set1_ps(r.org[r.kx]), oy = _mm256_set1_ps(r.org[r.ky]), oz = _mm256_set1_ps(r.org[r.kz]);
    const __m256 sx = _mm256_set1_ps(r.sx), sy = _mm256_set1_ps(r.sy);
    __m256 px[3], py[3];
    for (int c = 0; c < 3; ++c) {
      const __m256 z = _mm256_sub_ps(_mm256_load_ps(b.v[c][r.kz]), oz);
      px[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(b.v[c][r.kx]), ox), _mm256_mul_ps(sx, z));
      py[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(b.v[c][r.ky]), oy), _mm256_mul_ps(sy, z));
    }
    const __m256 U = _mm256_sub_ps(_mm256_mul_ps(px[2], py[1]), _mm256_mul_ps(py[2], px[1]));
    const __m256 V = _mm256_sub_ps(_mm256_mul_ps(px[0], py[2]), _mm256_mul_ps(py[0], px[2]));
    const __m256 W = _mm256_sub_ps(_mm256_mul_ps(px[1], py[0]), _mm256_mul_ps(py[1], px[0]));
    const __m256 zero = _mm256_setzero_ps();
    const __m256 sum = _mm256_add_ps(_mm256_add_ps(U, V), W);
    const __mmask8 finite =
        _mm256_cmp_ps_mask(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), sum), _mm256_set1_ps(std::numeric_limits<float>::infinity()), _CMP_LT_OQ);
    const __mmask8 any_zero = _mm256_cmp_ps_mask(U, zero, _CMP_EQ_OQ) | _mm256_cmp_ps_mask(V, zero, _CMP_EQ_OQ) |
                              _mm256_cmp_ps_mask(W, zero, _CMP_EQ_OQ);
    const __mmask8 all_pos = _mm256_mask_cmp_ps_mask(
        _mm256_mask_cmp_ps_mask(_mm256_cmp_ps_mask(U, zero, _CMP_GT_OQ), V, zero, _CMP_GT_OQ), W, zero, _CMP_GT_OQ);
    const __mmask8 all_neg = _mm256_mask_cmp_ps_mask(
        _mm256_mask_cmp_ps_mask(_mm256_cmp_ps_mask(U, zero, _CMP_LT_OQ), V, zero, _CMP_LT_OQ), W, zero, _CMP_LT_OQ);
    return std::uint32_t(any_zero | __mmask8(~finite) | all_pos | all_neg) & b.valid;
  }
};

}  // namespace pierce::simd
