// Scene-driven effects: only the requested effects run, rays stop once every requested effect is
// settled, and the results match closed-form answers (Beer-Lambert on a plate stack, alpha
// compositing, energy budgets, line-of-sight thickness).
#include <gtest/gtest.h>

#include <cmath>

#include "csg_test_scenes.h"
#include "effect_scene.h"
#include "pierce/analysis/effects.h"
#include "pierce/error.h"

namespace pierce::analysis {
namespace {

using csgtest::make_world;
using csgtest::World;
// The scene-file format of `pierce run` is the CLI's (apps/pierce/effect_scene.h).
using cli::bind_effect_scene;
using cli::camera_rays;
using cli::CameraSpec;
using cli::EffectSceneSpec;
using cli::make_scene_rays;
using cli::parse_effect_scene;
using cli::SceneRays;

constexpr int kPlates = 20;
constexpr double kPlateT = 0.1;
constexpr double kMuLead = 5.0, kMuFoam = 0.5;

// 20 plates of 1 x 1 x 0.1, alternating lead (even) and foam (odd).
std::unique_ptr<World> plate_stack() { return make_world(gen::stacked_plates(kPlates, 1.0, kPlateT)); }

EffectsConfig plate_config(std::initializer_list<Effect> effects) {
  EffectsConfig cfg;
  for (Effect e : effects) cfg.enable(e);
  Material lead{"lead", 11.3, kMuLead, 0.5, {0.5, 0.5, 0.6}, 10.0};
  Material foam{"foam", 0.1, kMuFoam, 0.5, {1.0, 0.9, 0.8}, 1.0};
  cfg.materials = {lead, foam};
  for (int i = 0; i < kPlates; ++i) cfg.solid_material.push_back(i % 2);
  return cfg;
}

std::vector<Ray> rays_along_z(int n) {
  std::vector<Ray> rays;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) rays.push_back(Ray{{(i + 0.5) / n, (j + 0.5) / n, -1}, {0, 0, 1}});
  return rays;
}

double analytic_transmission(const Ray& r) {
  return csgtest::plate_stack_transmission(r, kPlates, kPlateT, kMuLead, kMuFoam);
}

TEST(Effects, XrayOnPlateStackMatchesBeerLambertAndStopsEarly) {
  auto w = plate_stack();
  // An oblique orthographic camera: rays cross different numbers of plates, some leave through
  // the sides, some miss.
  CameraSpec cam;
  cam.center = {0.5, 0.5, -1};
  cam.direction = {0.35, 0.15, 1};
  cam.up = {0, 1, 0};
  cam.width = cam.height = 1.6;
  cam.pixels_x = cam.pixels_y = 24;
  const std::vector<Ray> rays = camera_rays(cam);
  EffectsConfig cfg = plate_config({Effect::xray});
  cfg.xray_threshold = 0.02;  // reached by the rays that cross most of the stack
  cfg.audit = true;
  const EffectsResult r = run_effects(w->accel, rays, cfg);
  ASSERT_TRUE(r.completed);
  std::size_t settled = 0, open = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double exact = analytic_transmission(rays[i]);
    if (exact >= cfg.xray_threshold * 1.0001) {
      EXPECT_NEAR(r.transmission[i], exact, 2e-5 * exact) << i;  // float hit distances: ~1e-7 relative each
      EXPECT_EQ(r.xray_settled[i], 0) << i;
      ++open;
    } else if (exact < cfg.xray_threshold * 0.9999) {
      EXPECT_EQ(r.xray_settled[i], 1) << i;
      EXPECT_LT(r.transmission[i], cfg.xray_threshold) << i;
      EXPECT_GE(r.transmission[i], exact * (1 - 2e-5)) << i;  // stopped before the rest attenuated it
      ++settled;
    }
  }
  EXPECT_GT(settled, 50u);  // the scene exercises both cases
  EXPECT_GT(open, 50u);
  EXPECT_LT(r.stats.hits_traversed, r.stats.hits_existing);
  EXPECT_GT(r.stats.rays_settled_early, 0u);
  EXPECT_GT(r.stats.partition_groups, 0u);
  EXPECT_EQ(r.stats.updates[std::size_t(Effect::transparency)], 0u);
  EXPECT_EQ(r.stats.updates[std::size_t(Effect::classification)], 0u);
}

