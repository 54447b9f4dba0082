// CSG expressions: parsing and its errors, per-ray evaluation on partitions (touching, nested and
// overlapping solids, spheres and boxes) and point classification.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "csg_test_scenes.h"
#include "pierce/analysis/csg.h"
#include "pierce/error.h"
#include "pierce/solid_reference.h"

namespace pierce::analysis {
namespace {

using csgtest::make_world;
using csgtest::World;

std::string parse_error(std::string_view text, const Scene& scene) {
  try {
    parse_csg(text, scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The expression's intervals along `ray` (traced as a full line, clipped to the ray).
std::vector<CsgInterval> intervals(const World& w, const CsgExpr& e, const Ray& ray) {
  HitIterator it(w.accel, KernelKind::queue, KernelOptions{HitOrder{TieOrder::leave_before_enter}});
  std::vector<Hit> hits;
  collect_hits(it, full_line_ray(ray, w.scene.bounds()), 0, hits);
  PartitionBuilder builder(w.scene.geometries().size());
  RayPartitions parts;
  builder.build(hits, parts);
  clip_partitions(parts, ray.tmin, ray.tmax);
  CsgEvaluator eval(e, w.scene.geometries().size());
  std::vector<CsgInterval> out;
  eval.evaluate(parts, out);
  return out;
}

std::unique_ptr<World> touching_boxes() {
  return make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "b")});
}

TEST(CsgParse, BuildsPostfixProgramWithBoundLeaves) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "b"),
                       gen::box({2, 0, 0}, {3, 1, 1}, "c")});
  const CsgExpr e = parse_csg(" difference( union(a,b) ,c )", w->scene);
  ASSERT_EQ(e.program.size(), 5u);
  EXPECT_EQ(e.program[0].op, CsgOp::leaf);
  EXPECT_EQ(e.program[1].op, CsgOp::leaf);
  EXPECT_EQ(e.program[2].op, CsgOp::union_of);
  EXPECT_EQ(e.program[2].arg, 2u);
  EXPECT_EQ(e.program[3].op, CsgOp::leaf);
  EXPECT_EQ(e.program[4].op, CsgOp::difference_of);
  EXPECT_EQ(e.leaves, (std::vector<std::vector<std::uint32_t>>{{0}, {1}, {2}}));
  EXPECT_EQ(e.solids(), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(CsgParse, QuotedNamesIdsAndSharedNames) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "part one"), gen::box({1, 0, 0}, {2, 1, 1}, "union"),
                       gen::box({2, 0, 0}, {3, 1, 1}, "part one")});
  const CsgExpr e = parse_csg(R"(union("part one", union, #1))", w->scene);
  EXPECT_EQ(e.leaves, (std::vector<std::vector<std::uint32_t>>{{0, 2}, {1}, {1}}));
  EXPECT_EQ(parse_csg("\"union\"", w->scene).leaves, (std::vector<std::vector<std::uint32_t>>{{1}}));
}

TEST(CsgParse, SyntaxErrorsGiveColumnAndCaret) {
  auto w = touching_boxes();
  const std::string missing_paren = parse_error("union(a, b", w->scene);
  EXPECT_NE(missing_paren.find("column 11"), std::string::npos) << missing_paren;
  EXPECT_NE(missing_paren.find("expected ',' or ')'"), std::string::npos) << missing_paren;
  EXPECT_NE(missing_paren.find("\n  union(a, b\n            ^"), std::string::npos) << missing_paren;

  const std::string unknown_op = parse_error("union(a, merge(a, b))", w->scene);
  EXPECT_NE(unknown_op.find("column 10"), std::string::npos) << unknown_op;
  EXPECT_NE(unknown_op.find("unknown operation 'merge'"), std::string::npos) << unknown_op;

  EXPECT_NE(parse_error("", w->scene).find("empty"), std::string::npos);
  EXPECT_NE(parse_error("union(a)", w->scene).find("at least two operands"), std::string::npos);
  EXPECT_NE(parse_error("union(a,)", w->scene).find("column 9"), std::string::npos);
  EXPECT_NE(parse_error("a b", w->scene).find("unexpected 'b'"), std::string::npos);
  EXPECT_NE(parse_error("union(a, \"b)", w->scene).find("not closed"), std::string::npos);
  std::string deep;
  for (int i = 0; i < 300; ++i) deep += "union(a,";
  EXPECT_NE(parse_error(deep, w->scene).find("nested more than"), std::string::npos);
}

