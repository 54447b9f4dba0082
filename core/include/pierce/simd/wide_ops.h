#pragma once
// The SIMD operations of the wide-BVH traversal, at each instruction-set level:
//  - node_hits: slab test of a node's eight child boxes against [lo, hi]; the result (mask, entry
//    distances, child references) comes in the node's near-to-far order for the ray's octant;
//  - push_hits: the same test, with the children that pass stored onto a depth-first stack far to
//    near in two SIMD stores (compressed with AVX-512, left-packed by a table with AVX2), so the
//    loop neither branches per child nor sorts; it also gives the slots of the stored children
//    other than the nearest, so the loop prefetches them by addresses read from the node;
//  - push_all: the same test, with every child that passes stored in slot order and no branch on
//    how many did (a breadth-first traversal's queue);
//  - tri_test: the triangle test of a leaf block's eight lanes. A lane whose edge functions are
//    non-zero and finite has exact signs already and is finished in SIMD (det, t, the clamp into
//    the triangle's slab interval, the range); only lanes with a zero or non-finite edge function
//    (or an overflowed t) go to the exact scalar test (triangle.h). The scalar level sends them all.
// The leaf test is bit for bit the scalar arithmetic of slab.h and triangle.h, lane by lane: the
// same operations in the same order (the project builds with -ffp-contract=off, so nothing is
// fused), min/max with the scalar code's NaN behaviour, ordered compares; a rejected lane is one the
// scalar test rejects too. The node test of the SIMD levels is one fused multiply-add per plane
// (as Embree's), with per-ray offsets that make each box's interval contain the one slab() and
// widen() give it (SimdRay::node_offsets): every box a triangle lies in still passes wherever the
// triangle's own box passes, which is all the exact test relies on. The scalar level keeps slab().
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

#define PIERCE_AVX2_TARGET "avx2,fma,bmi,bmi2"
#define PIERCE_AVX512_TARGET "avx2,fma,avx512f,avx512vl,avx512bw,avx512dq,bmi,bmi2"

// Octant of a direction: bit a set where component a is negative (WideNode::order's index).
template <typename T>
inline int octant(const TraversalRay<T>& r) {
  return (r.dir.x < 0 ? 1 : 0) | (r.dir.y < 0 ? 2 : 0) | (r.dir.z < 0 ? 4 : 0);
}

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

// The scalar path: every level reduces to this on CPUs without AVX2, and the double BVH uses it.
template <typename T>
struct ScalarOps {
  const TraversalRay<T>& r;
  int oct;
  ScalarOps(const TraversalRay<T>& ray, double /*scene_max_abs*/) : r(ray), oct(octant(ray)) {}

  std::uint32_t node_hits(const WideNode<T>& n, T lo, T hi, T* tn, NodeRef* child) const {
    return node_hits(n, n.order[oct], lo, hi, tn, child);
  }
  // The same, with the node's order for the ray's octant already read.
  std::uint32_t node_hits(const WideNode<T>& n, std::uint32_t order, T lo, T hi, T* tn, NodeRef* child) const {
    const std::uint32_t valid = order >> 24;
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
  // The children that pass, stored at `top` far to near (the nearest last, also given in `nearest`,
  // so the loop can descend into it without reading it back); returns how many.
  // `others`: the slots of the stored children other than the nearest, for the caller's prefetch
  // (read from the node, which is in the cache, rather than from the entries just stored).
  std::uint32_t push_hits(const WideNode<T>& n, T lo, T hi, NodeEntry<T>* top, NodeEntry<T>& nearest,
                          std::uint32_t& others) const {
    T tn[kWideArity];
    NodeRef child[kWideArity];
    const std::uint32_t order = n.order[oct];
    const std::uint32_t mask = node_hits(n, order, lo, hi, tn, child);
    std::uint32_t count = 0;
    others = 0;
    for (int k = kWideArity - 1; k >= 0; --k)
      if (mask >> k & 1) {
        top[count++] = {tn[k], child[k]};
        others |= 1u << WideNode<T>::slot_at_rank(order, k);
      }
    if (count > 0) {
      nearest = top[count - 1];
      others &= ~(1u << WideNode<T>::slot_at_rank(order, __builtin_ctz(mask)));
    }
    return count;
  }
  // Every child that passes, stored at `top` in any order (a breadth-first traversal's queue); returns
  // the slots stored (as many entries as bits), for the caller's prefetch.
  std::uint32_t push_all(const WideNode<T>& n, T lo, T hi, NodeEntry<T>* top) const {
    T tn[kWideArity];
    NodeRef child[kWideArity];
    const std::uint32_t order = n.order[oct];
    std::uint32_t slots = 0;
    for (std::uint32_t m = node_hits(n, order, lo, hi, tn, child); m != 0; m &= m - 1) {
      const int k = __builtin_ctz(m);
      *top++ = {tn[k], child[k]};
      slots |= 1u << WideNode<T>::slot_at_rank(order, k);
    }
    return slots;
  }
  // Every lane to the scalar test.
  LeafLanes tri_test(const TriBlock<T>& b, T /*lo*/, T /*hi*/, BlockHits<T>& /*out*/) const { return {b.valid, 0}; }
};

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

