#include "pierce/analysis/overlaps.h"

namespace pierce::analysis {

TriangleOverlapArrays triangle_overlap_arrays(const Scene& scene, const CoplanarReport* coplanar,
                                              const RayOverlapReport* rays) {
  TriangleOverlapArrays a;
  a.tri_offset.push_back(0);
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const std::size_t n = scene.geometry(g).triangles.size();
    a.tri_offset.push_back(a.tri_offset.back() + n);
    a.solid.insert(a.solid.end(), n, g);
  }
  const std::size_t n = a.solid.size();
  a.coplanar_count.assign(n, 0);
  a.coplanar_partner.assign(n, -1);
  a.coplanar_hits.assign(n, 0);
  a.interference_hits.assign(n, 0);
  if (coplanar) {
    for (const CoplanarPair& p : coplanar->pairs) {
      const std::size_t ia = a.tri_offset[p.geom_a] + p.prim_a, ib = a.tri_offset[p.geom_b] + p.prim_b;
      ++a.coplanar_count[ia];
      ++a.coplanar_count[ib];
      // Prefer a partner in another solid: that is the contact or clash a user looks for.
      auto note = [&](std::size_t i, std::uint32_t self, std::uint32_t other) {
        std::int32_t& slot = a.coplanar_partner[i];
        if (slot < 0 || (std::uint32_t(slot) == self && other != self)) slot = std::int32_t(other);
      };
      note(ia, p.geom_a, p.geom_b);
      note(ib, p.geom_b, p.geom_a);
    }
  }
  if (rays && rays->coplanar_hits.size() == n) {
    a.coplanar_hits = rays->coplanar_hits;
    a.interference_hits = rays->interference_hits;
  }
  a.overlap_count.resize(n);
  for (std::size_t i = 0; i < n; ++i) a.overlap_count[i] = a.coplanar_count[i] + a.interference_hits[i];
  return a;
}

}  // namespace pierce::analysis
