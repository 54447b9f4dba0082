#pragma once
// The binned SAH step (Wald 2007) of Pierce's BVH builder (binned_builder.h), for every tree it
// builds, binary or 8-wide: bin a range of primitive references by centroid, choose the cheapest
// plane, and partition the range in place. Boxes are float, rounded outward; they only choose the
// partition (the writers recompute every box exactly in the BVH's precision). Areas are computed in
// a precision `Area`: float, or double where float areas could overflow (kMaxFloatAreaCoord).
//
// Vectors are GCC/Clang vector extensions (4 floats: x, y, z and a lane that carries an id), so the
// code is the same on every target and compiles to SSE on any x86-64, without run-time dispatch.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "pierce/wide_bvh.h"

namespace pierce::detail {

// ------------------------------------------------------------------ the knobs, for every tree
// Bins per axis at most; a range of n references gets 4 + n / 20 of them (fewer for small ranges,
// where more bins cost more than they find).
inline constexpr int kMaxBins = 32;
// A leaf's cost is counted in 8-lane blocks: a block tests its eight triangles at once, so a leaf
// of up to eight costs one test whatever the tree's branching.
inline constexpr std::uint32_t kCostLanes = kBlockLanes;
// Ranges of at least this many references are binned in parallel (the top of the tree, where
// there are not yet subtrees enough to keep the threads busy). Bins merge by min, max and sums, so
// the result is the same for any split of the work.
inline constexpr std::uint32_t kParallelBinning = 1u << 16;
// Ranges of at least this many references build their children in parallel.
inline constexpr std::uint32_t kParallelBuild = 1024;
// Float areas while every coordinate is below this: a half-area then stays below 3 * 2^120 and a
// centroid sum finite. Beyond it areas are computed in double.
inline constexpr double kMaxFloatAreaCoord = 0x1p59;

using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));

inline Float4 min4(Float4 a, Float4 b) { return a < b ? a : b; }
inline Float4 max4(Float4 a, Float4 b) { return a > b ? a : b; }

// A triangle as the builder moves it: its float box (rounded outward) in lanes 0-2, and in lane 3
// its geometry (lo) and primitive (hi) index as bits. 32 bytes, partitioned in place; 16-byte
// aligned (no over-aligned by-value parameters in std::sort).
struct PrimRef {
  Float4 lo, hi;
  std::uint32_t geom() const { return bits(lo[3]); }
  std::uint32_t prim() const { return bits(hi[3]); }
  static std::uint32_t bits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
  }
  // An id as the bits of a lane.
  static float id_lane(std::uint32_t id) {
    float f;
    std::memcpy(&f, &id, sizeof f);
    return f;
  }
  // Twice the centroid, with the id lane zeroed (never a denormal in arithmetic).
  Float4 centroid2() const {
    const Int4 xyz = {-1, -1, -1, 0};
    return Float4(Int4(lo + hi) & xyz);
  }
};

// A box in lanes 0-2 (lane 3 unused); empty: +inf below -inf.
struct Box4 {
  Float4 lo = {kInf, kInf, kInf, kInf}, hi = {-kInf, -kInf, -kInf, -kInf};
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  void extend(Float4 l, Float4 h) { lo = min4(lo, l), hi = max4(hi, h); }
  void extend(Float4 p) { extend(p, p); }
  void extend(const Box4& b) { extend(b.lo, b.hi); }
  template <typename Area>
  Area half_area() const {
    const Float4 d = hi - lo;
    return Area(d[0]) * Area(d[1]) + Area(d[1]) * Area(d[2]) + Area(d[2]) * Area(d[0]);
  }
};

// A range of prims[] with its boxes: of the triangles and of their (doubled) centroids.
struct PrimRange {
  std::uint32_t begin = 0, end = 0;
  Box4 geom, cent;
  std::uint32_t size() const { return end - begin; }
};

// A leaf's cost: the blocks its n triangles fill (kCostLanes).
inline double blocks_of(std::uint32_t n) { return double((n + kCostLanes - 1) / kCostLanes); }

// Centroid to bin (kMaxBins); an axis along which the centroids do not spread gets scale 0 (every
// centroid in bin 0: no plane).
struct BinMapping {
  int bins = 0;
  Float4 offset{}, scale{}, last{};
  BinMapping(std::uint32_t n, const Box4& cent) {
    bins = std::min(kMaxBins, int(4.0f + 0.05f * float(n)));
    offset = cent.lo;
    const Float4 extent = cent.hi - cent.lo;
    for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 1e-34f ? 0.99f * float(bins) / extent[a] : 0.0f;
    scale[3] = 0.0f;
    last = Float4{} + float(bins - 1);
  }
  // Clamped before converting: NaN and values below 0 go to bin 0 (`x > 0` is false for them).
  Int4 bin(Float4 centroid2) const {
    Float4 x = (centroid2 - offset) * scale;
    x = x > 0.0f ? x : Float4{};
    x = x < last ? x : last;
    return __builtin_convertvector(x, Int4);
  }
};