TEST(CsgParse, UnknownNamesAreAllListedWithTheKnownOnes) {
  auto w = touching_boxes();
  const std::string msg = parse_error("union(a, x, difference(y, b), x, #7)", w->scene);
  EXPECT_NE(msg.find("unknown solid names 'x', 'y', '#7'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("known: a, b"), std::string::npos) << msg;
  EXPECT_EQ(parse_error("union(a, b)", w->scene), "");
}

// One syntax for naming solids everywhere (solid_reference.h): name, #N or N; a name wins over
// the id reading, except an unquoted #N in an expression.
TEST(SolidReference, NamesHashIdsAndBareIds) {
  EXPECT_EQ(parse_solid_id("#12"), std::optional<std::uint32_t>(12));
  EXPECT_EQ(parse_solid_id("12"), std::optional<std::uint32_t>(12));
  EXPECT_EQ(parse_solid_id("#"), std::nullopt);
  EXPECT_EQ(parse_solid_id("-1"), std::nullopt);
  EXPECT_EQ(parse_solid_id("1a"), std::nullopt);
  EXPECT_EQ(parse_solid_id("1234567890"), std::nullopt);

  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "2"),
                       gen::box({2, 0, 0}, {3, 1, 1}, "a"), gen::box({3, 0, 0}, {4, 1, 1}, "#0")});
  using Ids = std::vector<std::uint32_t>;
  EXPECT_EQ(find_solids(w->scene, "a"), (Ids{0, 2}));
  EXPECT_EQ(find_solids(w->scene, "#1"), (Ids{1}));
  EXPECT_EQ(find_solids(w->scene, "1"), (Ids{1}));
  EXPECT_EQ(find_solids(w->scene, "2"), (Ids{1}));   // the name "2", not id 2
  EXPECT_EQ(find_solids(w->scene, "#0"), (Ids{3}));  // the name "#0"
  EXPECT_EQ(find_solids(w->scene, "4"), Ids{});
  EXPECT_EQ(find_solids(w->scene, "b"), Ids{});

  // In an expression: a bare id works as in --solid; an unquoted #N stays the id.
  EXPECT_EQ(parse_csg("union(3, \"#0\", #0, 2)", w->scene).leaves,
            (std::vector<Ids>{{3}, {3}, {0}, {1}}));
  EXPECT_NE(parse_error("union(a, 9)", w->scene).find("unknown solid name '9'"), std::string::npos);
}

TEST(CsgEvaluate, TouchingBoxesUnionIsOneSeamlessInterval) {
  auto w = touching_boxes();
  const Ray ray{{-5, 0.5, 0.5}, {1, 0, 0}};
  const auto u = intervals(*w, parse_csg("union(a, b)", w->scene), ray);
  ASSERT_EQ(u.size(), 1u);
  EXPECT_DOUBLE_EQ(u[0].t_in, 5.0);
  EXPECT_DOUBLE_EQ(u[0].t_out, 7.0);
  EXPECT_EQ(u[0].in_hit.geom, 0u);
  EXPECT_EQ(u[0].out_hit.geom, 1u);
  EXPECT_TRUE(intervals(*w, parse_csg("intersection(a, b)", w->scene), ray).empty());
  const auto d = intervals(*w, parse_csg("difference(b, a)", w->scene), ray);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_DOUBLE_EQ(d[0].t_in, 6.0);
  EXPECT_DOUBLE_EQ(d[0].t_out, 7.0);
}

using csgtest::rotated;

TEST(CsgEvaluate, SnappingRemovesFloatSliversBetweenCubesWithDifferentDiagonals) {
  // cube_grid alternates the faces' diagonals; rotated, a shared face is crossed at two t values
  // that differ by rounding. Unsnapped, some rays see a sliver of overlap or gap; snapped, none does.
  std::vector<gen::Mesh> cubes = gen::cube_grid(3);
  for (gen::Mesh& m : cubes)
    for (Vec3d& v : m.vertices) v = rotated(v);
  auto w = make_world(cubes);
  HitIterator it(w->accel, KernelKind::queue, KernelOptions{HitOrder{TieOrder::leave_before_enter}});
  PartitionBuilder builder(w->scene.geometries().size());
  std::string all = "union(";
  for (std::uint32_t g = 0; g < 27; ++g) all += (g ? ", #" : "#") + std::to_string(g);
  const CsgExpr e = parse_csg(all + ")", w->scene);
  CsgEvaluator eval(e, 27);
  std::size_t slivers = 0;
  for (int i = 0; i < 2700; ++i) {
    const int axis = i % 3, u = (axis + 1) % 3, v = (axis + 2) % 3, k = i / 3;
    Vec3d org, dir;
    dir[std::size_t(axis)] = 1;
    org[std::size_t(axis)] = -1;
    org[std::size_t(u)] = 0.0015 + 0.1 * (k % 30);
    org[std::size_t(v)] = 0.0421 + 0.0997 * (k / 30);
    const Ray ray{rotated(org), rotated(dir)};
    std::vector<Hit> hits;
    collect_hits(it, ray, 0, hits);
    RayPartitions parts;
    builder.build(hits, parts);
    for (std::size_t k = 0; k < parts.partitions.size(); ++k) {
      const Partition& p = parts.partitions[k];
      slivers += p.count > 1 || (k > 0 && parts.partitions[k - 1].t_out != p.t_in);
    }
    snap_partitions(parts, 1e-6);
    ASSERT_EQ(parts.partitions.size(), 3u) << i;
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(parts.partitions[k].count, 1u);
      EXPECT_NEAR(parts.partitions[k].t_out - parts.partitions[k].t_in, 1.0, 1e-5);
      if (k > 0) {
        EXPECT_EQ(parts.partitions[k - 1].t_out, parts.partitions[k].t_in);
      }
    }
    std::vector<CsgInterval> out;
    eval.evaluate(parts, out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(out[0].t_out - out[0].t_in, 3.0, 1e-5);
  }
  EXPECT_GT(slivers, 0u);  // the case the snapping is for does occur
}