  // Corner c's coordinates along the axis at `offset` (kx_offset, ky_offset or kz_offset), eight lanes.
  static const float* axis(const TriBlock<float>& b, int c, std::uint32_t offset) {
    return reinterpret_cast<const float*>(reinterpret_cast<const char*>(b.v[c]) + offset);
  }

  static const float* plane(const WideNode<float>& n, std::uint32_t offset) {
    return reinterpret_cast<const float*>(reinterpret_cast<const char*>(&n) + offset);
  }

  // Entry distances and widened exit distances of the eight boxes where `fused` (node_offsets()):
  // one fused multiply-add per plane. Never NaN: every offset and inv is finite and inv non-zero,
  // and a plane is finite or, in an empty slot, infinite. An empty slot's planes are +inf (lo) and
  // -inf (hi) (set_wide_boxes), so its entry distance is +inf and its exit distance -inf whatever
  // the direction: it fails in_range() without the node's valid bits.
  __attribute__((target(PIERCE_AVX2_TARGET))) void fused_slabs(const WideNode<float>& n, __m256& tn,
                                                               __m256& wf) const {
    tn = _mm256_fmadd_ps(_mm256_load_ps(plane(n, near_offset[0])), inv[0], near_c[0]);
    wf = _mm256_fmadd_ps(_mm256_load_ps(plane(n, far_offset[0])), inv[0], far_c[0]);
    for (int a = 1; a < 3; ++a) {
      tn = _mm256_max_ps(_mm256_fmadd_ps(_mm256_load_ps(plane(n, near_offset[a])), inv[a], near_c[a]), tn);
      wf = _mm256_min_ps(_mm256_fmadd_ps(_mm256_load_ps(plane(n, far_offset[a])), inv[a], far_c[a]), wf);
    }
  }

