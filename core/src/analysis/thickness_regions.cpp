// Thickness, stage 4: thin and thick samples grouped into regions (thickness_regions.h), each
// with its extreme sample, its exit and its area on both sides of the wall.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "pierce/analysis/bvh_query.h"
#include "pierce/analysis/mesh_topology.h"
#include "pierce/parallel_for_items.h"
#include "pierce/wide_bvh.h"
#include "thickness_internal.h"

namespace pierce::analysis::detail {

namespace {

constexpr std::uint8_t kThin = 1, kThick = 2;

// Refinement limits: a flagged area is subdivided uniformly down to sub-triangles of
// kCoarseDiv-th of the region's size, and where the flag changes down to kFineDiv-th of it,
// never deeper than kMaxDepth levels; all refinement together traces at most kRayBudget rays
// (spread evenly over the refined triangles, at least kMinRaysPerTriangle each), so a large
// model stays cheap whatever its regions.
constexpr double kCoarseDiv = 2, kFineDiv = 32;
constexpr int kMaxDepth = 12;
constexpr std::size_t kRayBudget = std::size_t(1) << 22, kMinRaysPerTriangle = 256,
                      kMaxRaysPerTriangle = std::size_t(1) << 16;

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// One sampled solid's topology: welded vertices, triangles around each welded vertex (CSR) and
// the result row of each element (kInvalidId where not sampled).
struct SolidTopo {
  std::uint32_t geom = 0;
  const Geometry* geo = nullptr;
  std::span<const std::uint32_t> weld;  // SampleSet::welds
  std::vector<std::uint32_t> around_begin, around, row_of;

  std::span<const std::uint32_t> around_vertex(std::uint32_t v) const {
    const std::uint32_t w = weld[v];
    return {around.data() + around_begin[w], around_begin[w + 1] - around_begin[w]};
  }
};

SolidTopo make_topo(const Scene& scene, std::uint32_t g, const std::vector<std::uint32_t>& weld, SampleAt per,
                    const ThicknessResult& res, std::pair<std::size_t, std::size_t> range) {
  SolidTopo t;
  t.geom = g;
  t.geo = &scene.geometry(g);
  const Geometry& geo = *t.geo;
  t.weld = weld;
  t.around_begin.assign(geo.vertices.size() + 1, 0);
  for (const Tri& tri : geo.triangles)
    for (auto v : tri) ++t.around_begin[t.weld[v] + 1];
  for (std::size_t v = 0; v < geo.vertices.size(); ++v) t.around_begin[v + 1] += t.around_begin[v];
  t.around.resize(t.around_begin.back());
  std::vector<std::uint32_t> fill(t.around_begin.begin(), t.around_begin.end() - 1);
  for (std::uint32_t i = 0; i < geo.triangles.size(); ++i)
    for (auto v : geo.triangles[i]) t.around[fill[t.weld[v]]++] = i;
  t.row_of.assign(per == SampleAt::vertex ? geo.vertices.size() : geo.triangles.size(), kInvalidId);
  for (std::size_t i = range.first; i < range.second; ++i) t.row_of[res.element[i]] = std::uint32_t(i);
  // A vertex without a row of its own (a sample mask left it to its coincident vertices, as in
  // distributed runs where the cut's vertices exist once per process) stands for its group's row,
  // so that connectivity and areas do not depend on how the vertices were split.
  if (per == SampleAt::vertex)
    for (std::uint32_t v = 0; v < geo.vertices.size(); ++v)
      if (t.row_of[v] == kInvalidId) t.row_of[v] = t.row_of[t.weld[v]];
  return t;
}

double tri_area(Vec3d a, Vec3d b, Vec3d c) { return 0.5 * length(cross(b - a, c - a)); }

double longest_edge(Vec3d a, Vec3d b, Vec3d c) {
  return std::sqrt(std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)}));
}

