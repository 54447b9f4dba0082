#pragma once
// Comparing a kernel's hit lists with a reference (the exact consensus of `pierce hits --kernel all`).
// Hits are identified by (geom, prim); two lists are equal when their (geom, prim, t) sequences are.
#include <cstddef>
#include <span>
#include <vector>

#include "pierce/hit.h"

namespace pierce::cli {

bool same_hits(std::span<const Hit> a, std::span<const Hit> b);

struct HitDiff {
  std::size_t rays = 0;          // rays compared
  std::size_t rays_differ = 0;   // rays whose list is not the reference's
  std::size_t missing = 0;       // reference hits not returned
  std::size_t extra = 0;         // returned hits whose (geom, prim) is not in the reference
  std::size_t duplicated = 0;    // returned more often than the reference has them
  std::size_t out_of_order = 0;  // matched hits returned before a hit the reference puts earlier
  std::size_t t_differs = 0;     // matched hits with a different t

  bool clean() const { return rays_differ == 0; }
  HitDiff& operator+=(const HitDiff& o);
};

// Compares one ray's list `got` with `reference` and adds the counts to `out`.
void diff_hits(std::span<const Hit> reference, std::span<const Hit> got, HitDiff& out);

// Index of the list most of `lists` equal (ties: the earliest such list); `majority` tells whether
// more than half agree. `lists` must not be empty.
std::size_t consensus_index(std::span<const std::span<const Hit>> lists, bool& majority);

}  // namespace pierce::cli