  // The same without `fused`: slab() and widen() themselves (max/min with slab()'s NaN behaviour);
  // `outside` gets the lanes a parallel axis misses.
  __attribute__((target(PIERCE_AVX2_TARGET))) void slabs(const WideNode<float>& n, __m256& tn, __m256& wf,
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
      const __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane(n, near_offset[a])), org[a]), inv[a]);
      const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane(n, far_offset[a])), org[a]), inv[a]);
      tn = _mm256_max_ps(t0, tn);  // t0 > tn ? t0 : tn, as slab()
      tf = _mm256_min_ps(t1, tf);  // t1 < tf ? t1 : tf
    }
    wf = widen(tf, pad);
  }

  // The edge functions U, V, W of triangle.h for the eight lanes, in the same operations, and the
  // corners' kz coordinates relative to the origin.
  __attribute__((target(PIERCE_AVX2_TARGET))) void edges(const TriBlock<float>& b, __m256 e[3], __m256 z[3]) const {
    __m256 px[3], py[3];
    for (int c = 0; c < 3; ++c) {
      z[c] = _mm256_sub_ps(_mm256_load_ps(axis(b, c, kz_offset)), okz);
      px[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(axis(b, c, kx_offset)), okx), _mm256_mul_ps(sx, z[c]));
      py[c] = _mm256_sub_ps(_mm256_sub_ps(_mm256_load_ps(axis(b, c, ky_offset)), oky), _mm256_mul_ps(sy, z[c]));
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
  __attribute__((target(PIERCE_AVX2_TARGET))) __m256 finish(const TriBlock<float>& b, const __m256 e[3], const __m256 z[3],
                                                float lo, float hi, BlockHits<float>& out, __m256& overflow) const {
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
  __attribute__((target(PIERCE_AVX2_TARGET))) LeafLanes tri_test(const TriBlock<float>& b, float lo, float hi,
                                                     BlockHits<float>& out) const {
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

struct Avx2Ops {
  // The ray's SimdRay, read where it was made (a copy's wide loads of the fields just stored
  // would stall on store forwarding).
  const SimdRay& ray;
  explicit Avx2Ops(const SimdRay& prepared) : ray(prepared) {}

  // Entry distances by slot; the result has all bits set in the lanes of the children that pass.
  __attribute__((target(PIERCE_AVX2_TARGET))) __m256 slot_hits(const WideNode<float>& n, std::uint32_t order, float lo, float hi,
                                                   __m256& tn) const {
    __m256 wf;
    if (ray.fused) [[likely]] {
      ray.fused_slabs(n, tn, wf);
      return in_range(tn, wf, lo, hi);  // an empty slot fails it (fused_slabs())
    }
    __m256 outside;
    ray.slabs(n, tn, wf, outside);
    const __m256 ok = in_range(tn, wf, lo, hi);
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    const __m256i valid = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(order >> 24)), bits), bits);
    return _mm256_and_ps(_mm256_andnot_ps(outside, ok), _mm256_castsi256_ps(valid));
  }

  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t node_hits(const WideNode<float>& n, float lo, float hi, float* tn_out,
                                                          NodeRef* child_out) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn;
    const __m256 pass = slot_hits(n, order, lo, hi, tn);
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutevar8x32_ps(tn, rank));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), rank));
    return std::uint32_t(_mm256_movemask_ps(_mm256_permutevar8x32_ps(pass, rank)));
  }

  // The entries (tn, child) of the lanes in `mask`, stored at `top` in lane order: two left-packed
  // stores of four entries each. Returns how many.
  __attribute__((target(PIERCE_AVX2_TARGET))) static std::uint32_t store_lanes(__m256 tn, __m256i child,
                                                                               std::uint32_t mask, NodeEntry<float>* top) {
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

  // ScalarOps::push_hits.
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t push_hits(const WideNode<float>& n, float lo, float hi,
                                                          NodeEntry<float>* top, NodeEntry<float>& nearest,
                                                          std::uint32_t& others) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn;
    const __m256 pass = slot_hits(n, order, lo, hi, tn);
    const auto slots = std::uint32_t(_mm256_movemask_ps(pass));
    if (slots == 0) return 0;
    if ((slots & (slots - 1)) == 0) {  // one child passes (most nodes of a first-hit ray): nothing to store
      const int s = __builtin_ctz(slots);
      nearest = {lane_tn(tn, s), n.child[s]};
      others = 0;
      return 1;
    }
    const __m256i rank = rank_slots_far_to_near(order);
    const auto mask = std::uint32_t(_mm256_movemask_ps(_mm256_permutevar8x32_ps(pass, rank)));
    tn = _mm256_permutevar8x32_ps(tn, rank);
    const __m256i child =
        _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), rank);
    const int near_lane = 31 - __builtin_clz(mask);
    others = slots & ~(1u << nearest_slot(order, near_lane));
    nearest = lane_entry(tn, child, near_lane);
    return store_lanes(tn, child, mask, top);
  }

  // ScalarOps::push_all: every child that passes, in slot order, with no branch on how many do
  // (in a breadth-first traversal that count is what the branches would have to guess).
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t push_all(const WideNode<float>& n, float lo, float hi,
                                                                     NodeEntry<float>* top) const {
    __m256 tn;
    const auto slots = std::uint32_t(_mm256_movemask_ps(slot_hits(n, n.order[ray.oct], lo, hi, tn)));
    store_lanes(tn, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), slots, top);
    return slots;
  }

  __attribute__((target(PIERCE_AVX2_TARGET))) LeafLanes tri_test(const TriBlock<float>& b, float lo, float hi,
                                                     BlockHits<float>& out) const {
    return ray.tri_test(b, lo, hi, out);
  }
};

