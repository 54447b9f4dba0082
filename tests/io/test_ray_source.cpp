// Ray sources: CSV files and the grid/random generators, including their error messages.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh_writers.h"
#include "pierce/error.h"
#include "pierce/generators.h"
#include "pierce/io/ray_source.h"
#include "pierce/kernel.h"
#include "temp_dir.h"

namespace pierce::test {
namespace {

using RaySource = TempDirTest;

Scene plates_scene() { return gen::to_scene(gen::stacked_plates(10)); }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST_F(RaySource, CsvWithHeaderCommentsAndOptionalRange) {
  write_text(file("rays.csv"),
             "ox,oy,oz,dx,dy,dz,tmin,tmax\n"
             "# a comment\n"
             "\n"
             "0.1, 0.2, -1, 0, 0, 1\n"
             "1e-3,-2.5,3,1,1,1,0.5,inf\r\n"
             "0,0,0,0,0,-2,-1,7.25\n");
  const auto rays = load_rays(file("rays.csv"), Scene{});
  ASSERT_EQ(rays.size(), 3u);
  EXPECT_EQ(rays[0].org, (Vec3d{0.1, 0.2, -1}));
  EXPECT_EQ(rays[0].dir, (Vec3d{0, 0, 1}));
  EXPECT_EQ(rays[0].tmin, 0.0);
  EXPECT_EQ(rays[0].tmax, std::numeric_limits<double>::infinity());
  EXPECT_EQ(rays[1].org, (Vec3d{1e-3, -2.5, 3}));
  EXPECT_EQ(rays[1].tmin, 0.5);
  EXPECT_EQ(rays[1].tmax, std::numeric_limits<double>::infinity());
  EXPECT_EQ(rays[2].dir, (Vec3d{0, 0, -2}));
  EXPECT_EQ(rays[2].tmin, -1.0);
  EXPECT_EQ(rays[2].tmax, 7.25);
}

TEST_F(RaySource, CsvWithoutHeader) {
  write_text(file("r.csv"), "1,2,3,4,5,6\n");
  const auto rays = load_rays(file("r.csv"), Scene{});
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_EQ(rays[0].dir, (Vec3d{4, 5, 6}));
}

TEST_F(RaySource, CsvErrorsNameFileAndLine) {
  struct Case {
    const char* content;
    const char* where;
    const char* what;
  };
  const Case cases[] = {
      {"0,0,0,0,0,1\n0,0,0,0,1\n", ":2:", "expected 6 or 8"},
      {"ox,oy,oz,dx,dy,dz\n0,0,0,0,0,1,0\n", ":2:", "found 7"},
      {"0,0,0,0,0,1\n\n# c\n0,0,zero,0,0,1\n", ":4:", "bad number for oz"},
      {"1.0x,0,0,0,0,1\n", ":1:", "bad number for ox"},  // a typo is not a header
      {"0,0,0,0,0,0\n", ":1:", "direction is zero"},
      {"0,0,0,1e-60,0,0\n", ":1:", "direction is zero"},
      {"0,nan,0,0,0,1\n", ":1:", "oy is NaN"},
      {"0,0,0,0,0,inf\n", ":1:", "dz is infinite"},
      {"0,0,0,0,0,1,2,1\n", ":1:", "tmin is greater than tmax"},
      {"0,0,0,0,0,1,-inf,1\n", ":1:", "tmin is infinite"},
      {"0,0,0,0,0,1,0,\n", ":1:", "bad number for tmax"},
      {"ox,oy,oz,dx,dy,dz\n", "", "no rays"},
      {"", "", "no rays"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const std::string path = file("bad" + std::to_string(i++) + ".csv");
    write_text(path, c.content);
    const std::string msg = error_of([&] { load_rays(path, Scene{}); });
    EXPECT_NE(msg.find(path + c.where), std::string::npos) << c.content << " -> " << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << c.content << " -> " << msg;
  }
  const std::string missing = file("missing.csv");
  EXPECT_NE(error_of([&] { load_rays(missing, Scene{}); }).find(missing + ": cannot open"), std::string::npos);
}

TEST(RayGrid, CellCentresAlongEachAxis) {
  const Scene scene = plates_scene();  // bounds [0,1] x [0,1] x [0,1]
  const BBoxd b = scene.bounds();
  for (int axis = 0; axis < 3; ++axis)
    for (const char* dir : {"+", "-"}) {
      const std::string spec = std::string("grid:axis=") + char('x' + axis) + ",n=5,dir=" + dir;
      const auto rays = load_rays(spec, scene);
      ASSERT_EQ(rays.size(), 25u) << spec;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const double sign = dir[0] == '+' ? 1.0 : -1.0;
      for (std::size_t j = 0; j < 5; ++j)
        for (std::size_t i = 0; i < 5; ++i) {
          const Ray& r = rays[j * 5 + i];
          Vec3d want_dir;
          want_dir[std::size_t(axis)] = sign;
          EXPECT_EQ(r.dir, want_dir) << spec;
          EXPECT_NEAR(r.org[std::size_t(u)], b.lo[std::size_t(u)] + (i + 0.5) / 5 * b.extent()[std::size_t(u)], 1e-15) << spec;
          EXPECT_NEAR(r.org[std::size_t(v)], b.lo[std::size_t(v)] + (j + 0.5) / 5 * b.extent()[std::size_t(v)], 1e-15) << spec;
          // Starts outside the bounds, on the side it looks in from.
          if (sign > 0) EXPECT_LT(r.org[std::size_t(axis)], b.lo[std::size_t(axis)]) << spec;
          else EXPECT_GT(r.org[std::size_t(axis)], b.hi[std::size_t(axis)]) << spec;
          EXPECT_EQ(r.tmin, 0.0);
        }
    }
  EXPECT_EQ(load_rays("grid:n=3", scene).size(), 9u);  // axis defaults to z
  EXPECT_EQ(load_rays("grid:n=3", scene)[0].dir, (Vec3d{0, 0, 1}));
}

TEST(RayGrid, EveryRayCrossesEveryPlateTwice) {
  const Scene scene = plates_scene();
  const Accel accel(scene);
  const auto rays = load_rays("grid:axis=z,n=16", scene);
  HitBatch hits;
  ASSERT_TRUE(trace_batch(accel, KernelKind::restart, rays, 0, hits));
  for (std::size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(hits.of(i).size(), 2 * scene.geometries().size()) << "ray " << i;
}

TEST(RayRandom, DeterministicOnTheSphereAndAimedInside) {
  gen::Mesh m = gen::translated(gen::scaled(gen::blob(1), 3.0), {10, -4, 2});
  const Scene scene = gen::to_scene({m});
  const auto a = load_rays("random:n=500,seed=5", scene);
  const auto b = load_rays("random:seed=5,n=500", scene);
  const auto c = load_rays("random:n=500,seed=6", scene);
  ASSERT_EQ(a.size(), 500u);
  std::size_t same_as_c = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].org, b[i].org);
    EXPECT_EQ(a[i].dir, b[i].dir);
    same_as_c += a[i].org == c[i].org;
  }
  EXPECT_EQ(same_as_c, 0u);
  EXPECT_EQ(load_rays("random:n=10", scene)[3].org, load_rays("random:n=10,seed=1", scene)[3].org);

