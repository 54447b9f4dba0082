#pragma once
// A node's children that pass, as the traversal stores them: (tn, child) entries, eight at most,
// in two SIMD stores of four (left-packed by a table with AVX2, compressed with AVX-512), so the
// loop neither branches per child nor sorts.
#include <immintrin.h>

#include <cstdint>

#include "pierce/simd/target.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

// The slot of push_hits' nearest child, stored in lane `lane` (far to near by rank_slots_far_to_near,
// so lane k holds rank 7 - k).
inline int nearest_slot(std::uint32_t order, int lane) {
  return WideNode<float>::slot_at_rank(order, kWideArity - 1 - lane);
}

// The eight (tn, child) entries of a node in lane order, as NodeEntry<float> pairs: entries 0-3 in
// `first`, 4-7 in `second`.
__attribute__((target(PIERCE_AVX2_TARGET))) inline void entry_pairs(__m256 tn, __m256i child, __m256i& first, __m256i& second) {
  const __m256i t = _mm256_castps_si256(tn);
  const __m256i lo = _mm256_unpacklo_epi32(t, child), hi = _mm256_unpackhi_epi32(t, child);
  first = _mm256_permute2x128_si256(lo, hi, 0x20);
  second = _mm256_permute2x128_si256(lo, hi, 0x31);
}

// Lane k of a node's entry distances.
__attribute__((target(PIERCE_AVX2_TARGET))) inline float lane_tn(__m256 tn, int k) {
  return _mm_cvtss_f32(_mm256_castps256_ps128(_mm256_permutevar8x32_ps(tn, _mm256_set1_epi32(k))));
}

// Lane k of a node's entry distances and child references, as a NodeEntry.
__attribute__((target(PIERCE_AVX2_TARGET))) inline NodeEntry<float> lane_entry(__m256 tn, __m256i child, int k) {
  return {lane_tn(tn, k),
          NodeRef(_mm_cvtsi128_si32(_mm256_castsi256_si128(_mm256_permutevar8x32_epi32(child, _mm256_set1_epi32(k)))))};
}

// Left-packing four 64-bit entries by a 4-bit mask with one permute (AVX2 has no compress): the
// dword indices that move the selected entries to the front.
struct LeftPack4 {
  alignas(32) std::int32_t idx[16][8];
  constexpr LeftPack4() : idx{} {
    for (int m = 0; m < 16; ++m) {
      int k = 0;
      for (int e = 0; e < 4; ++e)
        if (m >> e & 1) idx[m][2 * k] = 2 * e, idx[m][2 * k + 1] = 2 * e + 1, ++k;
      for (; k < 4; ++k) idx[m][2 * k] = 0, idx[m][2 * k + 1] = 1;
    }
  }
};
inline constexpr LeftPack4 kLeftPack4{};

// The entries (tn, child) of the lanes in `mask`, stored at `top` in lane order: two left-packed
// stores of four entries each. Returns how many.
__attribute__((target(PIERCE_AVX2_TARGET))) inline std::uint32_t store_lanes(Avx2, __m256 tn, __m256i child,
                                                                             std::uint32_t mask,
                                                                             NodeEntry<float>* top) {
  __m256i first, second;
  entry_pairs(tn, child, first, second);
  const std::uint32_t m0 = mask & 15u, m1 = mask >> 4;
  const auto n0 = std::uint32_t(__builtin_popcount(m0));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(top),
                      _mm256_permutevar8x32_epi32(first, _mm256_load_si256(reinterpret_cast<const __m256i*>(kLeftPack4.idx[m0]))));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(top + n0),
                      _mm256_permutevar8x32_epi32(second, _mm256_load_si256(reinterpret_cast<const __m256i*>(kLeftPack4.idx[m1]))));
  return n0 + std::uint32_t(__builtin_popcount(m1));
}

// The same, compressed in registers (a compress straight to memory is slow on Zen 4).
__attribute__((target(PIERCE_AVX512_TARGET))) inline std::uint32_t store_lanes(Avx512, __m256 tn, __m256i child,
                                                                               std::uint32_t mask,
                                                                               NodeEntry<float>* top) {
  __m256i first, second;
  entry_pairs(tn, child, first, second);
  const auto m0 = __mmask8(mask & 15u), m1 = __mmask8(mask >> 4);
  const auto n0 = std::uint32_t(__builtin_popcount(m0));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(top), _mm256_maskz_compress_epi64(m0, first));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(top + n0), _mm256_maskz_compress_epi64(m1, second));
  return n0 + std::uint32_t(__builtin_popcount(m1));
}

}  // namespace pierce::simd
