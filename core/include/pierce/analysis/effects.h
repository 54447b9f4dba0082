#pragma once
// Scene-driven effects along rays: only the requested ones run, and each ray walks the next-hit
// iterator only until every requested effect on it is settled (Gribble et al.'s multi-hit use
// cases: transparency and ballistic penetration; Beer-Lambert X-ray attenuation).
//
// Effects and when they are settled on a ray:
//   first_hit       distance, solid and obliquity of the first crossing      at the first hit
//   thickness       line of sight and normal thickness through the first     when the ray leaves
//                   solid the ray enters                                     that solid
//   transparency    front-to-back alpha compositing of every crossing        accumulated alpha >=
//                   (material opacity and colour, shaded by |cos obliquity|) saturation
//   xray            transmission I/I0 = exp(-sum mu_i L_i) (Beer-Lambert)    I/I0 < threshold
//   penetration     energy budget: energy_loss x length is consumed in each  energy exhausted
//                   solid; where the ray stops
//   overlaps        intervals inside two or more solids                     never (needs all hits)
//   classification  partitions (or CSG intervals), line of sight, areal      never (needs all hits)
//                   density sum rho_i L_i
// first_hit, thickness and transparency read single crossings; xray, penetration, overlaps and
// classification read partitions, built as the hits stream in (PartitionBuilder's streaming form)
// on the ray traced as a full line so that a ray starting inside a solid knows it. Without a
// partition effect no partition is built and the ray is traced as given. Overlapping solids each
// attenuate / consume energy over the shared interval (overlaps are modelling errors; the
// `overlaps` effect reports them).
//
// Open meshes: partitions are consumed as they close, before the ray knows a solid will never be
// left; a solid entered and never left keeps acting until the ray ends or is settled (counted in
// EffectsStats::unclosed). Effects act on [ray.tmin, ray.tmax] only.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pierce/analysis/csg.h"
#include "pierce/progress.h"
#include "pierce/enum_names.h"
#include "pierce/kernel.h"

namespace pierce::analysis {

enum class Effect : std::uint8_t { first_hit, thickness, transparency, xray, penetration, overlaps, classification };
constexpr EnumTable<Effect, 7> enum_table(Effect) {
  using enum Effect;
  return {"effect", {{first_hit, "first_hit"}, {thickness, "thickness"}, {transparency, "transparency"},
                  {xray, "xray"}, {penetration, "penetration"}, {overlaps, "overlaps"},
                  {classification, "classification"}}};
}
inline constexpr std::size_t kEffectCount = 7;
inline constexpr Effect kAllEffects[kEffectCount] = {Effect::first_hit,   Effect::thickness, Effect::transparency,
                                                      Effect::xray,        Effect::penetration, Effect::overlaps,
                                                      Effect::classification};
// The names of enum_table(Effect), as the scene files spell them.
inline std::string_view effect_name(Effect e) { return enum_name(e); }
inline std::optional<Effect> parse_effect(std::string_view name) { return parse_enum<Effect>(name); }
// True for the effects that read partitions (xray, penetration, overlaps, classification).
bool needs_partitions(Effect e);

struct Material {
  std::string name;
  double density = 0;      // mass per volume (classification: areal density)
  double mu = 0;           // linear attenuation coefficient, 1 / length (xray)
  double opacity = 0;      // alpha of one surface crossing, [0, 1] (transparency)
  Vec3d color{0.8, 0.8, 0.8};  // transparency, each channel in [0, 1]
  double energy_loss = 0;  // energy consumed per length inside (penetration)
};

struct EffectsConfig {
  std::array<bool, kEffectCount> enabled{};
  std::vector<Material> materials;
  std::vector<std::int32_t> solid_material;  // per geometry: index into materials, -1 = none
  double xray_threshold = 1e-3;    // settled below this transmission, in (0, 1)
  double alpha_saturation = 0.99;  // settled at this accumulated alpha, in (0, 1]
  Vec3d background{0, 0, 0};       // transparency: seen through what is left, (1 - alpha) x background
  double penetration_energy = 1;   // initial energy, > 0
  std::optional<CsgExpr> classification_csg;  // classification: the expression's intervals instead
  double tie_tolerance_rel = 1e-6;  // overlaps shorter than tie_distance() are contacts; classification snaps
  KernelKind kernel = kDefaultKernel;
  bool audit = false;  // also count the hits that exist along each ray (a second, full traversal)
  int timing_stride = 16;  // time the effects on every k-th ray (0: never) and extrapolate