struct Avx512Ops {
  // The ray's SimdRay, read where it was made (a copy's wide loads of the fields just stored
  // would stall on store forwarding).
  const SimdRay& ray;
  explicit Avx512Ops(const SimdRay& prepared) : ray(prepared) {}

  __attribute__((target(PIERCE_AVX512_TARGET))) __mmask8 slot_hits(const WideNode<float>& n, std::uint32_t order,
                                                                   float lo, float hi, __m256& tn) const {
    __m256 wf;
    if (ray.fused) [[likely]] {
      ray.fused_slabs(n, tn, wf);
      return in_range(__mmask8(0xff), tn, wf, lo, hi);  // an empty slot fails it (fused_slabs())
    }
    __m256 outside;
    ray.slabs(n, tn, wf, outside);
    const __mmask8 inside = __mmask8(order >> 24) & ~_mm256_movepi32_mask(_mm256_castps_si256(outside));
    return in_range(inside, tn, wf, lo, hi);
  }

  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t node_hits(const WideNode<float>& n, float lo, float hi,
                                                                        float* tn_out, NodeRef* child_out) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn;
    const __mmask8 ok = slot_hits(n, order, lo, hi, tn);
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutexvar_ps(rank, tn));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutexvar_epi32(rank, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child))));
    return _mm256_movepi32_mask(_mm256_permutexvar_epi32(rank, _mm256_movm_epi32(ok)));
  }

  // Avx2Ops::store_lanes, compressed in registers (a compress straight to memory is slow on Zen 4).
  __attribute__((target(PIERCE_AVX512_TARGET))) static std::uint32_t store_lanes(__m256 tn, __m256i child,
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

  // ScalarOps::push_hits.
  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t push_hits(const WideNode<float>& n, float lo, float hi,
                                                                        NodeEntry<float>* top,
                                                                        NodeEntry<float>& nearest,
                                                                        std::uint32_t& others) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn;
    const __mmask8 ok = slot_hits(n, order, lo, hi, tn);
    if (ok == 0) return 0;
    if ((ok & (ok - 1)) == 0) {  // one child passes (most nodes of a first-hit ray): nothing to store
      const int s = __builtin_ctz(ok);
      nearest = {lane_tn(tn, s), n.child[s]};
      others = 0;
      return 1;
    }
    const __m256i rank = rank_slots_far_to_near(order);
    const std::uint32_t mask = _mm256_movepi32_mask(_mm256_permutexvar_epi32(rank, _mm256_movm_epi32(ok)));
    tn = _mm256_permutexvar_ps(rank, tn);
    const __m256i child =
        _mm256_permutexvar_epi32(rank, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)));
    const int near_lane = 31 - __builtin_clz(mask);
    others = std::uint32_t(ok) & ~(1u << nearest_slot(order, near_lane));
    nearest = lane_entry(tn, child, near_lane);
    return store_lanes(tn, child, mask, top);
  }

  // ScalarOps::push_all (Avx2Ops::push_all).
  __attribute__((target(PIERCE_AVX512_TARGET))) std::uint32_t push_all(const WideNode<float>& n, float lo, float hi,
                                                                       NodeEntry<float>* top) const {
    __m256 tn;
    const __mmask8 slots = slot_hits(n, n.order[ray.oct], lo, hi, tn);
    store_lanes(tn, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), slots, top);
    return slots;
  }

  // SimdRay's (AVX2 instructions: the classification has no use for mask registers).
  __attribute__((target(PIERCE_AVX512_TARGET))) LeafLanes tri_test(const TriBlock<float>& b, float lo, float hi,
                                                                     BlockHits<float>& out) const {
    return ray.tri_test(b, lo, hi, out);
  }
};

}  // namespace pierce::simd
