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
// An Ops object is made once per traversal from the ray: it holds the ray's broadcast constants and
// per-axis choices (near plane, parallel axes), so the loop keeps them in registers.
//
// Intrinsics behind our own run-time dispatch (simd_level.h): the functions carry GCC target
// attributes, and only code reached after the CPU check runs them. Width 8 fits one AVX2 register
// of floats; AVX-512 (VL) adds mask registers, so compares need no movemask and blends.
#include <immintrin.h>

#include <cstddef>
#include <cstdint>
#include <limits>

#include "pierce/slab.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

// Octant of a direction: bit a set where component a is negative (WideNode::order's index).
template <typename T>
inline int octant(const TraversalRay<T>& r) {
  return (r.dir.x < 0 ? 1 : 0) | (r.dir.y < 0 ? 2 : 0) | (r.dir.z < 0 ? 4 : 0);
}

// The scalar path: every level reduces to this on CPUs without AVX2, and the double BVH uses it.
template <typename T>
struct ScalarOps {
  const TraversalRay<T>& r;
  int oct;
  explicit ScalarOps(const TraversalRay<T>& ray) : r(ray), oct(octant(ray)) {}

  std::uint32_t node_hits(const WideNode<T>& n, T lo, T hi, T* tn, NodeRef* child) const {
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
  std::uint32_t tri_candidates(const TriBlock<T>& b) const { return b.valid; }
};

constexpr float kWidenUp = 1.0f + 1.0f / float(1 << 20);  // TraversalRay::widen's factors, exact in float
constexpr float kWidenDown = 1.0f - 1.0f / float(1 << 20);

// Lane k of the result: the slot ranked k-th in `order` (WideNode::order).
__attribute__((target("avx2"))) inline __m256i rank_slots(std::uint32_t order) {
  const __m256i shifts = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  return _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(order)), shifts), _mm256_set1_epi32(7));
}

// What both SIMD levels precompute from the ray.
struct SimdRay {
  __m256 org[3], inv[3];
  __m256 pad;
  __m256 okx, oky, okz, sx, sy;  // triangle test: origin in the shear frame's axes, shear constants
  std::uint32_t near_offset[3], far_offset[3];  // byte offsets of the near and far planes in a WideNode
  bool zero[3];
  int oct, kx, ky, kz;

  __attribute__((target("avx2"))) explicit SimdRay(const TraversalRay<float>& r) {
    for (int a = 0; a < 3; ++a) {
      org[a] = _mm256_set1_ps(r.org[a]);
      inv[a] = _mm256_set1_ps(r.inv[a]);
      zero[a] = r.zero[a];
      const auto lo = std::uint32_t(offsetof(WideNode<float>, lo) + sizeof(float) * kWideArity * std::size_t(a));
      const auto hi = std::uint32_t(offsetof(WideNode<float>, hi) + sizeof(float) * kWideArity * std::size_t(a));
      // slab(): t0 from lo, t1 from hi, swapped where inv < 0.
      near_offset[a] = r.inv[a] < 0.0f ? hi : lo;
      far_offset[a] = r.inv[a] < 0.0f ? lo : hi;
    }
    pad = _mm256_set1_ps(r.pad);
    kx = r.kx, ky = r.ky, kz = r.kz;
    okx = _mm256_set1_ps(r.org[kx]), oky = _mm256_set1_ps(r.org[ky]), okz = _mm256_set1_ps(r.org[kz]);
    sx = _mm256_set1_ps(r.sx), sy = _mm256_set1_ps(r.sy);
    oct = octant(r);
  }

  static const float* plane(const WideNode<float>& n, std::uint32_t offset) {
    return reinterpret_cast<const float*>(reinterpret_cast<const char*>(&n) + offset);
  }

  // Entry and exit distances of the eight boxes (slab(): max/min with its NaN behaviour); `outside`
  // gets the lanes a parallel axis misses.
  __attribute__((target("avx2"))) void slabs(const WideNode<float>& n, __m256& tn, __m256& tf, __m256& outside) const {
    tn = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
    tf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
    outside = _mm256_setzero_ps();
    for (int a = 0; a < 3; ++a) {
      if (zero[a]) {  // parallel to the slabs: inside or a miss
        const __m256 L = _mm256_load_ps(n.lo[a]), H = _mm256_load_ps(n.hi[a]);
        outside = _mm256_or_ps(outside, _mm256_or_ps(_mm256_cmp_ps(org[a], L, _CMP_LT_OQ),
                                                     _mm256_cmp_ps(org[a], H, _CMP_GT_OQ)));
        continue;
      }
      const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane(n, near_offset[a])), org[a]), inv[a]);
      const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane(n, far_offset[a])), org[a]), inv[a]);
      tn = _mm256_max_ps(t0, tn);  // t0 > tn ? t0 : tn, as slab()
      tf = _mm256_min_ps(t1, tf);  // t1 < tf ? t1 : tf
    }
  }

  // The edge functions U, V, W of triangle.h for the eight lanes, in the same operations.
  __attribute__((target("avx2"))) void edges(const TriBlock<float>& b, __m256& U, __m256& V, __m256& W) const {
    __m256 px[3], py[3];
    for (int c = 0; c < 3; ++c) {
      const __m256 z = _mm256_sub_ps(_mm256_load_ps(b.v[c][kz]), okz);
      px[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(b.v[c][kx]), okx), _mm256_mul_ps(sx, z));
      py[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(b.v[c][ky]), oky), _mm256_mul_ps(sy, z));
    }
    // U = cx*by - cy*bx, V = ax*cy - ay*cx, W = bx*ay - by*ax
    U = _mm256_sub_ps(_mm256_mul_ps(px[2], py[1]), _mm256_mul_ps(py[2], px[1]));
    V = _mm256_sub_ps(_mm256_mul_ps(px[0], py[2]), _mm256_mul_ps(py[0], px[2]));
    W = _mm256_sub_ps(_mm256_mul_ps(px[1], py[0]), _mm256_mul_ps(py[1], px[0]));
  }
};