// The triangle of geometry `geom` closest to q (kInvalidId if the geometry has none), found on
// the scene's float BVH and measured in double: boxes around q grow until one holds a triangle
// of the solid.
std::uint32_t nearest_triangle(const Scene& scene, const WideBvhf& bvh, std::uint32_t geom, Vec3d q, double start,
                               double limit, NodeStack<float>& stack) {
  for (double h = start; h <= limit; h *= 8) {
    BBoxd box;
    box.lo = q - Vec3d{h, h, h}, box.hi = q + Vec3d{h, h, h};
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t prim = kInvalidId;
    for_each_overlapping(scene, bvh, box, stack, [&](const Triangle<double>& t) {
      if (t.geom != geom) return;
      const Vec3d p = closest_point_on_triangle(q, t.v0, t.v1, t.v2);
      const double d2 = dot(p - q, p - q);
      if (d2 < best || (d2 == best && t.prim < prim)) best = d2, prim = t.prim;
    });
    // Only a triangle within the box's half size is surely the nearest one.
    if (prim != kInvalidId && best <= h * h) return prim;
  }
  return kInvalidId;
}

struct Sub {
  Vec3d a, b, c;
  int depth;
};

struct Worker {
  HitIterator it;
  std::vector<Sub> subs;
};

// One triangle to refine, for the first region that reached it.
struct RefineItem {
  std::uint32_t region, geom, tri;
  double coarse, fine;  // sub-triangle sizes: uniform down to coarse, down to fine where mixed
};

}  // namespace