TEST(Effects, XrayStraightThroughStopsAtTheThresholdPlate) {
  auto w = plate_stack();
  EffectsConfig cfg = plate_config({Effect::xray});
  cfg.materials[1].mu = kMuLead;  // all lead: 0.5 optical depth per plate
  cfg.audit = true;
  const std::vector<Ray> rays = rays_along_z(8);
  const EffectsResult r = run_effects(w->accel, rays, cfg);
  // exp(-0.5 k) < 1e-3 first for k = 14 plates; the 14th plate's partition closes when the group
  // at its far face is applied, which happens when the first hit beyond it arrives: 1 + 2*14 + 1.
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_NEAR(r.transmission[i], std::exp(-7.0), 1e-6);
    EXPECT_EQ(r.xray_settled[i], 1);
  }
  EXPECT_EQ(r.stats.hits_existing, rays.size() * 2 * kPlates);
  EXPECT_EQ(r.stats.hits_traversed, rays.size() * 30);
}

TEST(Effects, AllExactKernelsGiveTheSameEffectsAndTraversal) {
  auto w = plate_stack();
  const std::vector<Ray> rays = rays_along_z(6);
  std::vector<double> reference;
  std::uint64_t traversed = 0;
  for (KernelKind k : {KernelKind::queue, KernelKind::filter, KernelKind::restart, KernelKind::embree_filter}) {
    EffectsConfig cfg = plate_config({Effect::xray, Effect::penetration});
    cfg.kernel = k;
    const EffectsResult r = run_effects(w->accel, rays, cfg);
    if (reference.empty()) {
      reference = r.transmission;
      traversed = r.stats.hits_traversed;
      continue;
    }
    EXPECT_EQ(r.transmission, reference) << kernel_name(k);
    EXPECT_EQ(r.stats.hits_traversed, traversed) << kernel_name(k);
  }
}

TEST(Effects, ThicknessOnlySceneDoesNoClassificationOrEffectWork) {
  auto w = plate_stack();
  EffectsConfig cfg;
  cfg.enable(Effect::thickness);
  cfg.solid_material.assign(kPlates, -1);  // no materials needed
  cfg.audit = true;
  const std::vector<Ray> rays = rays_along_z(10);
  const EffectsResult r = run_effects(w->accel, rays, cfg);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(r.thick_geom[i], 0u);
    EXPECT_NEAR(r.thick_los[i], kPlateT, 1e-6);
    EXPECT_NEAR(r.thick_normal[i], kPlateT, 1e-6);
  }
  const EffectsStats& s = r.stats;
  EXPECT_EQ(s.partition_groups, 0u);
  EXPECT_EQ(s.partitions_consumed, 0u);
  EXPECT_EQ(s.csg_evaluations, 0u);
  for (Effect e : kAllEffects)
    if (e != Effect::thickness) {
      EXPECT_EQ(s.updates[std::size_t(e)], 0u) << effect_name(e);
    }
  EXPECT_EQ(s.updates[std::size_t(Effect::thickness)], 2 * rays.size());
  // Enter plate 0, leave it (ranked before plate 1's entry at the same t): two hits per ray.
  EXPECT_EQ(s.hits_traversed, 2 * rays.size());
  EXPECT_EQ(s.hits_existing, 2 * kPlates * rays.size());
  EXPECT_EQ(s.rays_settled_early, rays.size());
  EXPECT_TRUE(r.transmission.empty());
  EXPECT_TRUE(r.class_intervals.empty());
}

TEST(Effects, FirstHitOnlyNeverTraversesPastTheFirstHit) {
  auto w = plate_stack();
  EffectsConfig cfg;
  cfg.enable(Effect::first_hit);
  cfg.solid_material.assign(kPlates, -1);
  std::vector<Ray> rays = rays_along_z(10);
  rays.push_back(Ray{{5, 5, -1}, {0, 0, 1}});  // misses
  const EffectsResult r = run_effects(w->accel, rays, cfg);
  EXPECT_EQ(r.stats.hits_traversed, rays.size() - 1);
  EXPECT_EQ(r.stats.partition_groups, 0u);
  EXPECT_NEAR(r.first_t[0], 1.0, 1e-6);
  EXPECT_EQ(r.first_geom[0], 0u);
  EXPECT_DOUBLE_EQ(r.first_obliquity[0], 0.0);
  EXPECT_TRUE(std::isnan(r.first_t.back()));
  EXPECT_EQ(r.first_geom.back(), kInvalidId);
}

