#include "pierce/analysis/shotline.h"

#include "pierce/analysis/tie_distance.h"
#include "pierce/parallel_for_items.h"
#include "partition_walker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace pierce::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

struct ShotWorker : PartitionWalker {
  std::optional<CsgEvaluator> eval;
  std::vector<std::uint32_t> named;  // solids the expression names
  std::uint64_t unmatched = 0, unclosed = 0;
  double tie = 0;

  ShotWorker(const Accel& accel, const ShotOptions& o)
      : PartitionWalker(accel, o.kernel),
        tie(tie_distance(accel.scene(), o.tie_tolerance_rel)) {
    if (o.csg) {
      eval.emplace(*o.csg, accel.scene().geometries().size());
      named = o.csg->solids();
    }
  }
};

ShotRow make_row(std::uint32_t ray_index, const Ray& ray, ShotKind kind, double t_in, double t_out, const Hit& in_hit,
                 const Hit& out_hit) {
  ShotRow r;
  r.ray = ray_index;
  r.kind = kind;
  r.t_in = t_in;
  r.t_out = t_out;
  r.in_point = ray.org + ray.dir * t_in;
  r.out_point = ray.org + ray.dir * t_out;
  r.los = (t_out - t_in) * length(ray.dir);
  const bool gap = kind == ShotKind::gap;
  r.obliquity_in = gap ? kNaN : obliquity_deg(ray.dir, in_hit);
  r.obliquity_out = gap ? kNaN : obliquity_deg(ray.dir, out_hit);
  r.normal_thickness = std::isnan(r.obliquity_in) ? kNaN : r.los * std::cos(r.obliquity_in * kDegToRad);
  r.in_geom = in_hit.valid() ? in_hit.geom : kInvalidId;
  r.out_geom = out_hit.valid() ? out_hit.geom : kInvalidId;
  return r;
}

// Gap rows between consecutive rows of one ray (rows sorted by t_in, non-overlapping).
void add_gaps(std::vector<ShotRow>& rows, std::uint32_t ray_index, const Ray& ray) {
  const std::size_t n = rows.size();
  for (std::size_t i = 1; i < n; ++i) {
    const ShotRow& prev = rows[i - 1];
    const ShotRow& next = rows[i];
    if (!(prev.t_out < next.t_in)) continue;
    ShotRow g = make_row(ray_index, ray, ShotKind::gap, prev.t_out, next.t_in, Hit{}, Hit{});
    g.in_geom = prev.out_geom;
    g.out_geom = next.in_geom;
    g.solids = prev.solids;
    g.solids.insert(g.solids.end(), next.solids.begin(), next.solids.end());
    std::sort(g.solids.begin(), g.solids.end());
    g.solids.erase(std::unique(g.solids.begin(), g.solids.end()), g.solids.end());
    rows.push_back(std::move(g));
  }
}

void shoot_one(ShotWorker& w, const Accel& accel, const ShotOptions& o, std::uint32_t ray_index, const Ray& ray,
               std::vector<ShotRow>& rows) {
  w.hits.clear();
  collect_hits(w.it, full_line_ray(ray, accel.scene().bounds()), 0, w.hits);
  w.builder.build(w.hits, w.parts);
  w.unmatched += w.parts.unmatched_leaves;
  w.unclosed += w.parts.unclosed;
  snap_partitions(w.parts, w.tie / length(ray.dir));
  clip_partitions(w.parts, ray.tmin, ray.tmax);
  if (o.csg) {
    w.eval->evaluate(w.parts, w.intervals);
    for (const CsgInterval& iv : w.intervals) {
      rows.push_back(make_row(ray_index, ray, ShotKind::region, iv.t_in, iv.t_out, iv.in_hit, iv.out_hit));
      rows.back().solids = w.named;
    }
  } else {
    for (const Partition& p : w.parts.partitions) {
      rows.push_back(make_row(ray_index, ray, p.count >= 2 ? ShotKind::overlap : ShotKind::solid, p.t_in, p.t_out,
                              p.in_hit, p.out_hit));
      const auto s = w.parts.solids_of(p);
      rows.back().solids.assign(s.begin(), s.end());
    }
  }
  add_gaps(rows, ray_index, ray);
  if (o.csg) {  // overlaps are reported whatever the expression
    for (const Partition& p : w.parts.partitions) {
      if (p.count < 2) continue;
      rows.push_back(make_row(ray_index, ray, ShotKind::overlap, p.t_in, p.t_out, p.in_hit, p.out_hit));
      const auto s = w.parts.solids_of(p);
      rows.back().solids.assign(s.begin(), s.end());
    }
  }
  std::stable_sort(rows.begin(), rows.end(), [](const ShotRow& a, const ShotRow& b) { return a.t_in < b.t_in; });
}

}  // namespace

std::string_view shot_kind_name(ShotKind k) {
  switch (k) {
    case ShotKind::solid: return "solid";
    case ShotKind::overlap: return "overlap";
    case ShotKind::region: return "region";
    case ShotKind::gap: return "gap";
  }
  return "?";
}

ShotResult shoot(const Accel& accel, const std::vector<Ray>& rays, const ShotOptions& opts, const Progress& progress) {
  if (!is_exact(opts.kernel)) throw std::invalid_argument("shotlines need an exact kernel");
  if (!(opts.tie_tolerance_rel >= 0)) throw std::invalid_argument("shotlines: tie tolerance must be >= 0");
  ShotResult result;
  result.rays = rays.size();
  std::vector<std::vector<ShotRow>> per_ray(rays.size());
  tbb::enumerable_thread_specific<ShotWorker> workers([&] { return ShotWorker(accel, opts); });
  result.completed = parallel_for_items(rays.size(), 64, workers, progress, [&](ShotWorker& w, std::size_t i) {
    shoot_one(w, accel, opts, std::uint32_t(i), rays[i], per_ray[i]);
  });
  for (const ShotWorker& w : workers) {
    result.unmatched_leaves += w.unmatched;
    result.unclosed += w.unclosed;
  }
  for (auto& rows : per_ray) {
    if (!rows.empty()) ++result.rays_hitting;
    for (ShotRow& r : rows) result.rows.push_back(std::move(r));
  }
  return result;
}

}  // namespace pierce::analysis