// A plane: primitives whose centroid bin along `axis` is below `bin` go left.
struct SahSplit {
  // Sum of area x blocks over both sides, in double: a float area times a block count could
  // overflow.
  double cost = std::numeric_limits<double>::infinity();
  int axis = -1, bin = 0;
  bool valid() const { return axis >= 0; }
};

template <typename Area>
struct Bins {
  Box4 box[3][kMaxBins];
  std::uint32_t count[3][kMaxBins] = {};

  void add(const PrimRef* prims, std::uint32_t begin, std::uint32_t end, const BinMapping& m) {
    for (std::uint32_t i = begin; i < end; ++i) {
      const PrimRef& p = prims[i];
      const Int4 b = m.bin(p.centroid2());
      for (int a = 0; a < 3; ++a) {
        box[a][b[a]].extend(p.lo, p.hi);
        ++count[a][b[a]];
      }
    }
  }

  void merge(const Bins& other, int bins) {
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < bins; ++k) {
        box[a][k].extend(other.box[a][k]);
        count[a][k] += other.count[a][k];
      }
  }

  // The cheapest plane: per axis, a right-to-left sweep of areas and counts, then a left-to-right
  // one; both sides must hold primitives. Ties keep the lower axis and bin.
  SahSplit best(const BinMapping& m) const {
    SahSplit s;
    for (int a = 0; a < 3; ++a) {
      if (m.scale[a] == 0.0f) continue;
      double right_cost[kMaxBins];
      std::uint32_t right_count[kMaxBins];
      Box4 acc;
      std::uint32_t n = 0;
      for (int k = m.bins - 1; k > 0; --k) {
        acc.extend(box[a][k]);
        n += count[a][k];
        right_count[k] = n;
        right_cost[k] = n > 0 ? double(acc.half_area<Area>()) * blocks_of(n) : 0.0;
      }
      acc = Box4{};
      n = 0;
      for (int k = 1; k < m.bins; ++k) {
        acc.extend(box[a][k - 1]);
        n += count[a][k - 1];
        if (n == 0 || right_count[k] == 0) continue;
        const double cost = double(acc.half_area<Area>()) * blocks_of(n) + right_cost[k];
        if (cost < s.cost) s.cost = cost, s.axis = a, s.bin = k;
      }
    }
    return s;
  }
};

template <typename Area>
SahSplit find_split(const PrimRef* prims, const PrimRange& r) {
  const BinMapping m(r.size(), r.cent);
  if (r.size() < kParallelBinning) {
    Bins<Area> bins;
    bins.add(prims, r.begin, r.end, m);
    return bins.best(m);
  }
  const Bins<Area> bins = tbb::parallel_reduce(
      tbb::blocked_range<std::uint32_t>(r.begin, r.end, kParallelBinning / 4), Bins<Area>{},
      [&](const tbb::blocked_range<std::uint32_t>& chunk, Bins<Area> b) {
        b.add(prims, chunk.begin(), chunk.end(), m);
        return b;
      },
      [&](Bins<Area> a, const Bins<Area>& b) {
        a.merge(b, m.bins);
        return a;
      });
  return bins.best(m);
}

// Splits `r` in place by `s` (the plane find_split chose from the same mapping, so both sides are
// non-empty), or, where no plane separates the range, at its middle by index. One pass: each
// reference is classified once and added to its side's boxes as it is placed.
inline void partition(PrimRef* prims, const PrimRange& r, const SahSplit& s, PrimRange& left, PrimRange& right) {
  left = right = PrimRange{};
  auto add = [](PrimRange& side, const PrimRef& p) {
    side.geom.extend(p.lo, p.hi);
    side.cent.extend(p.centroid2());
  };
  std::uint32_t mid = r.begin + r.size() / 2;
  if (s.valid()) {
    const BinMapping m(r.size(), r.cent);
    auto goes_left = [&](const PrimRef& p) { return m.bin(p.centroid2())[s.axis] < s.bin; };
    PrimRef *l = prims + r.begin, *h = prims + r.end;  // [begin, l) left, [h, end) right
    for (;;) {
      while (l < h && goes_left(*l)) add(left, *l++);
      while (l < h && !goes_left(h[-1])) add(right, *--h);
      if (l == h) break;
      std::swap(*l, *--h);
      add(left, *l++);
      add(right, *h);
    }
    mid = std::uint32_t(l - prims);
    if (mid != r.begin && mid != r.end) {
      left.begin = r.begin, left.end = right.begin = mid, right.end = r.end;
      return;
    }
    left = right = PrimRange{};  // cannot happen (same mapping): split by index instead
    mid = r.begin + r.size() / 2;
  }
  left.begin = r.begin, left.end = right.begin = mid, right.end = r.end;
  for (std::uint32_t i = left.begin; i < left.end; ++i) add(left, prims[i]);
  for (std::uint32_t i = right.begin; i < right.end; ++i) add(right, prims[i]);
}

}  // namespace pierce::detail