TEST(Effects, TransparencyCompositesUntilSaturated) {
  auto w = plate_stack();
  EffectsConfig cfg = plate_config({Effect::transparency});
  cfg.alpha_saturation = 0.99;
  cfg.background = {1, 1, 1};
  const std::vector<Ray> rays = rays_along_z(4);
  const EffectsResult r = run_effects(w->accel, rays, cfg);
  // Every crossing has alpha 0.5: 1 - 0.5^7 >= 0.99 first after 7 crossings.
  EXPECT_EQ(r.stats.hits_traversed, 7 * rays.size());
  // Crossings alternate lead / foam colours in the order lead, lead, foam, foam, lead, lead, foam.
  const Vec3d lead{0.5, 0.5, 0.6}, foam{1.0, 0.9, 0.8};
  const int order[7] = {0, 0, 1, 1, 0, 0, 1};
  Vec3d c{};
  double a = 0;
  for (int k : order) {
    c = c + (k ? foam : lead) * ((1 - a) * 0.5);
    a += (1 - a) * 0.5;
  }
  c = c + Vec3d{1, 1, 1} * (1 - a);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_NEAR(r.rgba[4 * i + 0], c.x, 1e-6);
    EXPECT_NEAR(r.rgba[4 * i + 1], c.y, 1e-6);
    EXPECT_NEAR(r.rgba[4 * i + 2], c.z, 1e-6);
    EXPECT_NEAR(r.rgba[4 * i + 3], a, 1e-6);
  }
  EXPECT_EQ(r.stats.partition_groups, 0u);
}

TEST(Effects, PenetrationStopsWhereTheEnergyRunsOut) {
  auto w = plate_stack();
  EffectsConfig cfg = plate_config({Effect::penetration});
  // Lead loses 10 per unit length, foam 1: plates 0-3 take 1 + 0.1 + 1 + 0.1 = 2.2; 0.45 more
  // lasts 0.045 into plate 4.
  cfg.penetration_energy = 2.65;
  cfg.audit = true;
  const std::vector<Ray> rays = rays_along_z(3);
  const EffectsResult r = run_effects(w->accel, rays, cfg);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_NEAR(r.stop_distance[i], 1.0 + 0.445, 1e-6);
    EXPECT_EQ(r.stop_geom[i], 4u);
    EXPECT_EQ(r.energy[i], 0.0);
  }
  EXPECT_LT(r.stats.hits_traversed, r.stats.hits_existing);
  // A projectile with more energy than the stack absorbs goes through with the rest.
  cfg.penetration_energy = 100;
  const EffectsResult through = run_effects(w->accel, rays, cfg);
  EXPECT_NEAR(through.energy[0], 100 - (10 * 10.0 * kPlateT + 10 * 1.0 * kPlateT), 1e-6);
  EXPECT_TRUE(std::isnan(through.stop_distance[0]));
  EXPECT_EQ(through.stats.hits_traversed, through.stats.hits_existing);
}

TEST(Effects, RaysStartingInsideOrEndingInsideASolidCountOnlyTheirOwnSegment) {
  auto w = plate_stack();
  EffectsConfig cfg = plate_config({Effect::xray});
  cfg.materials[1].mu = kMuLead;
  // From inside plate 10 (z = 1.05) up: 0.05 of plate 10 and plates 11..19.
  const Ray inside{{0.5, 0.5, 1.05}, {0, 0, 1}};
  // From below, ending inside plate 2 (z = 0.25): plates 0, 1 and half of 2.
  Ray short_ray{{0.5, 0.5, -1}, {0, 0, 1}};
  short_ray.tmax = 1.25;
  const EffectsResult r = run_effects(w->accel, {inside, short_ray}, cfg);
  EXPECT_NEAR(r.transmission[0], std::exp(-kMuLead * 0.95), 1e-6);
  EXPECT_NEAR(r.transmission[1], std::exp(-kMuLead * 0.25), 1e-6);
}

