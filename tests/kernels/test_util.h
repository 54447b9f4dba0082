#pragma once
// Shared pieces of the kernel tests: a scene with its acceleration structures, the brute-force
// reference (every non-degenerate triangle through the same intersect(), sorted in the total
// order), hit-list comparison with a readable first difference, and ray generators.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "../common/test_world.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"
#include "pierce/kernels/bvh_common.h"

namespace pierce::test {

// `s` times the unit vector along `axis`.
inline Vec3d axis_unit(int axis, double s = 1.0) {
  Vec3d v{0, 0, 0};
  v[std::size_t(axis)] = s;
  return v;
}

// Point with coordinate `w` on `axis` and (p, q) on the next two axes (right-handed frame).
inline Vec3d on_plane(int axis, double w, double p, double q) {
  Vec3d v;
  v[std::size_t(axis)] = w;
  v[std::size_t((axis + 1) % 3)] = p;
  v[std::size_t((axis + 2) % 3)] = q;
  return v;
}

inline std::vector<KernelKind> exact_kernels() {
  std::vector<KernelKind> out;
  for (KernelKind k : kAllKernels)
    if (is_exact(k)) out.push_back(k);
  return out;
}

inline constexpr TieOrder kTieOrders[] = {TieOrder::geom_prim, TieOrder::leave_before_enter};

inline const char* tie_name(TieOrder t) { return t == TieOrder::geom_prim ? "geom_prim" : "leave_before_enter"; }

// Brute force: every triangle the scene does not mark degenerate, through the same watertight
// test the kernels use, in the kernels' precision, over [tmin, tmax]; sorted in `order`.
inline std::vector<Hit> reference_hits(const Scene& scene, const Ray& ray, HitOrder order) {
  std::vector<Hit> out;
  const auto r = TraversalRay<float>::make(ray, scene.bounds().max_abs_coord());
  if (!r.valid()) return out;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      if (geo.degenerate[p]) continue;
      const Tri& t = geo.triangles[p];
      const Triangle<float> tri{Vec3f(geo.vertices[t[0]]), Vec3f(geo.vertices[t[1]]), Vec3f(geo.vertices[t[2]]), g,
                                p};
      TriangleHit<float> th;
      if (intersect(r, tri.v0, tri.v1, tri.v2, r.tmin, r.tmax, th)) out.push_back(make_hit(tri, th));
    }
  }
  std::sort(out.begin(), out.end(), order);
  return out;
}

inline std::vector<Hit> kernel_hits(HitIterator& it, const Ray& ray, std::size_t max_hits = 0) {
  std::vector<Hit> out;
  collect_hits(it, ray, max_hits, out);
  return out;
}

inline std::string str(const Hit& h) {
  std::ostringstream o;
  o.precision(9);
  o << "{t=" << h.t << " geom=" << h.geom << " prim=" << h.prim << " enter=" << h.enter << " u=" << h.u
    << " v=" << h.v << "}";
  return o.str();
}

inline std::string str(const Ray& r) {
  std::ostringstream o;
  o.precision(17);
  o << "ray org=(" << r.org.x << ", " << r.org.y << ", " << r.org.z << ") dir=(" << r.dir.x << ", " << r.dir.y
    << ", " << r.dir.z << ") t=[" << r.tmin << ", " << r.tmax << "]";
  return o.str();
}

inline bool identical(const Hit& a, const Hit& b) {
  return a.t == b.t && a.geom == b.geom && a.prim == b.prim && a.enter == b.enter && a.u == b.u && a.v == b.v &&
         a.ng == b.ng;
}

// Same length, same hits in the same order (t, geom, prim, enter, barycentrics, normal).
inline ::testing::AssertionResult same_hits(std::span<const Hit> want, std::span<const Hit> got) {
  const std::size_t n = std::min(want.size(), got.size());
  for (std::size_t i = 0; i < n; ++i)
    if (!identical(want[i], got[i]))
      return ::testing::AssertionFailure() << "hit " << i << ": expected " << str(want[i]) << ", got "
                                           << str(got[i]) << " (" << want.size() << " expected, " << got.size()
                                           << " got)";
  if (want.size() != got.size()) {
    auto f = ::testing::AssertionFailure();
    f << "expected " << want.size() << " hits, got " << got.size();
    if (got.size() > n) f << "; first extra " << str(got[n]);
    if (want.size() > n) f << "; first missing " << str(want[n]);
    return f;
  }
  return ::testing::AssertionSuccess();
}

// Hits per geometry, in list order.
inline std::vector<std::vector<Hit>> by_geometry(const std::vector<Hit>& hits, std::size_t geoms) {
  std::vector<std::vector<Hit>> out(geoms);
  for (const Hit& h : hits) out.at(h.geom).push_back(h);
  return out;
}