TEST(CsgEvaluate, NestedBoxesDifferenceHasTwoIntervals) {
  auto w = make_world({gen::box({0, 0, 0}, {3, 3, 3}, "outer"), gen::box({1, 1, 1}, {2, 2, 2}, "inner")});
  const Ray ray{{1.5, 1.5, -1}, {0, 0, 1}};
  const auto d = intervals(*w, parse_csg("difference(outer, inner)", w->scene), ray);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d[0].t_in, 1.0);
  EXPECT_DOUBLE_EQ(d[0].t_out, 2.0);
  EXPECT_DOUBLE_EQ(d[1].t_in, 3.0);
  EXPECT_DOUBLE_EQ(d[1].t_out, 4.0);
  EXPECT_EQ(d[0].out_hit.geom, 1u);  // the hole's surface bounds the result
  const auto i = intervals(*w, parse_csg("intersection(outer, inner)", w->scene), ray);
  ASSERT_EQ(i.size(), 1u);
  EXPECT_DOUBLE_EQ(i[0].t_in, 2.0);
  EXPECT_DOUBLE_EQ(i[0].t_out, 3.0);
  const auto u = intervals(*w, parse_csg("union(outer, inner)", w->scene), ray);
  ASSERT_EQ(u.size(), 1u);
  EXPECT_DOUBLE_EQ(u[0].t_out - u[0].t_in, 3.0);
}

TEST(CsgEvaluate, PlateStackUnionMergesAllTwentyPlates) {
  auto w = make_world(gen::stacked_plates(20, 1.0, 0.1));
  std::string expr = "union(";
  for (int i = 0; i < 20; ++i) expr += (i ? ", plate" : "plate") + std::to_string(i);
  expr += ")";
  const Ray ray{{0.3, 0.6, -1}, {0, 0, 1}};
  const auto u = intervals(*w, parse_csg(expr, w->scene), ray);
  ASSERT_EQ(u.size(), 1u);
  EXPECT_NEAR(u[0].t_in, 1.0, 1e-9);
  EXPECT_NEAR(u[0].t_out, 3.0, 1e-6);
  // Every second plate: ten separate intervals.
  std::string odd = "union(";
  for (int i = 1; i < 20; i += 2) odd += (i > 1 ? ", plate" : "plate") + std::to_string(i);
  odd += ")";
  EXPECT_EQ(intervals(*w, parse_csg(odd, w->scene), ray).size(), 10u);
}

TEST(CsgEvaluate, SphereMinusBoxAgreesWithAnalyticChords) {
  // Sphere of radius 1 at the origin minus the box z >= 0: along z, the chord below the plane.
  auto w = make_world({csgtest::sphere(1.0, {0, 0, 0}, "ball", 4), gen::box({-2, -2, 0}, {2, 2, 2}, "lid")});
  const CsgExpr e = parse_csg("difference(ball, lid)", w->scene);
  for (double x : {0.0, 0.3, -0.55, 0.7}) {
    const Ray ray{{x, 0.1, -3}, {0, 0, 1}};
    const auto d = intervals(*w, e, ray);
    ASSERT_EQ(d.size(), 1u) << x;
    const double half_chord = std::sqrt(1.0 - x * x - 0.01);
    EXPECT_NEAR(d[0].t_in, 3.0 - half_chord, 0.01) << x;  // tessellation error of level 4
    EXPECT_NEAR(d[0].t_out, 3.0, 1e-6) << x;  // float hit arithmetic
    EXPECT_EQ(d[0].out_hit.geom, 1u);
  }
}

