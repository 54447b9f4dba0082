// Origin offsets (Zoet): a ray started at its safe offset finds exactly the hits it finds from
// the surface, less those on its own start triangle (patch) before the offset; radii are exactly
// 0 wherever other geometry touches a hemisphere's centre; thickness is unchanged by them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "analysis_scenes.h"
#include "hardcases.h"
#include "oracle.h"
#include "pierce/analysis/thickness.h"
#include "pierce/origin_offsets.h"

namespace pierce::test {
namespace {

struct Start {
  std::uint32_t geom, prim;
  Vec3d origin, dir;
};

// Rays starting on the surface: centroids, interior points, edge midpoints, corners and median
// points of random triangles, random directions to either side, a few in the triangle's plane.
std::vector<Start> surface_rays(const Scene& scene, int count, std::uint64_t seed) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> tris;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
    for (std::uint32_t p = 0; p < scene.geometry(g).triangles.size(); ++p)
      if (!scene.geometry(g).degenerate[p]) tris.emplace_back(g, p);
  std::vector<Start> out;
  if (tris.empty()) return out;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < count; ++i) {
    const auto [g, p] = tris[rng() % tris.size()];
    const Geometry& geo = scene.geometry(g);
    Vec3d v[3];
    for (int k = 0; k < 3; ++k) v[k] = Vec3d(Vec3f(geo.vertices[geo.triangles[p][k]]));
    const Vec3d c = (v[0] + v[1] + v[2]) * (1.0 / 3.0);
    Vec3d o;
    switch (rng() % 6) {
      case 0:
      case 1: o = c; break;
      case 2: {
        double a = u01(rng), b = u01(rng);
        if (a + b > 1) a = 1 - a, b = 1 - b;
        o = v[0] + (v[1] - v[0]) * a + (v[2] - v[0]) * b;
        break;
      }
      case 3: o = (v[rng() % 3] + v[rng() % 3]) * 0.5; break;
      case 4: o = v[rng() % 3]; break;
      default: o = (v[rng() % 3] + c) * 0.5; break;
    }
    Vec3d d{gauss(rng), gauss(rng), gauss(rng)};
    if (rng() % 16 == 0) d = v[1] - v[0];  // in the plane
    out.push_back({g, p, o, d});
  }
  return out;
}

std::string describe(const Start& s, double offset) {
  std::ostringstream os;
  os.precision(17);
  os << "geom " << s.geom << " prim " << s.prim << " origin (" << s.origin.x << ", " << s.origin.y << ", "
     << s.origin.z << ") dir (" << s.dir.x << ", " << s.dir.y << ", " << s.dir.z << ") offset " << offset;
  return os.str();
}

struct Tally {
  std::size_t rays = 0, offset_rays = 0, skipped_hits = 0;
};

// The property, for every exact kernel on Pierce's BVH and (when `oracle` is given) against
// the exact hits of the float geometry.
void check_scene(const Accel& accel, const OriginOffsets& oo, const std::vector<Start>& starts,
                 const oracle::Oracle<float>* oracle, Tally& tally, const std::string& label) {
  std::vector<HitIterator> its;
  for (KernelKind k : {KernelKind::filter, KernelKind::queue, KernelKind::restart, KernelKind::nodecull})
    its.emplace_back(accel, k);
  std::vector<Hit> without, with, expected;
  for (const Start& s : starts) {
    const double off = safe_offset(oo, s.geom, s.prim, s.origin, s.dir);
    ASSERT_TRUE(off >= 0 && std::isfinite(off)) << label << " " << describe(s, off);
    ++tally.rays;
    tally.offset_rays += off > 0;
    const std::uint32_t own = oo.surface_id(s.geom, s.prim);
    without.clear();
    collect_hits(its[0], Ray{s.origin, s.dir, 0, std::numeric_limits<double>::infinity()}, 0, without);
    expected.clear();
    for (const Hit& h : without) {
      if (h.t < off && oo.surface_id(h.geom, h.prim) == own) {
        ++tally.skipped_hits;
        continue;
      }
      ASSERT_GE(h.t, off) << label << ": hit on geom " << h.geom << " prim " << h.prim << " before the offset, "
                          << describe(s, off);
      expected.push_back(h);
    }
    for (HitIterator& it : its) {
      with.clear();
      collect_hits(it, Ray{s.origin, s.dir, off, std::numeric_limits<double>::infinity()}, 0, with);
      ASSERT_EQ(with.size(), expected.size()) << label << " kernel " << kernel_name(it.kind()) << " " << describe(s, off);
      for (std::size_t i = 0; i < with.size(); ++i) {
        ASSERT_TRUE(same_hit(with[i], expected[i]) && with[i].enter == expected[i].enter)
            << label << " kernel " << kernel_name(it.kind()) << " hit " << i << " " << describe(s, off);
      }
    }
    if (oracle) {
      const oracle::OracleResult exact = oracle->trace(Ray{s.origin, s.dir, 0, std::numeric_limits<double>::infinity()});
      for (const oracle::ExactHit& h : exact.hits) {
        if (oo.surface_id(h.geom, h.prim) == own) continue;
        ASSERT_GE(h.t_approx, off) << label << ": exact hit on geom " << h.geom << " prim " << h.prim
                                   << " before the offset, " << describe(s, off);
      }
    }
  }
}

