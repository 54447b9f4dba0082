#include "pierce/analysis/thickness.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "pierce/analysis/bvh_query.h"
#include "pierce/analysis/mesh_topology.h"
#include "pierce/bvh_builder.h"
#include "pierce/parallel_for_items.h"

namespace pierce::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One point to measure: where, along which inward direction, and which triangles pass
// through it (skipped by the sphere method's closest-point queries).
struct Sample {
  std::uint32_t geom;
  std::uint32_t out_index;  // position in the result arrays
  Vec3d point, inward;
  std::uint32_t exclude_begin, exclude_end;  // range in SampleSet::exclude
  std::uint32_t prim = kInvalidId;           // face samples: the triangle the point lies on
};

struct SampleSet {
  std::vector<Sample> samples;
  std::vector<std::uint32_t> exclude;
  // Result slots filled by copying another slot's result (welded duplicates of a vertex).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;  // (to, from)
};

// Orthonormal basis (u, v) completing unit vector n.
void basis(Vec3d n, Vec3d& u, Vec3d& v) {
  const Vec3d a = std::abs(n.x) < 0.6 ? Vec3d{1, 0, 0} : (std::abs(n.y) < 0.6 ? Vec3d{0, 1, 0} : Vec3d{0, 0, 1});
  u = cross(n, a);
  u = u * (1.0 / length(u));
  v = cross(n, u);
}

struct ConeDir {
  Vec3d local;  // (x, y, z) with z along the cone's axis
  double angle;
};

// Directions spread evenly in solid angle over the cap (Fibonacci spiral), axis first.
std::vector<ConeDir> cone_directions(int k, double full_angle_deg) {
  std::vector<ConeDir> dirs{{{0, 0, 1}, 0.0}};
  const double half = full_angle_deg * std::numbers::pi / 360.0;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 1; i < k; ++i) {
    const double c = 1.0 - (1.0 - std::cos(half)) * (double(i) - 0.5) / double(k - 1);
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = golden * i;
    dirs.push_back({{s * std::cos(phi), s * std::sin(phi), c}, std::acos(std::clamp(c, -1.0, 1.0))});
  }
  return dirs;
}

void check_options(const Accel& accel, const ThicknessOptions& o) {
  if (!(o.max_distance > 0)) throw std::invalid_argument("thickness: max distance must be positive");
  if (!(o.min_thickness >= 0)) throw std::invalid_argument("thickness: min thickness must be >= 0");
  if (o.method == ThicknessMethod::cone) {
    if (o.cone_rays < 1) throw std::invalid_argument("thickness: cone needs at least one ray");
    if (!(o.cone_angle_deg > 0 && o.cone_angle_deg < 180))
      throw std::invalid_argument("thickness: cone angle must be in (0, 180) degrees");
  }
  if (!(o.tie_tolerance_rel >= 0)) throw std::invalid_argument("thickness: tie tolerance must be >= 0");
  if (!is_exact(o.kernel)) throw std::invalid_argument("thickness: needs an exact kernel");
  for (auto s : o.solids)
    if (s >= accel.scene().geometries().size())
      throw std::invalid_argument("thickness: no solid with id " + std::to_string(s));
  if (!o.sample_mask.empty()) {
    const auto& geos = accel.scene().geometries();
    if (o.sample_mask.size() != geos.size())
      throw std::invalid_argument("thickness: the sample mask needs one entry per solid");
    for (std::size_t g = 0; g < geos.size(); ++g) {
      const std::size_t n = o.per == SampleAt::vertex ? geos[g].vertices.size() : geos[g].triangles.size();
      if (!o.sample_mask[g].empty() && o.sample_mask[g].size() != n)
        throw std::invalid_argument("thickness: the sample mask of solid " + std::to_string(g) +
                                    " does not match its element count");
    }
  }
}

}  // namespace

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

