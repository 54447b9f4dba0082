#pragma once
// The node test of the SIMD levels: a slab test of a node's eight child boxes against the active
// range [lo, hi], giving each slot its entry distance and whether it passes. One fused multiply-add
// per plane (as Embree's), with per-ray offsets that make each box's interval contain the one
// slab() and widen() give it (SimdRay::node_offsets, ray_setup.h): every box a triangle lies in
// still passes wherever the triangle's own box passes, which is all the exact test relies on.
// Where the offsets cannot be used (SimdRay::fused false) the test is slab() and widen() themselves.
#include <immintrin.h>

#include <cstdint>
#include <limits>

#include "pierce/simd/ray_setup.h"
#include "pierce/simd/target.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

constexpr float kWidenUp = 1.0f + 1.0f / float(1 << 20);  // TraversalRay::widen's factors, exact in float
constexpr float kWidenDown = 1.0f - 1.0f / float(1 << 20);

// box_overlaps() for eight boxes, decision for decision: tn <= wf && tn <= hi && wf >= lo is
// max(lo, tn) <= min(hi, wf), one compare after two independent steps instead of three dependent
// ones. They agree because lo <= hi (seed() starts no traversal otherwise, and the policies only
// narrow hi down to hits at or after lo; were it not so, no triangle could be accepted either) and
// no operand is NaN: lo and hi are not, tn and tf never are (slabs() starts from -inf and +inf
// and keeps the non-NaN operand), and where wf is NaN (an infinite far distance plus an infinite
// pad) min(hi, wf) passes the NaN on, so the compare fails as the scalar one does.
__attribute__((target(PIERCE_AVX2_TARGET))) inline __m256 in_range(__m256 tn, __m256 wf, float lo, float hi) {
  return _mm256_cmp_ps(_mm256_max_ps(_mm256_set1_ps(lo), tn), _mm256_min_ps(_mm256_set1_ps(hi), wf), _CMP_LE_OQ);
}
__attribute__((target(PIERCE_AVX512_TARGET))) inline __mmask8 in_range(__mmask8 lanes, __m256 tn, __m256 wf,
                                                                         float lo, float hi) {
  return _mm256_mask_cmp_ps_mask(lanes, _mm256_max_ps(_mm256_set1_ps(lo), tn), _mm256_min_ps(_mm256_set1_ps(hi), wf),
                                 _CMP_LE_OQ);
}

// TraversalRay::widen for eight far distances, bit for bit: tf * (1 + k) for tf >= 0 and tf * (1 - k)
// below is the larger of the two products (rounding is monotone), so a max replaces the sign test
// and the blend (one dependent step less on the way to the next node). A far distance is never
// NaN: slabs() starts its min from +inf and keeps the non-NaN operand.
__attribute__((target(PIERCE_AVX2_TARGET))) inline __m256 widen(__m256 tf, __m256 pad) {
  return _mm256_add_ps(_mm256_max_ps(_mm256_mul_ps(tf, _mm256_set1_ps(kWidenDown)),
                                     _mm256_mul_ps(tf, _mm256_set1_ps(kWidenUp))),
                       pad);
}

// Lane k of the result: the slot ranked k-th in `order` (WideNode::order).
__attribute__((target(PIERCE_AVX2_TARGET))) inline __m256i rank_slots(std::uint32_t order) {
  const __m256i shifts = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  return _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(order)), shifts), _mm256_set1_epi32(7));
}

// Lane k of the result: the slot ranked (7-k)-th, so lanes run far to near.
__attribute__((target(PIERCE_AVX2_TARGET))) inline __m256i rank_slots_far_to_near(std::uint32_t order) {
  const __m256i shifts = _mm256_setr_epi32(21, 18, 15, 12, 9, 6, 3, 0);
  return _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(order)), shifts), _mm256_set1_epi32(7));
}

// The plane at byte `offset` of a node (SimdRay's near_offset and far_offset), eight slots.
inline const float* node_plane(const WideNode<float>& n, std::uint32_t offset) {
  return reinterpret_cast<const float*>(reinterpret_cast<const char*>(&n) + offset);
}