TEST(Effects, OverlapsAndClassificationNeedEveryHit) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.75, 0, 0}, {1.75, 1, 1}, "b"),
                       gen::box({1.75, 0, 0}, {2, 1, 1}, "c")});
  EffectsConfig cfg;
  cfg.enable(Effect::overlaps);
  cfg.enable(Effect::classification);
  cfg.materials = {Material{"steel", 7.8, 0, 0, {}, 0}};
  cfg.solid_material = {0, 0, 0};
  cfg.audit = true;
  const Ray ray{{-1, 0.5, 0.5}, {1, 0, 0}};
  const EffectsResult r = run_effects(w->accel, {ray}, cfg);
  EXPECT_EQ(r.stats.hits_traversed, r.stats.hits_existing);
  EXPECT_EQ(r.overlap_count[0], 1u);
  EXPECT_NEAR(r.overlap_max_depth[0], 0.25, 1e-6);
  ASSERT_EQ(r.overlap_intervals.size(), 1u);
  EXPECT_EQ(r.overlap_intervals[0].a, 0u);
  EXPECT_EQ(r.overlap_intervals[0].b, 1u);
  ASSERT_EQ(r.class_intervals.size(), 4u);  // a, a+b, b, c (touching: no gap)
  EXPECT_EQ(r.class_intervals[1].count, 2u);
  EXPECT_EQ(r.class_intervals[2].t_out, r.class_intervals[3].t_in);
  EXPECT_NEAR(r.class_los[0], 2.0, 1e-6);
  EXPECT_NEAR(r.areal_density[0], 7.8 * (1.0 + 1.0 + 0.25), 1e-5);  // the overlap counts for both

  cfg.classification_csg = parse_csg("union(a, b, c)", w->scene);
  const EffectsResult u = run_effects(w->accel, {ray}, cfg);
  ASSERT_EQ(u.class_intervals.size(), 1u);
  EXPECT_NEAR(u.class_intervals[0].los, 2.0, 1e-6);
  EXPECT_GT(u.stats.csg_evaluations, 0u);
}

TEST(Effects, ValidationNamesTheProblem) {
  auto w = plate_stack();
  EffectsConfig cfg = plate_config({Effect::xray});
  cfg.solid_material[3] = -1;
  try {
    run_effects(w->accel, rays_along_z(1), cfg);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("plate3"), std::string::npos) << e.what();
  }
  cfg = plate_config({Effect::xray});
  cfg.xray_threshold = 1.5;
  EXPECT_THROW(run_effects(w->accel, rays_along_z(1), cfg), std::invalid_argument);
  cfg = plate_config({Effect::xray});
  cfg.kernel = KernelKind::epsilon;
  EXPECT_THROW(run_effects(w->accel, rays_along_z(1), cfg), std::invalid_argument);
}

// ---- scene files -------------------------------------------------------------------------------

std::string scene_error(const std::string& text) {
  try {
    parse_effect_scene(text, "dir/scene.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// bind_effect_scene's InputError message ("" when it binds).
std::string bind_error(const EffectSceneSpec& spec, const Scene& scene) {
  try {
    bind_effect_scene(spec, scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(EffectScene, ParsesModelsMaterialsRaysEffectsAndOutputs) {
  const EffectSceneSpec s = parse_effect_scene(R"js({
    // comments are allowed
    "models": ["stack.obj", "/abs/other.stl"],
    "materials": {"lead": {"density": 11.3, "mu": 5, "opacity": 0.5, "color": [0.5, 0.5, 0.6], "energy_loss": 10}},
    "solids": {"plate0": "lead", "*": {"mu": 0.5}},
    "rays": "grid:axis=z,n=16",
    "kernel": "filter",
    "effects": {"xray": {"threshold": 0.01, "image": "out/x.png", "vti": "x.vti"}, "thickness": {},
                "classification": {"csg": "union(plate0, plate1)"}},
    "output": {"rays": "rays.csv", "report": "report.json", "intervals": "iv.csv"}
  })js",
                                               "dir/scene.json");
  EXPECT_EQ(s.models, (std::vector<std::string>{"dir/stack.obj", "/abs/other.stl"}));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].mu, 5);
  EXPECT_EQ(s.materials[1].mu, 0.5);
  ASSERT_EQ(s.assignments.size(), 2u);
  EXPECT_EQ(s.assignments[0], (std::pair<std::string, std::size_t>{"plate0", 0}));
  EXPECT_EQ(s.assignments[1], (std::pair<std::string, std::size_t>{"*", 1}));
  EXPECT_EQ(s.rays, "grid:axis=z,n=16");
  EXPECT_EQ(s.config.kernel, KernelKind::filter);
  EXPECT_TRUE(s.config.on(Effect::xray));
  EXPECT_TRUE(s.config.on(Effect::thickness));
  EXPECT_FALSE(s.config.on(Effect::overlaps));
  EXPECT_EQ(s.config.xray_threshold, 0.01);
  EXPECT_EQ(s.xray_png, "dir/out/x.png");
  EXPECT_EQ(s.rays_csv, "dir/rays.csv");
  EXPECT_EQ(s.csg, "union(plate0, plate1)");

  auto w = plate_stack();
  const EffectsConfig cfg = bind_effect_scene(s, w->scene);
  EXPECT_EQ(cfg.solid_material[0], 0);
  EXPECT_EQ(cfg.solid_material[7], 1);
  ASSERT_TRUE(cfg.classification_csg.has_value());
}

TEST(EffectScene, EffectsAsAListAndCameraRays) {
  const EffectSceneSpec s = parse_effect_scene(R"js({"models": "m.obj", "effects": ["first_hit", "thickness"],
    "rays": {"camera": {"center": [0, 0, -5], "direction": [0, 0, 2], "up": [0, 1, 0], "size": [2, 1], "pixels": [4, 2]}}})js",
                                               "scene.json");
  ASSERT_TRUE(s.camera.has_value());
  EXPECT_TRUE(s.config.on(Effect::first_hit));
  const std::vector<Ray> rays = camera_rays(*s.camera);
  ASSERT_EQ(rays.size(), 8u);
  // Top-left pixel first; right = direction x up = -x here.
  EXPECT_NEAR(rays[0].org.x, 0.75, 1e-12);
  EXPECT_NEAR(rays[0].org.y, 0.25, 1e-12);
  EXPECT_NEAR(rays[7].org.x, -0.75, 1e-12);
  EXPECT_NEAR(rays[7].org.y, -0.25, 1e-12);
  EXPECT_NEAR(length(rays[0].dir), 1.0, 1e-12);
}