  bool on(Effect e) const { return enabled[std::size_t(e)]; }
  void enable(Effect e) { enabled[std::size_t(e)] = true; }
};

// Throws std::invalid_argument naming the problem: a non-exact kernel, parameters out of range,
// solid_material not sized to the scene, an index past `materials`, or a solid without a material
// when an effect needs one (xray, transparency, penetration).
void validate(const EffectsConfig& cfg, const Scene& scene);

struct ClassInterval {
  std::uint32_t ray = 0;
  double t_in = 0, t_out = 0;
  double los = 0;  // (t_out - t_in) * |dir|
  std::uint32_t first = 0, count = 0;  // solids: EffectsResult::class_solids[first, first + count); 0 for CSG
};

struct OverlapInterval {
  std::uint32_t ray = 0, a = 0, b = 0;  // the two lowest solid ids of the partition
  std::uint32_t solids = 0;             // how many solids claim it
  double t_in = 0, t_out = 0, depth = 0;
};

// Work counters, summed over rays. The partition and effect counters stay 0 for effects that were
// not requested: that is how a run proves it did no work for them.
struct EffectsStats {
  std::uint64_t rays = 0;
  std::uint64_t hits_traversed = 0;  // hits pulled from the iterator
  std::uint64_t hits_existing = 0;   // with audit: every hit on the traced rays; else 0
  std::uint64_t rays_settled_early = 0;  // rays stopped before their hits ran out
  std::uint64_t partition_groups = 0;    // hit groups fed to the partition builder
  std::uint64_t partitions_consumed = 0;
  std::uint64_t csg_evaluations = 0;
  std::array<std::uint64_t, kEffectCount> updates{};  // times each effect's update ran
  std::uint64_t unclosed = 0, unmatched_leaves = 0;   // bad-mesh events
  std::uint64_t timed_rays = 0;
  double seconds_wall = 0;
  double seconds_audit = 0;
  // CPU seconds estimated from the timed rays (scaled to all rays): traversal (iterator), partition
  // building, and each effect's updates.
  double seconds_traversal = 0, seconds_partitions = 0;
  std::array<double, kEffectCount> seconds_effect{};
};

struct EffectsResult {
  std::size_t rays = 0;
  // Per ray, filled for enabled effects only (empty otherwise). NaN / kInvalidId: nothing found.
  std::vector<double> first_t;  // distance from the origin (t * |dir|)
  std::vector<std::uint32_t> first_geom;
  std::vector<double> first_obliquity;
  std::vector<std::uint32_t> thick_geom;
  std::vector<double> thick_los, thick_normal;
  std::vector<float> rgba;  // transparency: 4 per ray, premultiplied colour over the background + alpha
  std::vector<double> transmission;         // xray: I / I0 (below the threshold where settled early)
  std::vector<std::uint8_t> xray_settled;   // 1 where the ray stopped because I/I0 < threshold
  std::vector<double> energy;               // penetration: energy left
  std::vector<double> stop_distance;        // where the energy ran out (distance from the origin); NaN: through
  std::vector<std::uint32_t> stop_geom;
  std::vector<std::uint32_t> overlap_count;  // overlaps: intervals per ray
  std::vector<double> overlap_max_depth;
  std::vector<OverlapInterval> overlap_intervals;
  std::vector<double> areal_density;  // classification: sum of density x length (NaN without materials)
  std::vector<double> class_los;      // classification: total length inside (or inside the expression)
  std::vector<ClassInterval> class_intervals;
  std::vector<std::uint32_t> class_solids;
  EffectsStats stats;
  bool completed = true;
};

// Runs the enabled effects on every ray (TBB, deterministic results). Calls validate() first.
EffectsResult run_effects(const Accel& accel, const std::vector<Ray>& rays, const EffectsConfig& cfg,
                          const Progress& progress = {});

}  // namespace pierce::analysis
