#include "pierce/analysis/ray_partitions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pierce {

PartitionBuilder::PartitionBuilder(std::size_t geometry_count)
    : depth_(geometry_count, 0), net_(geometry_count, 0), opened_at_(geometry_count, 0.0) {}

void PartitionBuilder::build(std::span<const Hit> hits, RayPartitions& out) {
  begin(out);
  std::size_t first = 0;
  while (first < hits.size()) {
    std::size_t end = first + 1;
    while (end < hits.size() && hits[end].t == hits[first].t) ++end;
    apply_group(hits.subspan(first, end - first), out);
    first = end;
  }
  finish(out);
}

void PartitionBuilder::begin(RayPartitions& out) {
  out.clear();
  open_ = false;
  for (std::uint32_t g : inside_) depth_[g] = 0;  // a previous ray stopped early
  inside_.clear();
}

void PartitionBuilder::finish(RayPartitions& out) {
  if (open_) {  // runs to infinity: an exit is missing
    out.solids.resize(out.partitions.back().first);
    out.partitions.pop_back();
    open_ = false;
  }
  out.unclosed = static_cast<std::uint32_t>(inside_.size());
  if (!inside_.empty()) drop_unclosed_claims(out);
  for (std::uint32_t g : inside_) depth_[g] = 0;
  inside_.clear();
}

// Rare path (open meshes): rebuilds the partition list without the claims of solids whose last
// entry has no exit, merging neighbours that become equal.
void PartitionBuilder::drop_unclosed_claims(RayPartitions& out) {
  const std::vector<Partition> old = std::move(out.partitions);
  const std::vector<std::uint32_t> old_solids = std::move(out.solids);
  out.partitions.clear();
  out.solids.clear();
  for (Partition p : old) {
    const std::size_t first = out.solids.size();
    for (std::uint32_t k = p.first; k < p.first + p.count; ++k) {
      const std::uint32_t g = old_solids[k];
      const bool dropped = std::binary_search(inside_.begin(), inside_.end(), g) && p.t_in >= opened_at_[g];
      if (!dropped) out.solids.push_back(g);
    }
    p.first = static_cast<std::uint32_t>(first);
    p.count = static_cast<std::uint32_t>(out.solids.size() - first);
    if (p.count == 0) continue;
    if (!out.partitions.empty()) {
      Partition& prev = out.partitions.back();
      if (prev.t_out == p.t_in && prev.count == p.count &&
          std::equal(out.solids.begin() + prev.first, out.solids.begin() + prev.first + prev.count,
                     out.solids.begin() + p.first)) {
        prev.t_out = p.t_out;
        prev.out_hit = p.out_hit;
        out.solids.resize(first);
        continue;
      }
    }
    out.partitions.push_back(p);
  }
}

void PartitionBuilder::apply_group(std::span<const Hit> group, RayPartitions& out) {
  for (const Hit& h : group) {
    if (h.geom >= net_.size()) continue;  // not a geometry of this scene: cannot happen with one Accel
    if (net_[h.geom] == 0) touched_.push_back(h.geom);  // may repeat: net_ is reset once applied
    net_[h.geom] += h.enter ? 1 : -1;
  }
  bool changed = false;
  for (std::uint32_t g : touched_) {
    const int n = net_[g];
    net_[g] = 0;
    if (n < 0) {
      if (depth_[g] == 0) {
        ++out.unmatched_leaves;
      } else if (--depth_[g] == 0) {
        inside_.erase(std::find(inside_.begin(), inside_.end(), g));
        changed = true;
      }
    } else if (n > 0) {
      if (depth_[g]++ == 0) {
        opened_at_[g] = group.front().t;
        inside_.insert(std::upper_bound(inside_.begin(), inside_.end(), g), g);
        changed = true;
      }
    }
  }
  touched_.clear();
  if (!changed) return;

  const double t = group.front().t;
  auto first_with = [&](bool enter) {
    for (const Hit& h : group)
      if (h.enter == enter) return h;
    return group.front();
  };
  if (open_) {
    Partition& p = out.partitions.back();
    p.t_out = t;
    p.out_hit = first_with(false);
    open_ = false;
  }
  if (!inside_.empty()) open_partition(t, first_with(true), out);
}

void PartitionBuilder::open_partition(double t, const Hit& in_hit, RayPartitions& out) {
  Partition p;
  p.t_in = t;
  p.t_out = t;
  p.first = static_cast<std::uint32_t>(out.solids.size());
  p.count = static_cast<std::uint32_t>(inside_.size());
  p.in_hit = in_hit;
  out.solids.insert(out.solids.end(), inside_.begin(), inside_.end());
  out.partitions.push_back(p);
  open_ = true;
}

Ray full_line_ray(const Ray& ray, const BBoxd& bounds) {
  Ray r = ray;
  r.tmax = std::numeric_limits<double>::infinity();
  if (bounds.empty()) return r;
  // Parameter where the line enters the box (slab test); axes the line runs parallel to add nothing.
  double t_entry = -std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (r.dir[a] == 0.0) continue;
    const double t0 = (bounds.lo[a] - r.org[a]) / r.dir[a];
    const double t1 = (bounds.hi[a] - r.org[a]) / r.dir[a];
    t_entry = std::max(t_entry, std::min(t0, t1));
  }
  const double dir_len = length(r.dir);
  if (!std::isfinite(t_entry) || dir_len == 0.0) return r;
  // A margin of 1% of the box diagonal keeps faces lying on the box's boundary inside [tmin, ...].
  const double margin = 0.01 * std::max(length(bounds.extent()), 1e-30) / dir_len;
  r.tmin = std::min(ray.tmin, t_entry - margin);
  return r;
}

void clip_partitions(RayPartitions& p, double tmin, double tmax) {
  std::size_t kept = 0;
  for (Partition q : p.partitions) {
    if (q.t_out <= tmin || q.t_in >= tmax) continue;
    if (q.t_in < tmin) q.t_in = tmin, q.in_hit = Hit{};
    if (q.t_out > tmax) q.t_out = tmax, q.out_hit = Hit{};
    p.partitions[kept++] = q;
  }
  p.partitions.resize(kept);
}

}  // namespace pierce