  const BBoxd box = scene.bounds();
  const double radius = 0.75 * length(box.extent());
  for (const Ray& r : a) {
    EXPECT_NEAR(length(r.org - box.center()), radius, 1e-12 * radius);
    EXPECT_NEAR(length(r.dir), 1.0, 1e-12);
    // The ray passes through the bounds (slab test), coming from outside.
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < 3; ++k) {
      const double ta = (box.lo[k] - r.org[k]) / r.dir[k], tb = (box.hi[k] - r.org[k]) / r.dir[k];
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    EXPECT_LE(t0, t1);
    EXPECT_GT(t0, 0.0);
  }
}

TEST(RaySpec, ErrorsNameSpecAndProblem) {
  const Scene scene = plates_scene();
  const std::pair<const char*, const char*> cases[] = {
      {"grid:axis=z", "missing n"},
      {"grid", "missing n"},
      {"grid:n=0", "n must be positive"},
      {"grid:n=-4", "n must be positive"},
      {"grid:n=abc", "n must be an integer"},
      {"grid:n=4.5", "n must be an integer"},
      {"grid:n=1000000", "too large"},
      {"grid:n=4,axis=w", "axis must be x, y or z"},
      {"grid:n=4,dir=up", "dir must be + or -"},
      {"grid:n=4,size=2", "unknown key 'size'"},
      {"grid:n=4,n=5", "given twice"},
      {"grid:n=4,", "empty parameter"},
      {"grid:n", "not key=value"},
      {"grid:n=", "no value for n"},
      {"random:seed=1", "missing n"},
      {"random:n=10,seed=x", "seed must be"},
      {"random:n=10,axis=z", "unknown key 'axis'"},
      {"sphere:n=10", "unknown ray generator 'sphere'"},
  };
  for (const auto& [spec, what] : cases) {
    const std::string msg = error_of([&] { load_rays(spec, scene); });
    EXPECT_NE(msg.find(std::string("'") + spec + "'"), std::string::npos) << spec << " -> " << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << spec << " -> " << msg;
  }
  for (const char* spec : {"grid:n=4", "random:n=4"})
    EXPECT_NE(error_of([&] { load_rays(spec, Scene{}); }).find("scene is empty"), std::string::npos) << spec;
}

}  // namespace
}  // namespace pierce::test