TEST(OriginOffsets, HardCaseCorpusLosesNoHit) {
  hard::Options ho;
  ho.rays_per_case = 4;
  ho.deep_layers = 200;
  ho.deep_rays = 2;
  Tally tally;
  std::uint64_t seed = 11;
  for (hard::Case& c : hard::corpus(ho)) {
    if (c.scene.triangle_count() == 0) continue;
    const Accel accel(c.scene);
    const std::vector<Start> starts = surface_rays(c.scene, 24, ++seed);
    std::unique_ptr<oracle::Oracle<float>> orc;
    if (c.scene.triangle_count() <= 3000) orc = std::make_unique<oracle::Oracle<float>>(c.scene);
    for (HemisphereSet kind : kAllHemisphereSets) {
      const OriginOffsets oo = build_origin_offsets(c.scene, accel.wide(), kind);
      check_scene(accel, oo, starts, orc.get(), tally,
                  c.family + "/" + c.name + " set " + std::string(hemisphere_set_name(kind)));
      if (HasFatalFailure()) return;
    }
  }
  // Not vacuous: many of these rays do move (outer faces of plates, grids, slivers' far sides).
  EXPECT_GT(tally.offset_rays * 10, tally.rays) << tally.offset_rays << " of " << tally.rays;
  std::cout << "corpus: " << tally.offset_rays << " of " << tally.rays << " rays offset, " << tally.skipped_hits
            << " start-triangle hits skipped\n";
}

TEST(OriginOffsets, RandomScenesLoseNoHit) {
  Tally tally;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    hard::Case c = hard::random_dyadic(seed, 4 + int(seed % 8), 1);
    if (c.scene.triangle_count() == 0) continue;
    const Accel accel(c.scene);
    const oracle::Oracle<float> orc(c.scene);
    const std::vector<Start> starts = surface_rays(c.scene, 48, seed * 7);
    for (HemisphereSet kind : kAllHemisphereSets) {
      const OriginOffsets oo = build_origin_offsets(c.scene, accel.wide(), kind);
      check_scene(accel, oo, starts, &orc, tally,
                  "random " + std::to_string(seed) + " set " + std::string(hemisphere_set_name(kind)));
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(tally.offset_rays * 10, tally.rays) << tally.offset_rays << " of " << tally.rays;
}

TEST(OriginOffsets, OrganicAndSoupScenesLoseNoHitAndMostRaysMove) {
  // Tilted, non-dyadic geometry: general rays, kernels compared with and without offsets.
  for (const auto& meshes : {std::vector<gen::Mesh>{gen::blob(3)},
                             std::vector<gen::Mesh>{gen::random_soup(400, 0.08, 3)},
                             std::vector<gen::Mesh>{hollow_sphere(2)}}) {
    auto w = make_world(meshes);
    const std::vector<Start> starts = surface_rays(w->scene, 300, 5);
    for (HemisphereSet kind : kAllHemisphereSets) {
      const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), kind);
      Tally tally;
      check_scene(w->accel, oo, starts, nullptr, tally, meshes[0].name + " " + std::string(hemisphere_set_name(kind)));
      if (HasFatalFailure()) return;
      // Centroid-based sets move the rays that start at centroids (a third of them).
      if (kind == HemisphereSet::center || kind == HemisphereSet::median_center) {
        EXPECT_GT(tally.offset_rays * 5, tally.rays) << meshes[0].name << " " << hemisphere_set_name(kind);
      }
    }
  }
}

void expect_all_zero(const OriginOffsets& oo, std::uint32_t g, std::uint32_t p, const std::string& what) {
  for (int side = 0; side < 2; ++side)
    for (const Hemisphere& h : oo.hemispheres(g, p, side))
      EXPECT_EQ(h.radius, 0.0f) << what << " geom " << g << " prim " << p << " side " << side << " set "
                                << hemisphere_set_name(oo.kind());
}