void find_regions(const Accel& accel, const ThicknessOptions& opts, const SampleSet& set, ThicknessResult& res) {
  const Scene& scene = accel.scene();
  const std::size_t n = res.size();
  res.region.assign(n, -1);
  const bool want_thin = opts.min_thickness > 0, want_thick = std::isfinite(opts.max_thickness);
  if ((!want_thin && !want_thick) || set.ranges.size() != set.solids.size()) return;
  if (set.welds.size() != set.solids.size()) throw std::logic_error("find_regions: the sample set has no welds");
  // The one rule (thickness_regions.h), for samples and sub-samples alike.
  auto flag_of = [&](double t) -> std::uint8_t {
    if (!std::isfinite(t)) return 0;
    if (want_thin && t < opts.min_thickness) return kThin;
    if (want_thick && t > opts.max_thickness) return kThick;
    return 0;
  };
  std::vector<std::uint8_t> flag(n);
  for (std::size_t i = 0; i < n; ++i) flag[i] = flag_of(res.thickness[i]);
  auto exit_of = [&](std::size_t i) { return res.point[i] - res.normal[i] * res.thickness[i]; };

  UnionFind uf(n);
  auto join = [&](std::uint32_t a, std::uint32_t b) {
    if (a != kInvalidId && b != kInvalidId && flag[a] != 0 && flag[a] == flag[b]) uf.unite(a, b);
  };
  std::vector<SolidTopo> topo;
  std::vector<std::uint32_t> topo_of(scene.geometries().size(), kInvalidId);
  std::vector<std::uint32_t> exit_tri(n, kInvalidId);
  const WideBvhf& bvh = accel.wide();
  const double tie = tie_distance(scene, opts.tie_tolerance_rel);
  const double start = std::max(tie, 1e-9 * scene.scale()), limit = 2 * scene.scale();
  for (std::size_t k = 0; k < set.solids.size(); ++k) {
    const auto [b, e] = set.ranges[k];
    bool any = false;
    for (std::size_t i = b; i < e && !any; ++i) any = flag[i] != 0;
    if (!any) continue;
    const std::uint32_t g = set.solids[k];
    topo_of[g] = std::uint32_t(topo.size());
    topo.push_back(make_topo(scene, g, set.welds[k], opts.per, res, set.ranges[k]));
    const SolidTopo& t = topo.back();
    const Geometry& geo = *t.geo;
    if (opts.per == SampleAt::vertex) {
      for (const Tri& tri : geo.triangles)
        for (int c = 0; c < 3; ++c) join(t.row_of[tri[std::size_t(c)]], t.row_of[tri[std::size_t((c + 1) % 3)]]);
      for (std::uint32_t v = 0; v < geo.vertices.size(); ++v) join(t.row_of[v], t.row_of[t.weld[v]]);
    } else {
      for (std::uint32_t v = 0; v < geo.vertices.size(); ++v) {
        if (t.weld[v] != v) continue;
        const auto ring = t.around_vertex(v);
        for (std::size_t j = 1; j < ring.size(); ++j)
          for (std::size_t m = 0; m < j; ++m) {
            const std::uint32_t a = t.row_of[ring[j]], c = t.row_of[ring[m]];
            if (a != kInvalidId && c != kInvalidId && flag[a] == flag[c]) {
              join(a, c);
              break;  // joined with one earlier triangle of its class: the rest follow
            }
          }
      }
    }
    // Where each flagged sample's ray leaves: the triangle the trace recorded, else the nearest
    // triangle of the same solid to the exit point.
    tbb::enumerable_thread_specific<NodeStack<float>> stacks;
    parallel_for_items(e - b, 256, stacks, {}, [&](NodeStack<float>& stack, std::size_t j) {
      const std::size_t i = b + j;
      if (flag[i] == 0) return;
      exit_tri[i] = res.exit_triangle[i];
      if (exit_tri[i] == kInvalidId) exit_tri[i] = nearest_triangle(scene, bvh, g, exit_of(i), start, limit, stack);
    });
    for (std::size_t i = b; i < e; ++i) {
      if (exit_tri[i] == kInvalidId) continue;
      if (opts.per == SampleAt::face) {
        join(std::uint32_t(i), t.row_of[exit_tri[i]]);
      } else {
        for (auto v : geo.triangles[exit_tri[i]]) join(std::uint32_t(i), t.row_of[v]);
      }
    }
  }

  // Regions: the extreme sample of each root, sorted; then the ids.
  struct Found {
    std::uint32_t root, extreme;
    std::size_t samples = 0;
  };
  // A region counts sample points: per vertex, coincident vertices (one sample, copied) once.
  // Its extreme is the most extreme sample, the lowest point (x, y, z) among equals, so that
  // neither depends on the order of the rows.
  auto counts_as_sample = [&](std::uint32_t i) {
    if (opts.per != SampleAt::vertex) return true;
    const std::uint32_t v = res.element[i];
    return topo[topo_of[res.solid[i]]].weld[v] == v;
  };
  std::vector<std::uint32_t> slot(n, kInvalidId);
  std::vector<Found> found;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (flag[i] == 0) continue;
    const std::uint32_t r = uf.find(i);
    if (slot[r] == kInvalidId) slot[r] = std::uint32_t(found.size()), found.push_back({r, i});
    Found& f = found[slot[r]];
    f.samples += counts_as_sample(i);
    const double t = res.thickness[i], best = res.thickness[f.extreme];
    const bool more = flag[i] == kThin ? t < best : t > best;
    const Vec3d p = res.point[i], q = res.point[f.extreme];
    if (more || (t == best && std::tuple(p.x, p.y, p.z) < std::tuple(q.x, q.y, q.z))) f.extreme = i;
  }
  auto key = [&](const Found& f) {
    const Vec3d p = res.point[f.extreme];
    const double t = res.thickness[f.extreme];
    return std::tuple(flag[f.extreme] == kThin ? 0 : 1, flag[f.extreme] == kThin ? t : -t, res.solid[f.extreme], p.x,
                      p.y, p.z, f.extreme);
  };
  std::sort(found.begin(), found.end(), [&](const Found& a, const Found& b) { return key(a) < key(b); });
  std::vector<ThicknessRegion> regions(found.size());
  std::vector<std::int32_t> id_of_root(n, -1);
  std::size_t thin_count = 0;
  for (std::size_t r = 0; r < found.size(); ++r) {
    const Found& f = found[r];
    ThicknessRegion& reg = regions[r];
    reg.solid = res.solid[f.extreme];
    reg.thick = flag[f.extreme] == kThick;
    reg.thickness = res.thickness[f.extreme];
    reg.point = res.point[f.extreme];
    reg.exit = exit_of(f.extreme);
    reg.samples = f.samples;
    id_of_root[f.root] = std::int32_t(r);
    thin_count += flag[f.extreme] == kThin;
  }
  for (std::uint32_t i = 0; i < n; ++i)
    if (flag[i] != 0) res.region[i] = id_of_root[uf.find(i)];

  // Area. Each region's triangles (holding its samples or exits, and rings around them, below); a
  // triangle is taken by the first region (in id order) of its class that reaches it, so none
  // counts twice. One whose own and neighbours' samples are all in that region counts whole for
  // it; one already finer than the refinement's finest step is shared out by its samples; the
  // others are refined once, their flagged area shared out among the regions below.
  std::vector<std::vector<std::int32_t>> owner(2);  // per class: per (topo, triangle), by offset
  std::vector<std::size_t> tri_base(topo.size() + 1, 0);
  for (std::size_t k = 0; k < topo.size(); ++k) tri_base[k + 1] = tri_base[k] + topo[k].geo->triangles.size();
  owner[0].assign(tri_base.back(), -1), owner[1].assign(tri_base.back(), -1);
  // The samples of each region (CSR).
  std::vector<std::uint32_t> member_begin(regions.size() + 1, 0), members;
  for (std::uint32_t i = 0; i < n; ++i)
    if (res.region[i] >= 0) ++member_begin[std::size_t(res.region[i]) + 1];
  for (std::size_t r = 0; r < regions.size(); ++r) member_begin[r + 1] += member_begin[r];
  members.resize(member_begin.back());
  {
    std::vector<std::uint32_t> fill(member_begin.begin(), member_begin.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i)
      if (res.region[i] >= 0) members[fill[std::size_t(res.region[i])]++] = i;
  }
  // Region sizes for the refinement limits: the extent of the region's samples and exits, at
  // least its extreme thickness.
  std::vector<BBoxd> extent(regions.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    if (res.region[i] < 0) continue;
    extent[std::size_t(res.region[i])].extend(res.point[i]);
    extent[std::size_t(res.region[i])].extend(exit_of(i));
  }
  auto region_size = [&](std::size_t r) {
    return std::max(length(extent[r].hi - extent[r].lo), regions[r].thickness);
  };
  // Flagged area of triangle `tri` for region r (and its B-rep face, for CAD).
  auto credit_region = [&](const SolidTopo& topology, std::uint32_t tri, std::int32_t r, double area) {
    if (!(area > 0)) return;
    ThicknessRegion& reg = regions[std::size_t(r)];
    reg.area += area;
    if (opts.exact && opts.exact->covers(topology.geom)) reg.faces.push_back(opts.exact->face_of(topology.geom, tri));
  };
  // A triangle no longer than the finest sub-triangle refinement would trace is sampled densely
  // enough already: its samples of class `want` share out its area (a corner's third each per
  // vertex, all of it per face), with no rays traced.
  auto share_out = [&](const SolidTopo& topology, std::uint32_t tri, std::uint8_t want, double area) {
    auto share = [&](std::uint32_t element, double part) {
      const std::uint32_t row = topology.row_of[element];
      if (row != kInvalidId && flag[row] == want) credit_region(topology, tri, res.region[row], part);
    };
    if (opts.per == SampleAt::face) {
      share(tri, area);
    } else {
      for (auto v : topology.geo->triangles[tri]) share(v, area / 3);
    }
  };
  std::vector<RefineItem> items;
  std::vector<std::uint32_t> listed(tri_base.back(), kInvalidId);  // the last region listing it
  auto in_region = [&](const SolidTopo& t, std::uint32_t element, std::int32_t r) {
    const std::uint32_t row = t.row_of[element];
    return row != kInvalidId && res.region[row] == r;
  };
  for (std::size_t r = 0; r < regions.size(); ++r) {
    const std::uint32_t k = topo_of[regions[r].solid];
    const SolidTopo& t = topo[k];
    const Geometry& geo = *t.geo;
    auto& own = owner[r < thin_count ? 0 : 1];
    // The triangles that may hold some of the region's area: each once, a sample's own triangle
    // (per face) and every exit triangle, then per vertex those around its samples, then the
    // one-ring of the first. Per vertex, an exit triangle no longer than a coarse sub-triangle
    // grows none: samples that close together on its side show its thin area by themselves
    // (joining the region through their own rays), so only a coarse far face, whose samples lie
    // outside the region's shadow, needs its neighbours refined.
    std::vector<std::uint32_t> tris;
    auto list = [&](std::uint32_t tri) {
      if (std::uint32_t& l = listed[tri_base[k] + tri]; l != r) l = std::uint32_t(r), tris.push_back(tri);
    };
    const std::span<const std::uint32_t> mine(members.data() + member_begin[r], member_begin[r + 1] - member_begin[r]);
    for (std::uint32_t i : mine) {
      if (opts.per == SampleAt::face) list(res.element[i]);
      if (exit_tri[i] != kInvalidId) list(exit_tri[i]);
    }
    const std::size_t unique_seeds = tris.size();
    if (opts.per == SampleAt::vertex)
      for (std::uint32_t i : mine)
        for (std::uint32_t tri : t.around_vertex(res.element[i])) list(tri);
    const double coarse = region_size(r) / kCoarseDiv, fine = region_size(r) / kFineDiv;
    for (std::size_t q = 0; q < unique_seeds; ++q) {
      const Tri& c = geo.triangles[tris[q]];
      if (opts.per == SampleAt::vertex && longest_edge(geo.vertices[c[0]], geo.vertices[c[1]], geo.vertices[c[2]]) <= coarse)
        continue;
      for (auto v : c)
        for (std::uint32_t nb : t.around_vertex(v)) list(nb);
    }
    // In triangle order: sorted, or for a region over much of its solid, read off the marks.
    if (tris.size() * 8 < geo.triangles.size()) {
      std::sort(tris.begin(), tris.end());
    } else {
      tris.clear();
      for (std::uint32_t tri = 0; tri < geo.triangles.size(); ++tri)
        if (listed[tri_base[k] + tri] == r) tris.push_back(tri);
    }
    for (std::uint32_t tri : tris) {
      std::int32_t& o = own[tri_base[k] + tri];
      if (o >= 0) continue;
      o = std::int32_t(r);
      bool whole = true;
      if (opts.per == SampleAt::vertex) {
        for (auto v : geo.triangles[tri]) whole = whole && in_region(t, v, std::int32_t(r));
      } else {
        for (auto v : geo.triangles[tri])
          for (std::uint32_t nb : t.around_vertex(v)) whole = whole && in_region(t, nb, std::int32_t(r));
      }
      const Tri& c = geo.triangles[tri];
      const double area = tri_area(geo.vertices[c[0]], geo.vertices[c[1]], geo.vertices[c[2]]);
      if (whole) {
        credit_region(t, tri, std::int32_t(r), area);
      } else if (longest_edge(geo.vertices[c[0]], geo.vertices[c[1]], geo.vertices[c[2]]) <= fine) {
        if (!geo.degenerate[tri]) share_out(t, tri, r < thin_count ? kThin : kThick, area);
      } else {
        items.push_back({std::uint32_t(r), t.geom, tri, 0, 0});
      }
    }
  }
  for (RefineItem& it : items) {
    const double size = region_size(it.region);
    it.coarse = size / kCoarseDiv, it.fine = size / kFineDiv;
  }
  const std::size_t per_tri =
      items.empty() ? 0 : std::clamp(kRayBudget / items.size(), kMinRaysPerTriangle, kMaxRaysPerTriangle);

  KernelOptions kopts;
  kopts.order.tie = TieOrder::leave_before_enter;  // what ray_exit_distance requires
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker{HitIterator(accel, opts.kernel, kopts), {}}; });
  // A region of class `want` among the samples of triangle `tri` (its own, or its corners'), or -1.
  auto region_on = [&](const SolidTopo& t, std::uint32_t tri, std::uint8_t want) -> std::int32_t {
    auto of = [&](std::uint32_t element) {
      const std::uint32_t row = t.row_of[element];
      return row != kInvalidId && flag[row] == want ? res.region[row] : -1;
    };
    if (opts.per == SampleAt::face) return of(tri);
    for (auto v : t.geo->triangles[tri])
      if (const std::int32_t r = of(v); r >= 0) return r;
    return -1;
  };
  // Per item, the flagged area by region: a flagged sub-triangle belongs to the region of its
  // triangle's samples, else to that of the samples where its ray exits (as samples are grouped),
  // else to the region that reached the triangle first. So a coarse triangle under two thin
  // floors gives each floor its own share.
  std::vector<std::vector<std::pair<std::int32_t, double>>> item_area(items.size());
  parallel_for_items(items.size(), 4, workers, {}, [&](Worker& w, std::size_t j) {
    const RefineItem& item = items[j];
    const std::uint8_t want = item.region < thin_count ? kThin : kThick;
    const SolidTopo& topology = topo[topo_of[item.geom]];
    const Geometry& geo = *topology.geo;
    const Tri& tri = geo.triangles[item.tri];
    if (geo.degenerate[item.tri]) return;
    const Vec3d inward = face_normal(geo, item.tri) * -1.0;
    if (inward == Vec3d{}) return;
    const std::int32_t own = region_on(topology, item.tri, want);
    auto& out = item_area[j];
    auto credit = [&](std::int32_t r, double a) {
      auto it = std::find_if(out.begin(), out.end(), [&](const auto& e) { return e.first == r; });
      if (it == out.end()) out.emplace_back(r, a);
      else it->second += a;
    };
    const Vec3d v0 = geo.vertices[tri[0]], v1 = geo.vertices[tri[1]], v2 = geo.vertices[tri[2]];
    auto add = [&](const Sub& k, std::uint32_t exit_triangle) {
      std::int32_t r = own;
      if (r < 0 && exit_triangle != kInvalidId) r = region_on(topology, exit_triangle, want);
      if (r < 0) r = std::int32_t(item.region);
      credit(r, tri_area(k.a, k.b, k.c));
    };
    std::size_t rays = 0;
    w.subs.clear();
    w.subs.push_back({v0, v1, v2, 0});
    while (!w.subs.empty()) {
      const Sub s = w.subs.back();
      w.subs.pop_back();
      const Vec3d ab = (s.a + s.b) * 0.5, bc = (s.b + s.c) * 0.5, ca = (s.c + s.a) * 0.5;
      const std::array<Sub, 4> kids{Sub{s.a, ab, ca, s.depth + 1}, Sub{ab, s.b, bc, s.depth + 1},
                                    Sub{ca, bc, s.c, s.depth + 1}, Sub{ab, bc, ca, s.depth + 1}};
      std::array<std::uint32_t, 4> exit{};
      std::array<bool, 4> f{};
      for (std::size_t q = 0; q < 4; ++q) {
        const Vec3d m = (kids[q].a + kids[q].b + kids[q].c) * (1.0 / 3.0);
        f[q] = flag_of(ray_exit(w.it, item.geom, m, inward, opts.max_distance, tie, 0, exit[q])) == want;
      }
      rays += 4;
      const bool mixed = !(f[0] == f[1] && f[1] == f[2] && f[2] == f[3]);
      const double edge = longest_edge(s.a, s.b, s.c);
      const bool deeper = mixed ? 0.5 * edge > item.fine : edge > item.coarse;
      if (deeper && s.depth + 1 < kMaxDepth && rays + 4 * w.subs.size() + 16 <= per_tri) {
        for (const Sub& k : kids) w.subs.push_back(k);
        continue;
      }
      for (std::size_t q = 0; q < 4; ++q)
        if (f[q]) add(kids[q], exit[q]);
    }
  });
  for (std::size_t j = 0; j < items.size(); ++j)
    for (const auto& [r, a] : item_area[j]) credit_region(topo[topo_of[items[j].geom]], items[j].tri, r, a);
  for (ThicknessRegion& reg : regions) {
    std::sort(reg.faces.begin(), reg.faces.end());
    reg.faces.erase(std::unique(reg.faces.begin(), reg.faces.end()), reg.faces.end());
  }
  res.thin_regions.assign(std::make_move_iterator(regions.begin()), std::make_move_iterator(regions.begin() + std::ptrdiff_t(thin_count)));
  res.thick_regions.assign(std::make_move_iterator(regions.begin() + std::ptrdiff_t(thin_count)), std::make_move_iterator(regions.end()));
}

}  // namespace pierce::analysis::detail