// Entry distances and widened exit distances of the eight boxes where `fused` (node_offsets()):
// one fused multiply-add per plane. Never NaN: every offset and inv is finite and inv non-zero,
// and a plane is finite or, in an empty slot, infinite. An empty slot's planes are +inf (lo) and
// -inf (hi) (set_wide_boxes), so its entry distance is +inf and its exit distance -inf whatever
// the direction: it fails in_range() without the node's valid bits.
__attribute__((target(PIERCE_AVX2_TARGET))) inline void SimdRay::fused_slabs(const WideNode<float>& n, __m256& tn,
                                                                     __m256& wf) const {
  tn = _mm256_fmadd_ps(_mm256_load_ps(node_plane(n, near_offset[0])), inv[0], near_c[0]);
  wf = _mm256_fmadd_ps(_mm256_load_ps(node_plane(n, far_offset[0])), inv[0], far_c[0]);
  for (int a = 1; a < 3; ++a) {
    tn = _mm256_max_ps(_mm256_fmadd_ps(_mm256_load_ps(node_plane(n, near_offset[a])), inv[a], near_c[a]), tn);
    wf = _mm256_min_ps(_mm256_fmadd_ps(_mm256_load_ps(node_plane(n, far_offset[a])), inv[a], far_c[a]), wf);
  }
}

// The same without `fused`: slab() and widen() themselves (max/min with slab()'s NaN behaviour);
// `outside` gets the lanes a parallel axis misses.
__attribute__((target(PIERCE_AVX2_TARGET))) inline void SimdRay::slabs(const WideNode<float>& n, __m256& tn, __m256& wf,
                                                               __m256& outside) const {
  outside = _mm256_setzero_ps();
  tn = _mm256_set1_ps(-std::numeric_limits<float>::infinity());
  __m256 tf = _mm256_set1_ps(std::numeric_limits<float>::infinity());
  for (int a = 0; a < 3; ++a) {
    if (zero[a]) {  // parallel to the slabs: inside or a miss
      const __m256 L = _mm256_load_ps(n.lo[a]), H = _mm256_load_ps(n.hi[a]);
      outside = _mm256_or_ps(outside, _mm256_or_ps(_mm256_cmp_ps(org[a], L, _CMP_LT_OQ),
                                                   _mm256_cmp_ps(org[a], H, _CMP_GT_OQ)));
      continue;
    }
    const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node_plane(n, near_offset[a])), org[a]), inv[a]);
    const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(node_plane(n, far_offset[a])), org[a]), inv[a]);
    tn = _mm256_max_ps(t0, tn);  // t0 > tn ? t0 : tn, as slab()
    tf = _mm256_min_ps(t1, tf);  // t1 < tf ? t1 : tf
  }
  wf = widen(tf, pad);
}

// What passed a node's test, at each level: bit s of slots() for slot s, bit k of ranked(rank)
// for the slot in lane k of `rank` (rank_slots, rank_slots_far_to_near). AVX2 keeps all bits set
// in the lanes that pass; AVX-512 a mask register, so its compares need no movemask and blends.
struct Avx2Pass {
  __m256 lanes;
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t slots() const {
    return std::uint32_t(_mm256_movemask_ps(lanes));
  }
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t ranked(__m256i rank) const {
    return std::uint32_t(_mm256_movemask_ps(_mm256_permutevar8x32_ps(lanes, rank)));
  }
};
struct Avx512Pass {
  __mmask8 lanes;
  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t slots() const { return lanes; }
  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t ranked(__m256i rank) const {
    return _mm256_movepi32_mask(_mm256_permutexvar_epi32(rank, _mm256_movm_epi32(lanes)));
  }
};

// The node test at each level: entry distances by slot in `tn`, and the children that pass.
__attribute__((target(PIERCE_AVX2_TARGET))) inline Avx2Pass slot_hits(Avx2, const SimdRay& ray,
                                                                       const WideNode<float>& n, std::uint32_t order,
                                                                       float lo, float hi, __m256& tn) {
  __m256 wf;
  if (ray.fused) [[likely]] {
    ray.fused_slabs(n, tn, wf);
    return {in_range(tn, wf, lo, hi)};  // an empty slot fails it (fused_slabs())
  }
  __m256 outside;
  ray.slabs(n, tn, wf, outside);
  const __m256 ok = in_range(tn, wf, lo, hi);
  const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256i valid = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(order >> 24)), bits), bits);
  return {_mm256_and_ps(_mm256_andnot_ps(outside, ok), _mm256_castsi256_ps(valid))};
}
__attribute__((target(PIERCE_AVX512_TARGET))) inline Avx512Pass slot_hits(Avx512, const SimdRay& ray,
                                                                           const WideNode<float>& n,
                                                                           std::uint32_t order, float lo, float hi,
                                                                           __m256& tn) {
  __m256 wf;
  if (ray.fused) [[likely]] {
    ray.fused_slabs(n, tn, wf);
    return {in_range(__mmask8(0xff), tn, wf, lo, hi)};  // an empty slot fails it (fused_slabs())
  }
  __m256 outside;
  ray.slabs(n, tn, wf, outside);
  const __mmask8 inside = __mmask8(order >> 24) & ~_mm256_movepi32_mask(_mm256_castps_si256(outside));
  return {in_range(inside, tn, wf, lo, hi)};
}

}  // namespace pierce::simd
