#include "pierce/analysis/ray_overlaps.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "pierce/analysis/tie_distance.h"
#include "pierce/parallel_for_items.h"

namespace pierce::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Axis a ray runs along, or -1 if it is not axis-aligned.
int ray_axis(const Ray& r) {
  const int nonzero = (r.dir.x != 0) + (r.dir.y != 0) + (r.dir.z != 0);
  if (nonzero != 1) return -1;
  return r.dir.x != 0 ? 0 : (r.dir.y != 0 ? 1 : 2);
}

struct ContactAcc {
  std::size_t count = 0;
  std::uint32_t first_ray = 0;
  Vec3d where;
};

struct Local {
  std::vector<Hit> hits;
  std::vector<Interference> intervals;
  std::map<std::pair<std::uint32_t, std::uint32_t>, ContactAcc> contacts;
  CoplanarRayStats stats;
  std::size_t ending_inside = 0;
  // Per-ray scratch.
  std::vector<std::pair<std::uint32_t, int>> depth;  // geometry -> crossing depth (> 0: inside)
  std::vector<std::uint32_t> before, after, marked;
  struct Open {
    std::uint32_t a, b;
    double t;
  };
  std::vector<Open> open;
  struct GroupGeom {
    std::uint32_t geom;
    int net;  // enters minus leaves
  };
  std::vector<GroupGeom> group;
};

int& depth_of(std::vector<std::pair<std::uint32_t, int>>& d, std::uint32_t g) {
  for (auto& [geom, k] : d)
    if (geom == g) return k;
  d.emplace_back(g, 0);
  return d.back().second;
}

void inside_set(const std::vector<std::pair<std::uint32_t, int>>& d, std::vector<std::uint32_t>& out) {
  out.clear();
  for (auto& [g, k] : d)
    if (k > 0) out.push_back(g);
  std::sort(out.begin(), out.end());
}

bool contains(const std::vector<std::uint32_t>& sorted, std::uint32_t g) {
  return std::binary_search(sorted.begin(), sorted.end(), g);
}

}  // namespace

namespace {
// The bounds enlarged by 1% of their largest extent: the box the axis grid covers.
BBoxd axis_grid_box(const BBoxd& bounds) {
  const Vec3d ext = bounds.extent();
  const double pad = 0.01 * std::max({ext.x, ext.y, ext.z, 1e-30});
  BBoxd b = bounds;
  b.lo = b.lo - Vec3d{pad, pad, pad};
  b.hi = b.hi + Vec3d{pad, pad, pad};
  return b;
}
}  // namespace

std::vector<Ray> axis_grid_rays(const BBoxd& bounds, int n, std::span<const int> axes) {
  std::vector<Ray> rays;
  if (bounds.empty() || n <= 0) return rays;
  const BBoxd b = axis_grid_box(bounds);
  const Vec3d e = b.extent();
  for (int axis : axes) {
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    for (int a = 0; a < n; ++a)
      for (int c = 0; c < n; ++c) {
        Ray r;
        r.org[axis] = b.lo[axis];
        r.org[i] = b.lo[i] + e[i] * (a + 0.5) / n;
        r.org[j] = b.lo[j] + e[j] * (c + 0.5) / n;
        r.dir[axis] = 1.0;
        r.tmin = 0;
        r.tmax = e[axis];
        rays.push_back(r);
      }
  }
  return rays;
}

double axis_grid_cell_area(const BBoxd& bounds, int n, int axis) {
  if (bounds.empty() || n <= 0) return 0;
  const Vec3d e = axis_grid_box(bounds).extent();
  return e[(axis + 1) % 3] * e[(axis + 2) % 3] / (double(n) * double(n));
}