TEST(OriginOffsets, RadiusIsZeroWhereFacesTouchOrCoincide) {
  // Stacked plates: the shared faces have a coincident face in both closed half-spaces; the
  // outermost faces are free on their outward side.
  {
    auto w = make_world(gen::stacked_plates(3, 1.0, 0.25));
    for (HemisphereSet kind : kAllHemisphereSets) {
      const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), kind);
      std::size_t shared = 0, outer = 0;
      for (std::uint32_t g = 0; g < 3; ++g) {
        const Geometry& geo = w->scene.geometry(g);
        for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
          const Tri& t = geo.triangles[p];
          const double z0 = geo.vertices[t[0]].z, z1 = geo.vertices[t[1]].z, z2 = geo.vertices[t[2]].z;
          if (z0 != z1 || z1 != z2) continue;
          if (z0 > 0 && z0 < 0.75) {
            expect_all_zero(oo, g, p, "shared face");
            ++shared;
          } else if (kind == HemisphereSet::center) {
            // Outward side: normal (v1-v0)x(v2-v0) points out of the closed plate.
            EXPECT_GT(oo.hemispheres(g, p, 0)[0].radius, 0.1f) << "outer face " << g << " " << p;
            ++outer;
          }
        }
      }
      EXPECT_EQ(shared, 8u);
      EXPECT_EQ(outer, kind == HemisphereSet::center ? 4u : 0u);
    }
  }
  // Every face duplicated (alternating winding): all radii 0.
  {
    auto w = make_world({gen::duplicated(gen::box({0, 0, 0}, {1, 2, 3}), 2, true)});
    for (HemisphereSet kind : kAllHemisphereSets) {
      const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), kind);
      for (std::uint32_t p = 0; p < w->scene.geometry(0).triangles.size(); ++p) expect_all_zero(oo, 0, p, "duplicate");
    }
  }
  // A box standing on a larger one: its bottom face covers the centroids of the big top face.
  {
    auto w = make_world({gen::box({0, 0, 0}, {4, 4, 1}, "base"), gen::box({1, 1, 1}, {3, 3, 2}, "top")});
    const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), HemisphereSet::center);
    const Geometry& base = w->scene.geometry(0);
    std::size_t covered = 0;
    for (std::uint32_t p = 0; p < base.triangles.size(); ++p) {
      const Tri& t = base.triangles[p];
      if (base.vertices[t[0]].z == 1 && base.vertices[t[1]].z == 1 && base.vertices[t[2]].z == 1) {
        expect_all_zero(oo, 0, p, "covered by the top box");
        ++covered;
      }
    }
    EXPECT_EQ(covered, 2u);
  }
  // A tetrahedron whose apex touches a triangle's centroid (1, 1, 0): radius 0 on both sides
  // (the apex lies in the closed half-space of each); a far triangle keeps a positive radius.
  {
    gen::Mesh floor{"floor", {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {10, 10, 0}, {11, 10, 0}, {10, 11, 0}},
                    {{0, 1, 2}, {3, 4, 5}}};
    gen::Mesh tet{"tet", {{1, 1, 0}, {0, 0, 2}, {2, 0, 2}, {1, 2, 2}}, {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}, {1, 2, 3}}};
    auto w = make_world({floor, tet});
    const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), HemisphereSet::center);
    expect_all_zero(oo, 0, 0, "apex at the centroid");
    EXPECT_GT(oo.hemispheres(0, 1, 0)[0].radius, 0.2f);
    EXPECT_GT(oo.hemispheres(0, 1, 1)[0].radius, 0.2f);
    // Vertex set: the floor's corner (0,0,0) is 2 below the tet's vertex (0,0,2).
    const OriginOffsets ov = build_origin_offsets(w->scene, w->accel.wide(), HemisphereSet::vertex);
    EXPECT_GT(ov.hemispheres(0, 0, 0)[0].radius, 0.5f);
    EXPECT_LT(ov.hemispheres(0, 0, 0)[0].radius, 2.0f);
  }
}

TEST(OriginOffsets, QueryEdgeCases) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1})});
  const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), HemisphereSet::center);
  EXPECT_EQ(oo.memory_bytes() >= 12 * 2 * 16, true);
  const Geometry& g = w->scene.geometry(0);
  const Tri& t = g.triangles[0];
  const Vec3d c = (g.vertices[t[0]] + g.vertices[t[1]] + g.vertices[t[2]]) * (1.0 / 3.0);
  const Vec3d n = cross(g.vertices[t[1]] - g.vertices[t[0]], g.vertices[t[2]] - g.vertices[t[0]]);
  // Inward from the centroid: positive, and less than the distance to the opposite face.
  const double in = safe_offset(oo, 0, 0, c, n * -1.0);
  EXPECT_GT(in, 0);
  EXPECT_LT(in * length(n), 1.0);
  // Outward: nothing else in the scene; the offset is positive too.
  EXPECT_GT(safe_offset(oo, 0, 0, c, n), 0);
  // In the plane, bad ids, an origin outside the ball, non-finite input: 0.
  EXPECT_EQ(safe_offset(oo, 0, 0, c, g.vertices[t[1]] - g.vertices[t[0]]), 0);
  EXPECT_EQ(safe_offset(oo, 1, 0, c, n), 0);
  EXPECT_EQ(safe_offset(oo, 0, 99, c, n), 0);
  EXPECT_EQ(safe_offset(oo, 0, 0, c + n * 100.0, n), 0);
  EXPECT_EQ(safe_offset(oo, 0, 0, c, Vec3d{std::nan(""), 0, 1}), 0);
  // Scaling the direction scales the offset inversely (t is in units of |dir|).
  const double a = safe_offset(oo, 0, 0, c, n * -1.0), b = safe_offset(oo, 0, 0, c, n * -2.0);
  EXPECT_NEAR(a, 2 * b, 1e-9 * a);
  EXPECT_EQ(parse_hemisphere_set("median+center"), HemisphereSet::median_center);
  EXPECT_FALSE(parse_hemisphere_set("nope").has_value());
}

