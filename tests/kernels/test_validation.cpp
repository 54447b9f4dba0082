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
      std::vector<std::vector<Hit>> out;
      EXPECT_TRUE(trace_batch(w->accel, k, assorted_rays(), 0, out));
      for (const auto& h : out) EXPECT_TRUE(h.empty());
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

}  // namespace
}  // namespace pierce::test