struct Avx2Ops {
  SimdRay ray;
  __attribute__((target("avx2"))) explicit Avx2Ops(const TraversalRay<float>& r) : ray(r) {}

  __attribute__((target("avx2"))) std::uint32_t node_hits(const WideNode<float>& n, float lo, float hi, float* tn_out,
                                                          NodeRef* child_out) const {
    __m256 tn, tf, outside;
    ray.slabs(n, tn, tf, outside);
    const __m256 up = _mm256_mul_ps(tf, _mm256_set1_ps(kWidenUp));
    const __m256 down = _mm256_mul_ps(tf, _mm256_set1_ps(kWidenDown));
    const __m256 scaled = _mm256_blendv_ps(down, up, _mm256_cmp_ps(tf, _mm256_setzero_ps(), _CMP_GE_OQ));
    const __m256 wf = _mm256_add_ps(scaled, ray.pad);
    const __m256 ok = _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(tn, wf, _CMP_LE_OQ),
                                                  _mm256_cmp_ps(tn, _mm256_set1_ps(hi), _CMP_LE_OQ)),
                                    _mm256_cmp_ps(wf, _mm256_set1_ps(lo), _CMP_GE_OQ));
    const std::uint32_t order = n.order[ray.oct];
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i valid = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(order >> 24)), bits), bits);
    const __m256 pass = _mm256_and_ps(_mm256_andnot_ps(outside, ok), _mm256_castsi256_ps(valid));
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutevar8x32_ps(tn, rank));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), rank));
    return std::uint32_t(_mm256_movemask_ps(_mm256_permutevar8x32_ps(pass, rank)));
  }

  __attribute__((target("avx2"))) std::uint32_t tri_candidates(const TriBlock<float>& b) const {
    __m256 U, V, W;
    ray.edges(b, U, V, W);
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
    const std::uint32_t exact_path = std::uint32_t(_mm256_movemask_ps(any_zero)) | (~std::uint32_t(_mm256_movemask_ps(finite)) & 0xFFu);
    const std::uint32_t inside = std::uint32_t(_mm256_movemask_ps(_mm256_or_ps(all_pos, all_neg)));
    return (exact_path | inside) & b.valid;
  }
};

#define PIERCE_AVX512_TARGET "avx2,avx512f,avx512vl,avx512bw,avx512dq,bmi,bmi2"

struct Avx512Ops {
  SimdRay ray;
  __attribute__((target(PIERCE_AVX512_TARGET))) explicit Avx512Ops(const TraversalRay<float>& r) : ray(r) {}

  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t node_hits(const WideNode<float>& n, float lo, float hi,
                                                                        float* tn_out, NodeRef* child_out) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn, tf, outside;
    ray.slabs(n, tn, tf, outside);
    const __mmask8 inside = __mmask8(order >> 24) & ~_mm256_movepi32_mask(_mm256_castps_si256(outside));
    const __mmask8 non_negative = _mm256_cmp_ps_mask(tf, _mm256_setzero_ps(), _CMP_GE_OQ);
    const __m256 scaled = _mm256_mask_mul_ps(_mm256_mul_ps(tf, _mm256_set1_ps(kWidenDown)), non_negative, tf,
                                             _mm256_set1_ps(kWidenUp));
    const __m256 wf = _mm256_add_ps(scaled, ray.pad);
    __mmask8 ok = _mm256_mask_cmp_ps_mask(inside, tn, wf, _CMP_LE_OQ);
    ok = _mm256_mask_cmp_ps_mask(ok, tn, _mm256_set1_ps(hi), _CMP_LE_OQ);
    ok = _mm256_mask_cmp_ps_mask(ok, wf, _mm256_set1_ps(lo), _CMP_GE_OQ);
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutexvar_ps(rank, tn));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutexvar_epi32(rank, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child))));
    return _mm256_movepi32_mask(_mm256_permutexvar_epi32(rank, _mm256_movm_epi32(ok)));
  }

  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t tri_candidates(const TriBlock<float>& b) const {
    __m256 U, V, W;
    ray.edges(b, U, V, W);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 sum = _mm256_add_ps(_mm256_add_ps(U, V), W);
    const __mmask8 finite = _mm256_cmp_ps_mask(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), sum),
                                               _mm256_set1_ps(std::numeric_limits<float>::infinity()), _CMP_LT_OQ);
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