TEST(EffectScene, ErrorsNameFileKeyAndProblem) {
  EXPECT_NE(scene_error(R"js({"models": "m.obj", "rays": "grid", "effects": ["xray"], "colour": 1})js")
                .find("dir/scene.json: unknown key 'colour'"),
            std::string::npos);
  EXPECT_NE(scene_error(R"js({"models": "m.obj", "rays": "grid", "effects": {"xray": {"threshold": 2}}})js")
                .find("effects.xray.threshold: must be in (0, 1), got 2"),
            std::string::npos);
  EXPECT_NE(scene_error(R"js({"models": "m.obj", "rays": "grid", "effects": ["xrays"]})js").find("unknown effect 'xrays'"),
            std::string::npos);
  EXPECT_NE(scene_error(R"js({"models": "m.obj", "rays": "grid", "effects": [], "solids": {"a": "gold"}})js")
                .find("solids.a: unknown material 'gold'"),
            std::string::npos);
  EXPECT_NE(scene_error(R"js({"models": "m.obj", "rays": "grid", "effects": []})js").find("no effect requested"),
            std::string::npos);
  EXPECT_NE(scene_error("{\"models\": \"m.obj\",\n  \"rays\": \"grid\" \"effects\": []}").find("dir/scene.json:2:"),
            std::string::npos);
  EXPECT_NE(scene_error(R"js({"rays": "grid", "effects": ["xray"]})js").find("missing 'models'"), std::string::npos);
  EXPECT_NE(scene_error(R"js({"models": "m.obj", "rays": {"camera": {"center": [0,0,0], "up": [0,0,1]}},
                            "effects": ["xray"]})js")
                .find("rays.camera.up: must not be zero or parallel"),
            std::string::npos);

  auto w = plate_stack();
  const EffectSceneSpec s = parse_effect_scene(
      R"js({"models": "m.obj", "rays": "grid", "effects": ["xray"], "materials": {"lead": {"mu": 1}},
          "solids": {"plate0": "lead", "plate99": "lead", "wing": "lead"}})js",
      "s.json");
  EXPECT_NE(bind_error(s, w->scene).find("no solid named 'plate99', 'wing'"), std::string::npos);
  const EffectSceneSpec missing = parse_effect_scene(
      R"js({"models": "m.obj", "rays": "grid", "effects": ["xray"], "materials": {"lead": {"mu": 1}},
          "solids": {"plate0": "lead"}})js",
      "s.json");
  EXPECT_NE(bind_error(missing, w->scene).find("19 solid(s) without a material"), std::string::npos);
}

TEST(EffectScene, GridRaysFormAnImageWithRowZeroAtTheBottom) {
  auto w = plate_stack();
  EffectSceneSpec s;
  s.rays = "grid:axis=z,n=4";
  const SceneRays r = make_scene_rays(s, w->scene);
  ASSERT_TRUE(r.is_image());
  EXPECT_EQ(r.width, 4);
  EXPECT_EQ(r.ray_of_pixel(0, 3), 0u);   // bottom-left pixel is ray 0
  EXPECT_EQ(r.ray_of_pixel(3, 0), 15u);  // top-right is the last ray
  EXPECT_NEAR(r.plane_spacing.x, 0.25, 1e-12);
}

}  // namespace
}  // namespace pierce::analysis
