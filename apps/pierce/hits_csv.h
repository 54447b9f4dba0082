#pragma once
// The `ray,t,geom,prim,u,v,enter` CSV of `pierce hits`. t is printed in the shortest form that
// reads back to the same double (u, v: the same float), so the file round-trips exactly.
#include <cstdio>
#include <functional>
#include <span>

#include "pierce/hit.h"

namespace pierce::cli {

// Writes the header and every ray's hits in order; hits_of(i) gives ray i's list. Stops early and
// returns false when keep_going() turns false (polled every few thousand rows).
bool write_hits_csv(std::FILE* out, std::size_t ray_count, const std::function<std::span<const Hit>(std::size_t)>& hits_of,
                    const std::function<bool()>& keep_going);

}  // namespace pierce::cli