TEST(CsgEvaluate, ContainsIsTheBooleanFunctionOfTheSolidSet) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0, 0, 0}, {1, 1, 1}, "b"),
                       gen::box({0, 0, 0}, {1, 1, 1}, "c")});
  const CsgExpr e = parse_csg("union(intersection(a, b), difference(c, a, b))", w->scene);
  CsgEvaluator ev(e, 3);
  const std::vector<std::vector<std::uint32_t>> sets = {{}, {0}, {1}, {2}, {0, 1}, {0, 2}, {1, 2}, {0, 1, 2}};
  for (const auto& s : sets) {
    auto has = [&](std::uint32_t g) { return std::find(s.begin(), s.end(), g) != s.end(); };
    const bool expected = (has(0) && has(1)) || (has(2) && !has(0) && !has(1));
    EXPECT_EQ(ev.contains(s), expected) << s.size();
  }
  EXPECT_EQ(ev.evaluations, sets.size());
}

TEST(CsgClassify, PointsInsideOutsideOnForBoxesAndDifference) {
  auto w = touching_boxes();
  const CsgExpr a = parse_csg("a", w->scene);
  PointClassifier ca(w->accel, a);
  EXPECT_EQ(ca.classify({0.5, 0.5, 0.5}), PointClass::inside);
  EXPECT_EQ(ca.classify({1.5, 0.5, 0.5}), PointClass::outside);
  EXPECT_EQ(ca.classify({-0.5, 0.5, 0.5}), PointClass::outside);
  EXPECT_EQ(ca.classify({1.0, 0.5, 0.5}), PointClass::on);  // shared face
  EXPECT_EQ(ca.classify({0.0, 0.0, 0.0}), PointClass::on);  // corner
  EXPECT_EQ(ca.classify({0.5, 1.0, 0.25}), PointClass::on);

  // Under union the shared face is interior: no seam.
  const CsgExpr u = parse_csg("union(a, b)", w->scene);
  PointClassifier cu(w->accel, u);
  EXPECT_EQ(cu.classify({1.0, 0.5, 0.5}), PointClass::inside);
  EXPECT_EQ(cu.classify({2.0, 0.5, 0.5}), PointClass::on);

  auto n = make_world({gen::box({0, 0, 0}, {3, 3, 3}, "outer"), gen::box({1, 1, 1}, {2, 2, 2}, "inner")});
  const CsgExpr d = parse_csg("difference(outer, inner)", n->scene);
  PointClassifier cd(n->accel, d);
  EXPECT_EQ(cd.classify({1.5, 1.5, 1.5}), PointClass::outside);  // in the hole
  EXPECT_EQ(cd.classify({0.5, 1.5, 1.5}), PointClass::inside);
  EXPECT_EQ(cd.classify({1.0, 1.5, 1.5}), PointClass::on);  // the hole's wall
  EXPECT_EQ(cd.classify({4.0, 1.5, 1.5}), PointClass::outside);
}

TEST(CsgClassify, SpherePointsMatchDistanceFromCentre) {
  auto w = make_world({csgtest::sphere(1.0, {0, 0, 0}, "ball", 3)});
  const CsgExpr e = parse_csg("ball", w->scene);
  PointClassifier c(w->accel, e);
  // The icosphere lies between radius cos(max facet angle) ~0.99 and 1.
  for (int i = 0; i < 50; ++i) {
    const double r = 0.1 + 1.8 * i / 49.0;
    if (std::abs(r - 1.0) < 0.03) continue;
    const Vec3d p{r * 0.48, r * 0.6, r * 0.64};
    EXPECT_EQ(c.classify(p), r < 1.0 ? PointClass::inside : PointClass::outside) << r;
  }
  const auto& v = w->scene.geometry(0).vertices[5];
  EXPECT_EQ(c.classify(v), PointClass::on);
}

TEST(CsgObliquity, HeadOnIsZeroAndGrazingApproachesNinety) {
  Hit h;
  h.geom = 0;
  h.ng = {0, 0, 2};
  EXPECT_DOUBLE_EQ(obliquity_deg({0, 0, -3}, h), 0.0);
  EXPECT_NEAR(obliquity_deg({1, 0, 1}, h), 45.0, 1e-12);
  EXPECT_NEAR(obliquity_deg({1, 0, 0}, h), 90.0, 1e-12);
  EXPECT_TRUE(std::isnan(obliquity_deg({1, 0, 0}, Hit{})));
}

}  // namespace
}  // namespace pierce::analysis