void expect_same_thickness(const analysis::ThicknessResult& a, const analysis::ThicknessResult& b,
                           const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool both_nan = std::isnan(a.thickness[i]) && std::isnan(b.thickness[i]);
    EXPECT_TRUE(both_nan || a.thickness[i] == b.thickness[i])
        << what << " element " << i << ": " << a.thickness[i] << " vs " << b.thickness[i];
    EXPECT_EQ(a.status[i], b.status[i]) << what << " element " << i;
  }
}

TEST(OriginOffsets, ThicknessIsIdenticalWithAndWithout) {
  gen::Mesh one_dup = gen::box({0, 0, 0}, {2, 1, 0.5});
  one_dup.triangles.push_back(one_dup.triangles[10]);
  one_dup.triangles.push_back(one_dup.triangles[11]);
  gen::Mesh open = gen::box({0, 0, 0}, {1, 1, 1});
  open.triangles.erase(open.triangles.begin() + 10, open.triangles.end());
  const std::vector<std::pair<std::string, std::vector<gen::Mesh>>> models = {
      {"hollow sphere", {hollow_sphere(2)}},
      {"touching plates", gen::stacked_plates(4, 1.0, 0.25)},
      {"touching boxes", {gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {3, 1, 1}, "b")}},
      {"duplicated face", {one_dup}},
      {"duplicated alternating", {gen::duplicated(gen::box({0, 0, 0}, {2, 1, 0.5}), 2, true)}},
      {"open box", {open}},
      {"blob", {gen::blob(2)}},
  };
  for (const auto& [name, meshes] : models) {
    auto w = make_world(meshes);
    for (analysis::ThicknessMethod m : {analysis::ThicknessMethod::ray, analysis::ThicknessMethod::cone}) {
      for (HemisphereSet kind : {HemisphereSet::center, HemisphereSet::median_center, HemisphereSet::polygon}) {
        analysis::ThicknessOptions o;
        o.per = analysis::SampleAt::face;
        o.method = m;
        o.cone_rays = 9;
        o.offset_set = kind;
        o.origin_offsets = analysis::OffsetMode::off;
        const analysis::ThicknessResult off = analysis::compute_thickness(w->accel, o);
        o.origin_offsets = analysis::OffsetMode::on;
        ASSERT_TRUE(analysis::uses_origin_offsets(o));
        const analysis::ThicknessResult on = analysis::compute_thickness(w->accel, o);
        expect_same_thickness(off, on, name + " " + std::string(analysis::method_name(m)) + " " +
                                           std::string(hemisphere_set_name(kind)));
        o.max_distance = 0.3;  // offsets beyond max_distance: NaN either way
        o.origin_offsets = analysis::OffsetMode::off;
        const analysis::ThicknessResult off_short = analysis::compute_thickness(w->accel, o);
        o.origin_offsets = analysis::OffsetMode::on;
        expect_same_thickness(off_short, analysis::compute_thickness(w->accel, o), name + " short");
      }
    }
  }
}

TEST(OriginOffsets, ThicknessRaysActuallyMoveOnAHollowSphere) {
  // Otherwise the identity above would hold trivially.
  auto w = make_world({hollow_sphere(2)});
  const OriginOffsets oo = build_origin_offsets(w->scene, w->accel.wide(), HemisphereSet::center);
  const Geometry& g = w->scene.geometry(0);
  std::size_t moved = 0;
  for (std::uint32_t p = 0; p < g.triangles.size(); ++p) {
    const Tri& t = g.triangles[p];
    const Vec3d c = (g.vertices[t[0]] + g.vertices[t[1]] + g.vertices[t[2]]) * (1.0 / 3.0);
    const Vec3d n = cross(g.vertices[t[1]] - g.vertices[t[0]], g.vertices[t[2]] - g.vertices[t[0]]);
    moved += safe_offset(oo, 0, p, c, n * -1.0) > 0;
  }
  EXPECT_GT(moved * 2, g.triangles.size());
}

}  // namespace
}  // namespace pierce::test