// A ray starting outside a closed, consistently oriented mesh crosses it an even number of times,
// as many entering as leaving. With `alternate`, the list order must be enter, leave, enter, ...
// (true for generic rays, where no two crossings share a t).
inline ::testing::AssertionResult closed_parity(const std::vector<Hit>& hits, std::size_t geoms, bool alternate) {
  const auto per = by_geometry(hits, geoms);
  for (std::size_t g = 0; g < geoms; ++g) {
    std::size_t enter = 0;
    for (std::size_t i = 0; i < per[g].size(); ++i) {
      enter += per[g][i].enter;
      if (alternate && per[g][i].enter != (i % 2 == 0))
        return ::testing::AssertionFailure() << "geometry " << g << ": crossing " << i << " " << str(per[g][i])
                                             << " breaks enter/leave alternation";
    }
    if (2 * enter != per[g].size())
      return ::testing::AssertionFailure() << "geometry " << g << ": " << per[g].size() << " crossings, " << enter
                                           << " entering";
  }
  return ::testing::AssertionSuccess();
}

// At equal t the list is in the tie policy's order; t never decreases.
inline ::testing::AssertionResult ordered(const std::vector<Hit>& hits, HitOrder order) {
  for (std::size_t i = 1; i < hits.size(); ++i)
    if (!order.less(hits[i - 1], hits[i]))
      return ::testing::AssertionFailure() << "hits " << i - 1 << " and " << i << " out of order: "
                                           << str(hits[i - 1]) << " then " << str(hits[i]);
  return ::testing::AssertionSuccess();
}

// Coordinates as the kernels see them (float), back in double: a ray built from these passes
// through the float vertex, not near it.
inline Vec3d as_float(Vec3d p) { return Vec3d(Vec3f(p)); }

// Origin on a sphere around the box (radius = its diagonal), aimed at a uniform point inside.
inline std::vector<Ray> random_rays(const BBoxd& box, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0), N(-1.0, 1.0);
  const Vec3d c = box.center(), e = box.extent();
  const double radius = std::max(length(e), 1e-300);
  std::vector<Ray> rays;
  while (rays.size() < n) {
    const Vec3d s{N(rng), N(rng), N(rng)};
    const double l = length(s);
    if (l < 0.1 || l > 1.0) continue;
    const Vec3d org = c + s * (radius / l);
    const Vec3d target = box.lo + Vec3d{U(rng) * e.x, U(rng) * e.y, U(rng) * e.z};
    rays.push_back({org, target - org});
  }
  return rays;
}

// Rays from random outside points aimed exactly at (float) vertices of the meshes.
inline std::vector<Ray> vertex_rays(const std::vector<gen::Mesh>& meshes, const BBoxd& box, std::size_t n,
                                    std::uint64_t seed) {
  std::vector<Vec3d> verts;
  for (const auto& m : meshes)
    for (const Vec3d& v : m.vertices) verts.push_back(as_float(v));
  std::mt19937_64 rng(seed);
  std::vector<Ray> rays = random_rays(box, n, seed ^ 0x9e3779b97f4a7c15ull);
  for (Ray& r : rays) {
    r.org = as_float(r.org);
    const Vec3d v = verts[rng() % verts.size()];
    r.dir = v - r.org;
  }
  return rays;
}

// Touching plates, a box duplicated with alternating winding and a blob in one scene, with random
// rays and rays through its vertices (300 of each): hard cases for comparing two ways of
// traversing the same BVH hit for hit.
struct HardCases {
  std::vector<gen::Mesh> meshes;
  std::unique_ptr<World> world;
  std::vector<Ray> rays;
};
inline HardCases hard_cases(std::uint64_t seed) {
  HardCases h;
  h.meshes = gen::stacked_plates(6);
  h.meshes.push_back(gen::duplicated(gen::box({0.2, 0.2, 0.1}, {0.7, 0.7, 0.5}, "dup"), 3, true));
  h.meshes.push_back(gen::blob(3));
  h.world = make_world(h.meshes);
  const BBoxd box = h.world->scene.bounds();
  h.rays = random_rays(box, 300, seed);
  const std::vector<Ray> at_vertices = vertex_rays(h.meshes, box, 300, seed + 1);
  h.rays.insert(h.rays.end(), at_vertices.begin(), at_vertices.end());
  return h;
}

inline Ray transformed(Ray r, double scale, Vec3d offset) {
  r.org = r.org * scale + offset;
  r.dir = r.dir * scale;
  return r;
}

inline gen::Mesh transformed(gen::Mesh m, double scale, Vec3d offset) {
  return gen::translated(gen::scaled(std::move(m), scale), offset);
}

}  // namespace pierce::test
