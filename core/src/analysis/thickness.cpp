#include "pierce/analysis/thickness.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "pierce/parallel_for_items.h"
#include "thickness_internal.h"

namespace pierce::analysis {

using detail::kNaN;

bool uses_origin_offsets(const ThicknessOptions& opts) {
  return opts.per == SampleAt::face && opts.method != ThicknessMethod::sphere && opts.origin_offsets == OffsetMode::on;
}

// Shapira et al. 2008, section 4.
double cone_aggregate(std::span<const std::pair<double, double>> len_angle, ConeAggregate how, double min_angle) {
  std::vector<double> lens;
  for (auto& [l, a] : len_angle) lens.push_back(l);
  std::sort(lens.begin(), lens.end());
  const double median = percentile_sorted(lens, 50);
  double mean = 0;
  for (double l : lens) mean += l;
  mean /= double(lens.size());
  double var = 0;
  for (double l : lens) var += (l - mean) * (l - mean);
  const double sigma = std::sqrt(var / double(lens.size()));
  std::vector<double> kept;
  double wsum = 0, acc = 0;
  for (auto& [l, a] : len_angle) {
    if (std::abs(l - median) > sigma) continue;
    kept.push_back(l);
    const double w = 1.0 / std::max(a, 0.5 * min_angle);
    wsum += w;
    acc += w * l;
  }
  if (kept.empty()) return median;
  if (how == ConeAggregate::median) {
    std::sort(kept.begin(), kept.end());
    return percentile_sorted(kept, 50);
  }
  return acc / wsum;
}

ThicknessAlong thickness_along(const Accel& accel, const std::vector<std::uint32_t>& geoms,
                               const std::vector<Ray>& rays, double max_distance, double tie_tolerance_rel,
                               KernelKind kernel, const Progress& progress) {
  if (!is_exact(kernel)) throw std::invalid_argument("thickness_along: kernel must be exact");
  if (geoms.size() != rays.size()) throw std::invalid_argument("thickness_along: one geometry id per ray");
  for (const std::uint32_t g : geoms)
    if (g >= accel.scene().geometries().size())
      throw std::invalid_argument("geometry id " + std::to_string(g) + " is not in the scene");
  ThicknessAlong out;
  out.thickness.assign(rays.size(), kNaN);
  const double tie = tie_distance(accel.scene(), tie_tolerance_rel);
  KernelOptions ko;
  ko.order.tie = TieOrder::leave_before_enter;  // what ray_exit_distance requires
  tbb::enumerable_thread_specific<HitIterator> iters([&] { return HitIterator(accel, kernel, ko); });
  out.completed = parallel_for_items(rays.size(), 256, iters, progress, [&](HitIterator& it, std::size_t i) {
    const Vec3d dir = rays[i].dir * (1.0 / length(rays[i].dir));
    out.thickness[i] = ray_exit_distance(it, geoms[i], rays[i].org, dir, max_distance, tie);
  });
  return out;
}

// Sampling, tracing and statistics are separate stages (thickness_internal.h).
ThicknessResult compute_thickness(const Accel& accel, const ThicknessOptions& opts, const Progress& progress) {
  detail::check_options(accel, opts);
  ThicknessResult res;
  const detail::SampleSet set = detail::build_samples(accel.scene(), opts, res);
  if (!detail::trace_samples(accel, opts, set, res, progress)) {
    res.completed = false;
    return res;
  }
  detail::finish_statistics(accel.scene(), opts, set, res);
  detail::find_regions(accel, opts, set, res);
  return res;
}

ThicknessResult assemble_thickness(const Accel& accel, const ThicknessOptions& opts,
                                   std::span<const MeasuredSample> measured) {
  detail::check_options(accel, opts);
  ThicknessResult res;
  const detail::SampleSet set = detail::build_samples(accel.scene(), opts, res);
  auto key = [](std::uint32_t solid, std::uint32_t element) { return (std::uint64_t(solid) << 32) | element; };
  std::vector<std::pair<std::uint64_t, std::size_t>> rows(measured.size());
  for (std::size_t i = 0; i < measured.size(); ++i) rows[i] = {key(measured[i].solid, measured[i].element), i};
  std::sort(rows.begin(), rows.end());
  for (const detail::Sample& s : set.samples) {
    const std::size_t k = s.out_index;
    const auto found = std::lower_bound(rows.begin(), rows.end(), std::pair(key(res.solid[k], res.element[k]), std::size_t{0}));
    if (found == rows.end() || found->first != key(res.solid[k], res.element[k]))
      throw std::invalid_argument("assemble_thickness: no measured row for element " + std::to_string(res.element[k]) +
                                  " of solid " + std::to_string(res.solid[k]));
    const MeasuredSample& m = measured[found->second];
    res.point[k] = m.point;
    res.normal[k] = m.normal;
    res.thickness[k] = m.thickness;
    res.status[k] = m.status;
    if (!res.brep_faces.empty()) res.brep_faces[k] = m.brep_faces;
    res.exit_triangle[k] = m.exit_triangle;
  }
  detail::finish_statistics(accel.scene(), opts, set, res);
  detail::find_regions(accel, opts, set, res);
  return res;
}

ThicknessResult thickness_at(const Accel& accel, const std::vector<std::uint32_t>& solids,
                             const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                             const ThicknessOptions& opts, const Progress& progress) {
  detail::check_options(accel, opts);
  ThicknessResult res;
  const detail::SampleSet set = detail::build_point_samples(accel.scene(), opts, solids, points, normals, res);
  if (!detail::trace_samples(accel, opts, set, res, progress)) {
    res.completed = false;
    return res;
  }
  detail::finish_statistics(accel.scene(), opts, set, res);
  res.region.assign(res.size(), -1);  // regions are a map's findings; points have none
  return res;
}

}  // namespace pierce::analysis
