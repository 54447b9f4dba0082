#include "hit_diff.h"

#include <algorithm>
#include <cstdint>

namespace pierce::cli {

bool same_hits(std::span<const Hit> a, std::span<const Hit> b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const Hit& x, const Hit& y) { return same_hit(x, y); });
}

HitDiff& HitDiff::operator+=(const HitDiff& o) {
  rays += o.rays;
  rays_differ += o.rays_differ;
  missing += o.missing;
  extra += o.extra;
  duplicated += o.duplicated;
  out_of_order += o.out_of_order;
  t_differs += o.t_differs;
  return *this;
}

void diff_hits(std::span<const Hit> reference, std::span<const Hit> got, HitDiff& out) {
  ++out.rays;
  if (same_hits(reference, got)) return;
  ++out.rays_differ;
  // Reference positions sorted by (geom, prim, position): each returned hit takes the first unused
  // reference occurrence of its (geom, prim).
  struct Entry {
    std::uint32_t geom, prim;
    std::size_t pos;
  };
  std::vector<Entry> ref;
  ref.reserve(reference.size());
  for (std::size_t i = 0; i < reference.size(); ++i) ref.push_back({reference[i].geom, reference[i].prim, i});
  auto key_less = [](const Entry& a, const Entry& b) {
    return a.geom != b.geom ? a.geom < b.geom : (a.prim != b.prim ? a.prim < b.prim : a.pos < b.pos);
  };
  std::sort(ref.begin(), ref.end(), key_less);
  std::vector<bool> used(ref.size(), false);
  std::size_t matched = 0;
  bool have_last = false;
  std::size_t last_pos = 0;
  for (const Hit& h : got) {
    auto it = std::lower_bound(ref.begin(), ref.end(), Entry{h.geom, h.prim, 0}, key_less);
    bool known = false, found = false;
    for (; it != ref.end() && it->geom == h.geom && it->prim == h.prim; ++it) {
      known = true;
      const std::size_t k = std::size_t(it - ref.begin());
      if (used[k]) continue;
      used[k] = true;
      found = true;
      ++matched;
      if (have_last && it->pos < last_pos) ++out.out_of_order;
      have_last = true;
      last_pos = it->pos;
      if (reference[it->pos].t != h.t) ++out.t_differs;
      break;
    }
    if (!found) ++(known ? out.duplicated : out.extra);
  }
  out.missing += reference.size() - matched;
}

std::size_t consensus_index(std::span<const std::span<const Hit>> lists, bool& majority) {
  std::size_t best = 0, best_votes = 0;
  for (std::size_t i = 0; i < lists.size(); ++i) {
    std::size_t votes = 0;
    for (const auto& other : lists) votes += same_hits(lists[i], other);
    if (votes > best_votes) best = i, best_votes = votes;
  }
  majority = 2 * best_votes > lists.size();
  return best;
}

}  // namespace pierce::cli