RayOverlapReport analyse_ray_overlaps(const Accel& accel, const std::vector<Ray>& rays,
                                      const RayOverlapOptions& opts, const Progress& progress) {
  if (!is_exact(opts.kernel)) throw std::invalid_argument("ray overlaps: needs an exact kernel");
  if (!(opts.epsilon_rel >= 0) || !(opts.tie_tolerance_rel >= 0))
    throw std::invalid_argument("ray overlaps: tolerances must be >= 0");
  const Scene& scene = accel.scene();
  RayOverlapReport rep;
  rep.tri_offset.push_back(0);
  for (const Geometry& g : scene.geometries()) rep.tri_offset.push_back(rep.tri_offset.back() + g.triangles.size());
  const std::size_t ntri = rep.tri_offset.back();
  std::vector<std::atomic<std::uint32_t>> coplanar_hits(ntri), interference_hits(ntri);
  const double epsilon = opts.epsilon_rel * scene.scale();
  const double tie = tie_distance(scene, opts.tie_tolerance_rel);
  rep.coplanar.epsilon = epsilon;

  KernelOptions kopts;
  kopts.order.tie = TieOrder::leave_before_enter;
  struct Worker {
    HitIterator it;
    Local local;
  };
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker{HitIterator(accel, opts.kernel, kopts), {}}; });

  auto process = [&](Local& L, std::uint32_t ray_index, const Ray& ray) {
    const auto& hits = L.hits;
    ++L.stats.rays;
    if (hits.empty()) return;
    ++L.stats.rays_hitting;
    const double dlen = length(ray.dir);
    const double eps_t = epsilon / dlen, tie_t = tie / dlen;
    auto tri = [&](const Hit& h) { return rep.tri_offset[h.geom] + h.prim; };

    // Gribble et al.: equal t and t within epsilon (hits come sorted by t).
    bool equal = false, near = false;
    for (std::size_t i = 0; i < hits.size(); ++i) {
      const bool near_prev = i > 0 && hits[i].t - hits[i - 1].t <= eps_t;
      const bool near_next = i + 1 < hits.size() && hits[i + 1].t - hits[i].t <= eps_t;
      if (i > 0 && hits[i].t == hits[i - 1].t) equal = true;
      if (near_prev || near_next) {
        near = true;
        coplanar_hits[tri(hits[i])].fetch_add(1, std::memory_order_relaxed);
      }
    }
    L.stats.rays_equal_t += equal;
    L.stats.rays_within_eps += near;

    // Interference: crossings within tie_t of a group's first one happen together (coincident
    // faces whose t differ by rounding).
    L.depth.clear();
    L.open.clear();
    for (std::size_t i = 0; i < hits.size();) {
      const double t0 = hits[i].t;
      std::size_t j = i;
      L.group.clear();
      for (; j < hits.size() && hits[j].t - t0 <= tie_t; ++j) {
        auto it = std::find_if(L.group.begin(), L.group.end(), [&](auto& g) { return g.geom == hits[j].geom; });
        if (it == L.group.end()) L.group.push_back({hits[j].geom, 0}), it = L.group.end() - 1;
        it->net += hits[j].enter ? 1 : -1;
      }
      inside_set(L.depth, L.before);
      // A group moves a solid's depth by the sign of its net crossings: a duplicated face counts
      // once, a fold or a face duplicated with opposite winding (enter and leave) not at all. A
      // leave while outside (open mesh, ray starting inside) is ignored.
      for (auto& g : L.group) {
        int& d = depth_of(L.depth, g.geom);
        d = std::max(0, d + (g.net > 0) - (g.net < 0));
      }
      inside_set(L.depth, L.after);
      L.marked.clear();
      const Vec3d at = ray.org + ray.dir * t0;
      // Contacts: a solid left here and another entered here.
      for (auto l : L.before) {
        if (contains(L.after, l)) continue;
        for (auto e : L.after) {
          if (contains(L.before, e) || e == l) continue;
          auto& c = L.contacts[std::minmax(l, e)];
          if (c.count++ == 0 || ray_index < c.first_ray) c.first_ray = ray_index, c.where = at;
        }
      }
      // Close intervals of pairs no longer both inside.
      for (std::size_t k = 0; k < L.open.size();) {
        const auto o = L.open[k];
        if (contains(L.after, o.a) && contains(L.after, o.b)) {
          ++k;
          continue;
        }
        Interference iv{ray_index, o.a, o.b, o.t, t0, (t0 - o.t) * dlen, ray.org + ray.dir * o.t, at};
        L.intervals.push_back(iv);
        for (auto g : {o.a, o.b})
          if (!contains(L.after, g)) L.marked.push_back(g);
        L.open[k] = L.open.back();
        L.open.pop_back();
      }
      // Open intervals of pairs newly inside both.
      for (std::size_t x = 0; x < L.after.size(); ++x)
        for (std::size_t y = x + 1; y < L.after.size(); ++y) {
          const std::uint32_t a = L.after[x], b = L.after[y];
          if (contains(L.before, a) && contains(L.before, b)) continue;
          L.open.push_back({a, b, t0});
          for (auto g : {a, b})
            if (!contains(L.before, g)) L.marked.push_back(g);
        }
      for (std::size_t k = i; k < j; ++k)
        if (std::find(L.marked.begin(), L.marked.end(), hits[k].geom) != L.marked.end())
          interference_hits[tri(hits[k])].fetch_add(1, std::memory_order_relaxed);
      i = j;
    }
    bool inside = false;
    for (auto& [g, d] : L.depth) inside |= d > 0;
    L.ending_inside += inside;
  };

  const bool completed = parallel_for_items(rays.size(), 64, workers, progress, [&](Worker& w, std::size_t r) {
    w.local.hits.clear();
    collect_hits(w.it, rays[r], 0, w.local.hits);
    process(w.local, std::uint32_t(r), rays[r]);
  });
  if (!completed) {
    rep.completed = false;
    return rep;
  }

  std::map<std::pair<std::uint32_t, std::uint32_t>, ContactAcc> contacts;
  for (Worker& w : workers) {
    Local& L = w.local;
    rep.coplanar.rays += L.stats.rays;
    rep.coplanar.rays_hitting += L.stats.rays_hitting;
    rep.coplanar.rays_equal_t += L.stats.rays_equal_t;
    rep.coplanar.rays_within_eps += L.stats.rays_within_eps;
    rep.rays_ending_inside += L.ending_inside;
    rep.intervals.insert(rep.intervals.end(), L.intervals.begin(), L.intervals.end());
    for (auto& [k, c] : L.contacts) {
      ContactAcc& m = contacts[k];
      if (m.count == 0 || c.first_ray < m.first_ray) m.first_ray = c.first_ray, m.where = c.where;
      m.count += c.count;
    }
  }
  for (auto& [k, c] : contacts) rep.contacts.push_back({k.first, k.second, c.count, c.where});
  std::sort(rep.intervals.begin(), rep.intervals.end(), [](const Interference& x, const Interference& y) {
    return std::tie(x.ray, x.t_enter, x.a, x.b) < std::tie(y.ray, y.t_enter, y.a, y.b);
  });
  std::map<std::pair<std::uint32_t, std::uint32_t>, InterferencePair> pairs;
  for (const Interference& iv : rep.intervals) {
    InterferencePair& p = pairs[{iv.a, iv.b}];
    if (p.count == 0) {
      p.a = iv.a, p.b = iv.b;
      p.axis_max_depth = {kNaN, kNaN, kNaN};
    }
    ++p.count;
    if (iv.depth > p.max_depth || p.count == 1)
      p.max_depth = iv.depth, p.max_depth_entry = iv.entry, p.max_depth_ray = iv.ray;
    const int axis = ray_axis(rays[iv.ray]);
    if (axis >= 0 && !(p.axis_max_depth[axis] >= iv.depth)) p.axis_max_depth[axis] = iv.depth;
  }
  for (auto& [k, p] : pairs) {
    p.penetration = kNaN;
    for (double d : p.axis_max_depth)
      if (!std::isnan(d) && !(p.penetration <= d)) p.penetration = d;
    rep.interferences.push_back(p);
  }
  if (!opts.keep_intervals) rep.intervals.clear();
  rep.coplanar_hits.resize(ntri);
  rep.interference_hits.resize(ntri);
  for (std::size_t i = 0; i < ntri; ++i) {
    rep.coplanar_hits[i] = coplanar_hits[i].load();
    rep.interference_hits[i] = interference_hits[i].load();
  }
  return rep;
}

}  // namespace pierce::analysis
