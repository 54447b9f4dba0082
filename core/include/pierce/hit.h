#pragma once
// A ray-surface crossing and the total order on crossings (Wald et al. 2019, §3).
#include <algorithm>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "pierce/enum_names.h"
#include "pierce/vec3.h"

namespace pierce {

inline constexpr std::uint32_t kInvalidId = std::numeric_limits<std::uint32_t>::max();

struct Hit {
  double t = std::numeric_limits<double>::infinity();
  std::uint32_t geom = kInvalidId;
  std::uint32_t prim = kInvalidId;  // triangle index in its geometry's input order
  float u = 0.f, v = 0.f;           // barycentrics of vertices 1 and 2
  Vec3f ng;                         // geometric normal (v1-v0)x(v2-v0), unnormalised
  bool enter = false;               // ray direction against the outward (CCW) normal

  bool valid() const { return geom != kInvalidId; }
};

// What HitOrder ranks a hit by, without the rest of the record: the traversal's leaf callbacks
// rank candidates by it and make the full Hit only for the ones they keep.
struct HitKey {
  double t;
  std::uint32_t geom, prim;
  bool enter;
};
inline HitKey key_of(const Hit& h) { return {h.t, h.geom, h.prim, h.enter}; }
// The full record of a ranked candidate (the inverse of key_of).
inline Hit hit_of(const HitKey& k, float u, float v, const Vec3f& ng) {
  return {.t = k.t, .geom = k.geom, .prim = k.prim, .u = u, .v = v, .ng = ng, .enter = k.enter};
}

// How hits at equal t are ranked. `geom_prim` is Wald et al.'s (t, geom, prim).
// `leave_before_enter` ranks leaving crossings first at equal t, then (geom, prim):
// CSG classification needs a solid closed before its touching neighbour opens.
enum class TieOrder : std::uint8_t { geom_prim, leave_before_enter };
constexpr EnumTable<TieOrder, 2> enum_table(TieOrder) {
  using enum TieOrder;
  return {"tie order", {{geom_prim, "geom_prim"}, {leave_before_enter, "leave_before_enter"}}};
}

// Strict total order on hits under a tie policy. Hits are identified by (geom, prim);
// `enter` is a function of them, so the order stays total.
struct HitOrder {
  TieOrder tie = TieOrder::geom_prim;

  // A and B: Hit or HitKey.
  template <class A, class B>
  [[gnu::always_inline]] constexpr bool less(const A& a, const B& b) const {
    if (a.t != b.t) return a.t < b.t;
    if (tie == TieOrder::leave_before_enter && a.enter != b.enter) return !a.enter;
    if (a.geom != b.geom) return a.geom < b.geom;
    return a.prim < b.prim;
  }
  template <class A, class B>
  constexpr bool operator()(const A& a, const B& b) const {
    return less(a, b);
  }
};

// Moves the hit at `pos` down into the sorted hits [first, pos) (insertion sort's step).
template <class It>
[[gnu::always_inline]] inline void insert_into_sorted(It first, It pos, const HitOrder& order) {
  if (pos == first || !order.less(*pos, *(pos - 1))) return;  // in place already: the common case
  const Hit h = *pos;
  do {
    *pos = *(pos - 1);
    --pos;
  } while (pos != first && order.less(h, *(pos - 1)));
  *pos = h;
}

// Sorts the hits [first, last) in `order`. A ray holds few hits as a rule: up to 16 are sorted by
// insertion inline (what std::sort does with so few, without its calls), more by std::sort. Inline
// wherever hits are gathered, so that `filter` and `queue`'s gathering pass sort alike (left to
// GCC, std::sort's insertion step can be inline in one and out of line in the other).
template <class It>
[[gnu::always_inline]] inline void sort_hits(It first, It last, const HitOrder& order) {
  if (last - first > 16) {
    std::sort(first, last, order);
    return;
  }
  for (It i = first; i != last; ++i) insert_into_sorted(first, i, order);
}

// The first `count` hits of [first, last) in `order` moved to its front, sorted; the others after
// them in no order (count 0: all sorted). For a caller that wants only the first `count`: the rest
// are sorted only if asked for (`queue`'s gathering pass with a max-hits hint).
template <class It>
[[gnu::always_inline]] inline void sort_first_hits(It first, It last, std::size_t count, const HitOrder& order) {
  if (count == 0 || std::size_t(last - first) <= count) {
    sort_hits(first, last, order);
    return;
  }
  if (count > 16) {
    std::partial_sort(first, first + std::ptrdiff_t(count), last, order);
    return;
  }
  // A hit that ranks before the front's last one takes its place there and is moved down into the
  // front; the last one goes to the hit's place.
  const It back = first + std::ptrdiff_t(count - 1);
  sort_hits(first, back + 1, order);
  for (It i = back + 1; i != last; ++i) {
    if (!order.less(*i, *back)) continue;
    std::swap(*i, *back);
    insert_into_sorted(first, back, order);
  }
}

inline bool same_hit(const Hit& a, const Hit& b) { return a.t == b.t && a.geom == b.geom && a.prim == b.prim; }

}  // namespace pierce
