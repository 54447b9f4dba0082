// Bad input: scenes reject non-finite and out-of-float-range coordinates and bad indices with a
// message naming the element; empty scenes and bad rays give no hits and no crash, in every kernel.
#include <cmath>
#include <limits>

#include "pierce/error.h"
#include "test_util.h"

namespace pierce::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The InputError's message, or "" if add_mesh did not throw one.
std::string add_error(Scene& s, std::vector<Vec3d> v, std::vector<Tri> t) {
  try {
    s.add_mesh(std::move(v), std::move(t), "part7", "model.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::vector<Vec3d> kQuad{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<Tri> kQuadTris{{0, 1, 2}, {0, 2, 3}};

TEST(Validation, BadCoordinatesNameTheVertex) {
  const double bad[] = {kNaN, kInf, -kInf, 1e39, -3.5e38};
  for (double b : bad)
    for (int axis = 0; axis < 3; ++axis) {
      Scene s;
      auto v = kQuad;
      v[2][std::size_t(axis)] = b;
      const std::string msg = add_error(s, v, kQuadTris);
      ASSERT_FALSE(msg.empty()) << "accepted coordinate " << b;
      EXPECT_NE(msg.find("vertex 2"), std::string::npos) << msg;
      EXPECT_NE(msg.find("model.obj"), std::string::npos) << msg;
      EXPECT_NE(msg.find("part7"), std::string::npos) << msg;
      EXPECT_TRUE(s.geometries().empty()) << "a rejected mesh must not be added";
      EXPECT_TRUE(s.bounds().empty());
    }
  // Largest float is fine.
  Scene s;
  auto v = kQuad;
  v[1].x = double(std::numeric_limits<float>::max());
  EXPECT_EQ(add_error(s, v, kQuadTris), "");
}

TEST(Validation, BadIndexNamesTheTriangle) {
  Scene s;
  std::vector<Tri> t = kQuadTris;
  t.push_back({0, 1, 2});
  t.push_back({3, 4, 0});  // triangle 3 references vertex 4 of 4
  const std::string msg = add_error(s, kQuad, t);
  ASSERT_FALSE(msg.empty());
  EXPECT_NE(msg.find("triangle 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("4"), std::string::npos) << msg;
  EXPECT_TRUE(s.geometries().empty());
  Scene s2;
  const std::string huge = add_error(s2, kQuad, {{0, 1, 0xFFFFFFFFu}});
  EXPECT_NE(huge.find("triangle 0"), std::string::npos) << huge;
  // A good mesh after a rejected one gets id 0.
  EXPECT_EQ(s2.add_mesh(kQuad, kQuadTris), 0u);
}

std::vector<Ray> assorted_rays() {
  return {{{0.5, 0.5, -1}, {0, 0, 1}}, {{-1, -1, -1}, {1, 1, 1}}, {{0.5, 0.5, 0}, {0, 0, -1}}, {{3, 3, 3}, {-1, -2, -3}}};
}

TEST(Validation, EmptyScenesGiveNoHits) {
  std::vector<std::vector<gen::Mesh>> scenes;
  scenes.push_back({});                                                   // no geometry at all
  scenes.push_back({gen::Mesh{"empty", {}, {}}});                          // a geometry without triangles
  scenes.push_back({gen::Mesh{"points", kQuad, {{0, 0, 0}, {1, 1, 2}}}});   // only degenerate triangles
  for (const auto& meshes : scenes) {
    const auto w = make_world(meshes);
    EXPECT_TRUE(w->accel.bvh().empty());
    for (KernelKind k : kAllKernels) {
      HitIterator it(w->accel, k);
      for (const Ray& r : assorted_rays()) {
        EXPECT_TRUE(kernel_hits(it, r).empty()) << kernel_name(k);
        EXPECT_TRUE(kernel_hits(it, r, 3).empty()) << kernel_name(k);
      }
      HitBatch out;
      const std::vector<Ray> rays = assorted_rays();
      EXPECT_TRUE(trace_batch(w->accel, k, rays, 0, out));
      EXPECT_EQ(out.rays(), rays.size());
      EXPECT_TRUE(out.hits.empty());
    }
  }
}

TEST(Validation, BadRaysGiveNoHits) {
  const auto w = make_world(gen::stacked_plates(3));
  std::vector<Ray> bad;
  const Vec3d org{0.5, 0.5, -1}, dir{0, 0, 1};
  for (int axis = 0; axis < 3; ++axis)
    for (double v : {kNaN, kInf, -kInf}) {
      Ray r{org, dir};
      r.org[std::size_t(axis)] = v;
      bad.push_back(r);
      r = {org, dir};
      r.dir[std::size_t(axis)] = v;
      bad.push_back(r);
    }
  bad.push_back({org, {0, 0, 0}});           // zero direction
  bad.push_back({org, {0, 0, -0.0}});
  bad.push_back({org, dir, kNaN, kInf});     // NaN segment ends
  bad.push_back({org, dir, 0, kNaN});
  bad.push_back({org, dir, 5, 1});           // empty segment
  bad.push_back({org, dir, kInf, kInf});
  bad.push_back({org, dir, -kInf, -kInf});
  // Sanity: the same scene does have hits for the good ray.
  for (KernelKind k : kAllKernels) {
    HitIterator it(w->accel, k);
    const std::size_t good = kernel_hits(it, {org, dir}).size();
    EXPECT_GT(good, 0u) << kernel_name(k);
    if (is_exact(k)) {
      EXPECT_EQ(good, 6u) << kernel_name(k);
    }
    for (const Ray& r : bad) {
      EXPECT_TRUE(kernel_hits(it, r).empty()) << kernel_name(k) << " " << str(r);
      EXPECT_TRUE(kernel_hits(it, r, 2).empty()) << kernel_name(k) << " " << str(r);
    }
  }
  for (const Ray& r : bad) EXPECT_TRUE(reference_hits(w->scene, r, {}).empty()) << "reference " << str(r);
}

// Found by the kernel fuzzer: triangles near the float range overflow the SAH builder's centroids
// and extents to infinity; binning them converted NaN to int (undefined behaviour, reported by
// UBSan in the sanitizer build). The BVH must still be built and the small triangles found.
TEST(Validation, TrianglesNearTheFloatRangeBuildAndTrace) {
  gen::Mesh m{"huge", {}, {}};
  auto add_tri = [&](Vec3d a, Vec3d b, Vec3d c) {
    const auto i = std::uint32_t(m.vertices.size());
    m.vertices.insert(m.vertices.end(), {a, b, c});
    m.triangles.push_back({i, i + 1, i + 2});
  };
  for (int i = 0; i < 8; ++i) {
    const double s = i % 2 ? -1.0 : 1.0, z = 100.0 + i;  // box centres overflow to +-inf in float
    add_tri({s * 3.0e38, 0, z}, {s * 3.3e38, 0, z}, {s * 3.1e38, 1e38, z});
  }
  for (int i = 0; i < 8; ++i) add_tri({0, 0, double(i)}, {1, 0, double(i)}, {0, 1, double(i)});
  const auto w = make_world({m});
  const Ray ray{{0.25, 0.25, -1}, {0, 0, 1}};
  std::vector<KernelKind> kinds(std::begin(kDoubleKernels), std::end(kDoubleKernels));
  for (KernelKind k : kAllKernels)
    if (!uses_embree(k)) kinds.push_back(k);
  for (KernelKind k : kinds) {
    HitIterator it(w->accel, k);
    const auto hits = kernel_hits(it, ray);
    ASSERT_EQ(hits.size(), 8u) << kernel_name(k);
    for (std::size_t i = 0; i < hits.size(); ++i) {
      EXPECT_EQ(hits[i].prim, 8 + i) << kernel_name(k);
      EXPECT_EQ(hits[i].t, 1.0 + double(i)) << kernel_name(k);
    }
  }
}

// Found by the kernel fuzzer: Embree drops primitives beyond its FLT_LARGE (1.844e18), so its
// kernels refuse such scenes with a clear error instead of missing hits; Pierce's kernels trace them.
TEST(Validation, EmbreeKernelsRefuseScenesBeyondEmbreesRange) {
  for (double far : {1e18, 1e30, 3e38}) {
    const auto w = make_world({gen::Mesh{"far", {{-far, -far, 1}, {far, -far, 1}, {0, far, 1}}, {{0, 1, 2}}}});
    const Ray ray{{0, 0, 0}, {0, 0, 1}};
    for (KernelKind k : kAllKernels) {
      if (uses_embree(k)) {
        EXPECT_NE(unsupported_reason(w->accel, k), "") << kernel_name(k);
        try {
          HitIterator it(w->accel, k);
          ADD_FAILURE() << kernel_name(k) << " accepted a scene at " << far;
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("Embree"), std::string::npos) << e.what();
        }
      } else {
        // Float kernels: beyond their exact range (docs/EXACTNESS.md), only sane output.
        HitIterator it(w->accel, k);
        for (const Hit& h : kernel_hits(it, ray)) EXPECT_TRUE(std::isfinite(h.t) && h.t >= 0) << kernel_name(k);
      }
    }
    for (KernelKind k : kDoubleKernels) {  // inside the double kernels' range: exact
      HitIterator it(w->accel, k);
      const auto hits = kernel_hits(it, ray);
      ASSERT_EQ(hits.size(), 1u) << kernel_name(k) << " at " << far;
      EXPECT_EQ(hits[0].t, 1.0);
    }
  }
  // Just inside the range every kernel works.
  const double near = 1e17;
  const auto w = make_world({gen::Mesh{"near", {{-near, -near, 1}, {near, -near, 1}, {0, near, 1}}, {{0, 1, 2}}}});
  for (KernelKind k : kAllKernels) {
    EXPECT_EQ(unsupported_reason(w->accel, k), "") << kernel_name(k);
    HitIterator it(w->accel, k);
    EXPECT_EQ(kernel_hits(it, {{0, 0, 0}, {0, 0, 1}}).size(), 1u) << kernel_name(k);
  }
}

}  // namespace
}  // namespace pierce::test
