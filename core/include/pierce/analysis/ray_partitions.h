#pragma once
// Ray partitions (Roth 1982; BRL-CAD librt): along one ray, the intervals [t_in, t_out] with the
// set of solids (geometry ids) whose inside covers each interval, built from the ray's ordered hit
// stream. An interval claimed by two or more solids is an overlap; the space between two intervals
// is a gap. Touching solids give adjacent intervals (t_out == next t_in) and no gap.
//
// Hits that share one t are applied together, so the result does not depend on their order at
// that t (leave_before_enter is what a streaming consumer wants, but any order gives the same
// partitions). Within one such group, a solid's inside count moves by at most one: a duplicated
// coplanar face counts once, and a ray grazing a solid (entering and leaving at the same t) leaves
// it unchanged.
//
// Defined results on bad meshes (never an invented interval):
//  - a leaving crossing of a solid the ray is not inside (open, inverted or self-overlapping mesh)
//    is ignored and counted in `unmatched_leaves`;
//  - a solid still entered when the hits run out (open mesh: its exit is missing) claims nothing
//    from that last entry on; it is counted in `unclosed`. Its earlier, closed intervals stay.
#include <cstdint>
#include <span>
#include <vector>

#include "pierce/bbox.h"
#include "pierce/hit.h"
#include "pierce/ray.h"

namespace pierce {

struct Partition {
  double t_in = 0.0, t_out = 0.0;
  std::uint32_t first = 0;  // its solids: RayPartitions::solids[first, first + count), ascending
  std::uint32_t count = 0;  // >= 1; >= 2 is an overlap
  Hit in_hit, out_hit;      // crossings that open and close it; invalid where clipped to the ray's ends
};

struct RayPartitions {
  std::vector<Partition> partitions;  // ordered by t, disjoint
  std::vector<std::uint32_t> solids;
  std::uint32_t unmatched_leaves = 0;
  std::uint32_t unclosed = 0;

  std::span<const std::uint32_t> solids_of(const Partition& p) const {
    return std::span<const std::uint32_t>(solids).subspan(p.first, p.count);
  }
  void clear() {
    partitions.clear();
    solids.clear();
    unmatched_leaves = unclosed = 0;
  }
};

// Builds one ray's partitions from its hits, in order. Reusable across rays; keeps its buffers.
class PartitionBuilder {
 public:
  explicit PartitionBuilder(std::size_t geometry_count);
  // Clears `out` and builds its partitions from `hits` (sorted by a HitOrder).
  void build(std::span<const Hit> hits, RayPartitions& out);

  // Streaming form of build(), for consumers that stop a ray early: begin(out), then add_group()
  // for each run of hits sharing one t, in ray order, then finish(out) (or begin() the next ray).
  // After each add_group(), out.partitions holds every partition closed so far and, when
  // partition_open(), a last one whose t_out is not yet known.
  void begin(RayPartitions& out);
  void add_group(std::span<const Hit> group, RayPartitions& out) { apply_group(group, out); }
  void finish(RayPartitions& out);
  bool partition_open() const { return open_; }

 private:
  void apply_group(std::span<const Hit> group, RayPartitions& out);
  void open_partition(double t, const Hit& in_hit, RayPartitions& out);
  void drop_unclosed_claims(RayPartitions& out);

  std::vector<std::uint32_t> depth_;   // per geometry: how many nested insides the ray is in
  std::vector<int> net_;               // per geometry, scratch: enters minus leaves in a group
  std::vector<std::uint32_t> touched_; // geometries with a nonzero net_ entry
  std::vector<std::uint32_t> inside_;  // geometries with depth_ > 0, ascending
  std::vector<double> opened_at_;      // per geometry: t where depth_ last rose from 0
  bool open_ = false;
};

// The ray to trace so that the state at the ray's own tmin is known: the same origin and
// direction, tmin moved back to before the line enters `bounds` (when the ray starts inside them)
// and tmax = infinity, so every solid the line meets is entered from outside and left again.
Ray full_line_ray(const Ray& ray, const BBoxd& bounds);

// Restricts partitions to [tmin, tmax]; ends cut off get an invalid in_hit/out_hit.
void clip_partitions(RayPartitions& p, double tmin, double tmax);

}  // namespace pierce