// The ray starts on the solid's surface heading inward, so it is inside (depth 1) from the
// start. Crossings within `tie` of the origin are the start triangle, its neighbours through
// the same vertex and coplanar duplicates, all at t = 0 up to rounding: skipped via tmin.
// Beyond that, only this geometry's crossings count (a touching neighbour's coincident face
// is another geometry). Crossings of this geometry within `tie` of each other form one group
// (coplanar duplicates, whose t may differ by rounding): a group's leaves are applied once and
// before its enters, so a duplicated far face exits once and a zero-thickness fold (leave and
// enter together) still exits where the material ends.
double ray_exit_distance(HitIterator& it, std::uint32_t geom, Vec3d point, Vec3d dir, double max_distance,
                         double tie, double offset) {
  // Below the offset only the start triangle can be crossed, and its crossing is below `tie`.
  it.begin(Ray{point, dir, std::max(tie, offset), max_distance});
  int depth = 1;
  double group_t = -std::numeric_limits<double>::infinity();
  bool left_in_group = false, enter_pending = false;
  Hit h;
  while (it.next(h)) {
    if (h.geom != geom) continue;
    if (h.t - group_t > tie) {
      if (enter_pending) ++depth;
      group_t = h.t;
      left_in_group = enter_pending = false;
    }
    if (h.enter) {
      enter_pending = true;
    } else if (!left_in_group) {
      left_in_group = true;
      if (--depth <= 0) return h.t;
    }
  }
  return kNaN;
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

ThicknessResult compute_thickness(const Accel& accel, const ThicknessOptions& opts, const Progress& progress) {
  check_options(accel, opts);
  const Scene& scene = accel.scene();
  std::vector<std::uint32_t> solids = opts.solids;
  if (solids.empty())
    for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) solids.push_back(g);

  ThicknessResult res;
  res.per = opts.per;
  SampleSet set;
  std::size_t elements = 0;
  for (std::uint32_t g : solids)
    elements += opts.per == SampleAt::vertex ? scene.geometry(g).vertices.size() : scene.geometry(g).triangles.size();
  res.solid.reserve(elements), res.element.reserve(elements), res.point.reserve(elements);
  res.normal.reserve(elements), res.thickness.reserve(elements), res.thin.reserve(elements);
  res.status.reserve(elements), set.samples.reserve(elements);
  std::vector<std::pair<std::size_t, std::size_t>> ranges;  // result range per entry of `solids`
  for (std::uint32_t g : solids) {
    const Geometry& geo = scene.geometry(g);
    const auto weld = weld_by_position(geo.vertices);
    const std::size_t base = res.size();
    auto push = [&](std::uint32_t element, Vec3d p, Vec3d n) {
      res.solid.push_back(g);
      res.element.push_back(element);
      res.point.push_back(p);
      res.normal.push_back(n);
      res.thickness.push_back(kNaN);
      res.thin.push_back(0);
      res.status.push_back(n == Vec3d{} ? ThicknessStatus::no_normal : ThicknessStatus::ok);
    };
    const bool masked = !opts.sample_mask.empty();
    const std::vector<std::uint8_t>* mask = masked ? &opts.sample_mask[g] : nullptr;
    auto selected = [&](std::uint32_t e) { return !masked || (!mask->empty() && (*mask)[e] != 0); };
    if (opts.per == SampleAt::vertex) {
      const auto normals = vertex_normals(geo, weld);
      // With a mask, a group of coincident vertices is measured (at its first vertex) when any
      // of its vertices is selected.
      std::vector<std::uint8_t> group_wanted;
      std::vector<std::uint32_t> out_of;  // result index of each pushed vertex
      if (masked) {
        group_wanted.assign(geo.vertices.size(), 0);
        for (std::uint32_t v = 0; v < geo.vertices.size(); ++v)
          if (selected(v)) group_wanted[weld[v]] = 1;
        out_of.assign(geo.vertices.size(), kInvalidId);
      }
      // Triangles around each welded vertex, for the sphere method's exclusions.
      std::vector<std::vector<std::uint32_t>> around;
      if (opts.method == ThicknessMethod::sphere) {
        around.resize(geo.vertices.size());
        for (std::uint32_t t = 0; t < geo.triangles.size(); ++t)
          for (auto v : geo.triangles[t]) {
            auto& list = around[weld[v]];
            if (list.empty() || list.back() != t) list.push_back(t);
          }
      }
      for (std::uint32_t v = 0; v < geo.vertices.size(); ++v) {
        if (masked && !selected(v) && !(weld[v] == v && group_wanted[v])) continue;
        push(v, geo.vertices[v], normals[v]);
        const std::uint32_t out = std::uint32_t(res.size() - 1);
        if (masked) out_of[v] = out;
        if (normals[v] == Vec3d{}) continue;
        if (weld[v] != v) {
          set.copies.emplace_back(out, masked ? out_of[weld[v]] : std::uint32_t(base + weld[v]));
          continue;
        }
        Sample s{g, out, geo.vertices[v], normals[v] * -1.0, std::uint32_t(set.exclude.size()), 0};
        if (!around.empty()) set.exclude.insert(set.exclude.end(), around[v].begin(), around[v].end());
        s.exclude_end = std::uint32_t(set.exclude.size());
        set.samples.push_back(s);
      }
    } else {
      // A triangle repeating an earlier one's corners (a duplicated face, whatever its winding)
      // is measured like the first one, as vertex normals count it.
      const auto first = first_occurrence(geo, weld);
      for (std::uint32_t t = 0; t < geo.triangles.size(); ++t) {
        if (!selected(t)) continue;
        const Tri& tri = geo.triangles[t];
        const Vec3d c = (geo.vertices[tri[0]] + geo.vertices[tri[1]] + geo.vertices[tri[2]]) * (1.0 / 3.0);
        const Vec3d n = geo.degenerate[t] ? Vec3d{} : face_normal(geo, first[t]);
        push(t, c, n);
        if (n == Vec3d{}) continue;
        const std::uint32_t ex = std::uint32_t(set.exclude.size());
        set.exclude.push_back(t);
        set.samples.push_back({g, std::uint32_t(res.size() - 1), c, n * -1.0, ex, ex + 1, t});
      }
    }
    ranges.emplace_back(base, res.size());
  }

  // Sphere method: one closest-point BVH per sampled solid (queries stay inside the solid).
  std::vector<Bvhd> solid_bvh;
  std::vector<std::uint32_t> bvh_of(scene.geometries().size(), kInvalidId);
  if (opts.method == ThicknessMethod::sphere) {
    for (std::uint32_t g : solids) {
      if (bvh_of[g] != kInvalidId) continue;
      Scene one;
      one.add_mesh(scene.geometry(g).vertices, scene.geometry(g).triangles);
      bvh_of[g] = std::uint32_t(solid_bvh.size());
      solid_bvh.push_back(build_bvh<double>(one));
    }
  }

  const double tie = tie_distance(scene, opts.tie_tolerance_rel);
  std::optional<OriginOffsets> offsets;
  if (uses_origin_offsets(opts)) offsets = build_origin_offsets(scene, accel.bvh(), opts.offset_set);
  auto offset_of = [&](const Sample& s, Vec3d dir) {
    return offsets && s.prim != kInvalidId ? safe_offset(*offsets, s.geom, s.prim, s.point, dir) : 0.0;
  };
  const std::vector<ConeDir> cone =
      opts.method == ThicknessMethod::cone ? cone_directions(opts.cone_rays, opts.cone_angle_deg)
                                           : std::vector<ConeDir>{};
  const double min_cone_angle = cone.size() > 1 ? cone[1].angle : 1.0;
  KernelOptions kopts;
  kopts.order.tie = TieOrder::leave_before_enter;

  struct Worker {
    HitIterator it;
    std::vector<std::uint32_t> stack;
    std::vector<std::pair<double, double>> lens;
  };
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker{HitIterator(accel, opts.kernel, kopts), {}, {}}; });

  auto measure = [&](Worker& w, const Sample& s) -> double {
    const double ray_t =
        ray_exit_distance(w.it, s.geom, s.point, s.inward, opts.max_distance, tie, offset_of(s, s.inward));
    switch (opts.method) {
      case ThicknessMethod::ray: return ray_t;
      case ThicknessMethod::cone: {
        Vec3d u, v;
        basis(s.inward, u, v);
        w.lens.clear();
        std::size_t escaped = 0;
        for (std::size_t i = 0; i < cone.size(); ++i) {
          const Vec3d d = u * cone[i].local.x + v * cone[i].local.y + s.inward * cone[i].local.z;
          const double t =
              i == 0 ? ray_t : ray_exit_distance(w.it, s.geom, s.point, d, opts.max_distance, tie, offset_of(s, d));
          if (std::isnan(t)) ++escaped;
          else w.lens.emplace_back(t, cone[i].angle);
        }
        // Most rays escaping means there is no enclosed material here to measure.
        if (w.lens.empty() || 2 * escaped > cone.size()) return kNaN;
        return cone_aggregate(w.lens, opts.cone_aggregate, min_cone_angle);
      }
      case ThicknessMethod::sphere: {
        if (std::isnan(ray_t)) return kNaN;
        const Bvhd& bvh = solid_bvh[bvh_of[s.geom]];
        const std::span<const std::uint32_t> exclude(set.exclude.data() + s.exclude_begin,
                                                     s.exclude_end - s.exclude_begin);
        // Shrinking ball (Ma et al. 2012): the ball touching the point with its centre on the
        // inward normal shrinks to pass through the nearest surface point inside it, until
        // none is left. It starts at half the ray thickness, which bounds it.
        double r = 0.5 * ray_t;
        for (int iter = 0; iter < opts.sphere_max_iterations && r > tie; ++iter) {
          const Vec3d c = s.point + s.inward * r;
          const ClosestPoint cp = closest_point(bvh, c, r * r, exclude, w.stack);
          if (!cp.found() || cp.dist2 >= r * r * (1.0 - 1e-12)) break;
          const Vec3d d = cp.point - s.point;
          const double denom = 2.0 * dot(s.inward, d);
          if (!(denom > 0)) break;
          const double rn = dot(d, d) / denom;
          if (!(rn < r)) break;
          r = rn;
        }
        return 2.0 * r;
      }
    }
    return kNaN;
  };

  const bool completed = parallel_for_items(set.samples.size(), 64, workers, progress, [&](Worker& w, std::size_t i) {
    const Sample& s = set.samples[i];
    const double t = measure(w, s);
    res.thickness[s.out_index] = t;
    res.status[s.out_index] = std::isnan(t) ? ThicknessStatus::no_exit : ThicknessStatus::ok;
  });
  if (!completed) {
    res.completed = false;
    return res;
  }
  for (auto [to, from] : set.copies) {
    res.thickness[to] = res.thickness[from];
    res.status[to] = res.status[from];
  }
  for (std::size_t i = 0; i < res.size(); ++i)
    res.thin[i] = std::isfinite(res.thickness[i]) && res.thickness[i] < opts.min_thickness;

  for (std::size_t k = 0; k < solids.size(); ++k) {
    SolidThickness st;
    st.geom = solids[k];
    st.name = scene.geometry(solids[k]).name;
    const auto [b, e] = ranges[k];
    st.elements = e - b;
    std::vector<double> values;
    for (std::size_t i = b; i < e; ++i) {
      st.no_exit += res.status[i] == ThicknessStatus::no_exit;
      st.no_normal += res.status[i] == ThicknessStatus::no_normal;
      st.thin += res.thin[i];
      if (std::isfinite(res.thickness[i])) values.push_back(res.thickness[i]);
    }
    st.valid = values.size();
    st.summary = summarize(std::move(values), opts.percentiles, opts.histogram_bins);
    res.solids.push_back(std::move(st));
  }
  return res;
}

}  // namespace pierce::analysis
