#include "pierce/analysis/effects.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "pierce/analysis/tie_distance.h"
#include "pierce/parallel_for_items.h"

namespace pierce::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
using Clock = std::chrono::steady_clock;

std::size_t idx(Effect e) { return std::size_t(e); }

std::string label(const Scene& scene, std::uint32_t g) {
  std::string l = scene.geometry(g).name;
  if (l.empty()) l.append("#").append(std::to_string(g));
  return l;
}

// Material properties per geometry, looked up per partition or crossing.
struct SolidProps {
  std::vector<double> mu, loss, density, opacity;
  std::vector<Vec3d> color;
  bool all_have_material = true;

  SolidProps(const EffectsConfig& cfg, std::size_t geoms)
      : mu(geoms, 0), loss(geoms, 0), density(geoms, 0), opacity(geoms, 0), color(geoms) {
    for (std::size_t g = 0; g < geoms; ++g) {
      const std::int32_t m = cfg.solid_material[g];
      if (m < 0) {
        all_have_material = false;
        continue;
      }
      const Material& mat = cfg.materials[std::size_t(m)];
      mu[g] = mat.mu, loss[g] = mat.energy_loss, density[g] = mat.density, opacity[g] = mat.opacity;
      color[g] = mat.color;
    }
  }
};

// Per-ray interval lists, concatenated in ray order at the end.
struct RayLists {
  std::vector<OverlapInterval> overlaps;
  std::vector<ClassInterval> intervals;
  std::vector<std::uint32_t> solids;
};

// Everything one thread needs; reused across rays.
struct Worker {
  HitIterator it;
  std::optional<HitIterator> audit_it;
  PartitionBuilder builder;
  RayPartitions parts;
  std::vector<Hit> group;
  std::optional<CsgEvaluator> csg;
  std::vector<CsgInterval> csg_out;
  EffectsStats stats;
  RayLists no_lists;  // handed to rays when no effect keeps lists: never filled

  Worker(const Accel& accel, const EffectsConfig& cfg)
      : it(accel, cfg.kernel, KernelOptions{HitOrder{TieOrder::leave_before_enter}}),
        builder(accel.scene().geometries().size()) {
    if (cfg.audit) audit_it.emplace(accel, cfg.kernel, KernelOptions{HitOrder{TieOrder::leave_before_enter}});
    if (cfg.classification_csg) csg.emplace(*cfg.classification_csg, accel.scene().geometries().size());
  }
};

// Accumulates CPU time into a slot only on timed rays.
class Stopwatch {
 public:
  explicit Stopwatch(bool on) : on_(on) {}
  template <typename F>
  void run(double& slot, F&& f) {
    if (!on_) {
      f();
      return;
    }
    const auto t0 = Clock::now();
    f();
    slot += std::chrono::duration<double>(Clock::now() - t0).count();
  }

 private:
  bool on_;
};

// One ray's walk. Effects are plain members with enabled flags: no virtual calls, no allocation
// once the worker's buffers are warm.
class RayWalk {
 public:
  RayWalk(const EffectsConfig& cfg, const SolidProps& props, const Scene& scene, Worker& w, const Ray& ray,
          std::uint32_t index, bool timed, EffectsResult& res, RayLists& lists)
      : cfg_(cfg), props_(props), scene_(scene), w_(w), ray_(ray), index_(index), watch_(timed), timed_(timed),
        res_(res), lists_(lists), dir_len_(length(ray.dir)) {
    tie_t_ = tie_distance(scene, cfg.tie_tolerance_rel) / (dir_len_ > 0 ? dir_len_ : 1.0);
    for (Effect e : kAllEffects) {
      if (!cfg.on(e)) continue;
      open_[idx(e)] = true;
      ++unsettled_;
      partitions_ = partitions_ || needs_partitions(e);
    }
    energy_ = cfg.penetration_energy;
  }

  void run();

 private:
  void settle(Effect e) {
    if (open_[idx(e)]) open_[idx(e)] = false, --unsettled_;
  }
  bool open(Effect e) const { return open_[idx(e)]; }

  void on_hit(const Hit& h);
  void flush_group();
  void consume_closed();
  void consume(double t_in, double t_out, std::span<const std::uint32_t> solids);
  void finish_classification();
  void store();

  const EffectsConfig& cfg_;
  const SolidProps& props_;
  const Scene& scene_;
  Worker& w_;
  const Ray& ray_;
  std::uint32_t index_;
  Stopwatch watch_;
  bool timed_;
  EffectsResult& res_;
  RayLists& lists_;
  double dir_len_, tie_t_ = 0;

  std::array<bool, kEffectCount> open_{};
  int unsettled_ = 0;
  bool partitions_ = false;
  std::size_t consumed_ = 0;
  double secs_traversal_ = 0, secs_partitions_ = 0;
  std::array<double, kEffectCount> secs_{};

  // Effect state.
  double first_t_ = kNaN, first_obl_ = kNaN;
  std::uint32_t first_geom_ = kInvalidId;
  std::uint32_t thick_geom_ = kInvalidId;
  int thick_depth_ = 0;
  double thick_t0_ = 0, thick_obl_ = kNaN, thick_los_ = kNaN, thick_normal_ = kNaN;
  Vec3d color_{};
  double alpha_ = 0;
  double tau_ = 0;
  bool xray_settled_ = false;
  double energy_ = 0, stop_distance_ = kNaN;
  std::uint32_t stop_geom_ = kInvalidId;
  std::uint32_t overlap_count_ = 0;
  double overlap_max_ = 0;
};

void RayWalk::on_hit(const Hit& h) {
  if (open(Effect::first_hit)) {
    watch_.run(secs_[idx(Effect::first_hit)], [&] {
      ++w_.stats.updates[idx(Effect::first_hit)];
      first_t_ = h.t * dir_len_;
      first_geom_ = h.geom;
      first_obl_ = obliquity_deg(ray_.dir, h);
      settle(Effect::first_hit);
    });
  }
  if (open(Effect::thickness)) {
    watch_.run(secs_[idx(Effect::thickness)], [&] {
      ++w_.stats.updates[idx(Effect::thickness)];
      if (thick_geom_ == kInvalidId) {
        if (!h.enter) return;  // leaving a solid the ray started in
        thick_geom_ = h.geom;
        thick_t0_ = h.t;
        thick_depth_ = 1;
        thick_obl_ = obliquity_deg(ray_.dir, h);
        return;
      }
      if (h.geom != thick_geom_) return;
      thick_depth_ += h.enter ? 1 : -1;
      if (thick_depth_ > 0) return;
      thick_los_ = (h.t - thick_t0_) * dir_len_;
      thick_normal_ = thick_los_ * std::cos(thick_obl_ * kDegToRad);
      settle(Effect::thickness);
    });
  }
  if (open(Effect::transparency)) {
    watch_.run(secs_[idx(Effect::transparency)], [&] {
      ++w_.stats.updates[idx(Effect::transparency)];
      const double a = props_.opacity[h.geom];
      // |cos obliquity| without the angle: the surface's brightness under a head-on light.
      const Vec3d n(h.ng);
      const double nn = length(n) * dir_len_;
      const double shade = nn > 0 ? std::abs(dot(n, ray_.dir)) / nn : 1.0;
      const double weight = (1 - alpha_) * a * shade;
      color_ = color_ + props_.color[h.geom] * weight;
      alpha_ += (1 - alpha_) * a;
      if (alpha_ >= cfg_.alpha_saturation) settle(Effect::transparency);
    });
  }
}

void RayWalk::consume(double t_in, double t_out, std::span<const std::uint32_t> solids) {
  const double a = std::max(t_in, ray_.tmin), b = std::min(t_out, ray_.tmax);
  if (!(b > a)) return;
  ++w_.stats.partitions_consumed;
  const double len = (b - a) * dir_len_;
  if (open(Effect::xray)) {
    watch_.run(secs_[idx(Effect::xray)], [&] {
      ++w_.stats.updates[idx(Effect::xray)];
      double mu = 0;
      for (std::uint32_t g : solids) mu += props_.mu[g];
      tau_ += mu * len;
      if (std::exp(-tau_) < cfg_.xray_threshold) {
        xray_settled_ = true;
        settle(Effect::xray);
      }
    });
  }
  if (open(Effect::penetration)) {
    watch_.run(secs_[idx(Effect::penetration)], [&] {
      ++w_.stats.updates[idx(Effect::penetration)];
      double rate = 0;
      for (std::uint32_t g : solids) rate += props_.loss[g];
      if (!(rate > 0)) return;
      if (energy_ > rate * len) {
        energy_ -= rate * len;
        return;
      }
      stop_distance_ = a * dir_len_ + energy_ / rate;
      stop_geom_ = solids.front();
      energy_ = 0;
      settle(Effect::penetration);
    });
  }
  if (cfg_.on(Effect::overlaps) && solids.size() >= 2) {
    watch_.run(secs_[idx(Effect::overlaps)], [&] {
      ++w_.stats.updates[idx(Effect::overlaps)];
      if (len <= tie_t_ * dir_len_) return;  // touching faces a rounding error apart
      ++overlap_count_;
      overlap_max_ = std::max(overlap_max_, len);
      lists_.overlaps.push_back({index_, solids[0], solids[1], std::uint32_t(solids.size()), a, b, len});
    });
  }
}

void RayWalk::consume_closed() {
  const std::size_t closed = w_.parts.partitions.size() - (w_.builder.partition_open() ? 1 : 0);
  for (; consumed_ < closed; ++consumed_) {
    const Partition& p = w_.parts.partitions[consumed_];
    consume(p.t_in, p.t_out, w_.parts.solids_of(p));
  }
}

void RayWalk::flush_group() {
  if (w_.group.empty()) return;
  watch_.run(secs_partitions_, [&] {
    ++w_.stats.partition_groups;
    w_.builder.add_group(w_.group, w_.parts);
    w_.group.clear();
  });
  consume_closed();
}

void RayWalk::finish_classification() {
  ++w_.stats.updates[idx(Effect::classification)];
  RayPartitions& parts = w_.parts;
  snap_partitions(parts, tie_t_);
  clip_partitions(parts, ray_.tmin, ray_.tmax);
  double areal = props_.all_have_material ? 0.0 : kNaN, los = 0;
  for (const Partition& p : parts.partitions) {
    const double len = (p.t_out - p.t_in) * dir_len_;
    for (std::uint32_t g : parts.solids_of(p)) areal += props_.density[g] * len;
  }
  if (w_.csg) {
    const std::uint64_t before = w_.csg->evaluations;
    w_.csg->evaluate(parts, w_.csg_out);
    w_.stats.csg_evaluations += w_.csg->evaluations - before;
    for (const CsgInterval& iv : w_.csg_out) {
      const double len = (iv.t_out - iv.t_in) * dir_len_;
      los += len;
      lists_.intervals.push_back({index_, iv.t_in, iv.t_out, len, 0, 0});
    }
  } else {
    for (const Partition& p : parts.partitions) {
      const double len = (p.t_out - p.t_in) * dir_len_;
      los += len;
      const auto s = parts.solids_of(p);
      lists_.intervals.push_back({index_, p.t_in, p.t_out, len, std::uint32_t(lists_.solids.size()), p.count});
      lists_.solids.insert(lists_.solids.end(), s.begin(), s.end());
    }
  }
  res_.areal_density[index_] = areal;
  res_.class_los[index_] = los;
}

void RayWalk::run() {
  Ray traced = partitions_ ? full_line_ray(ray_, scene_.bounds()) : ray_;
  if (cfg_.audit) {
    const auto t0 = Clock::now();
    w_.audit_it->begin(traced);
    Hit h;
    while (w_.audit_it->next(h)) ++w_.stats.hits_existing;
    w_.stats.seconds_audit += std::chrono::duration<double>(Clock::now() - t0).count();
  }
  if (partitions_) {
    w_.builder.begin(w_.parts);
    w_.group.clear();
  }
  watch_.run(secs_traversal_, [&] { w_.it.begin(traced); });
  bool exhausted = false, beyond = false;
  Hit h;
  while (unsettled_ > 0) {
    bool got = false;
    watch_.run(secs_traversal_, [&] { got = w_.it.next(h); });
    if (!got) {
      exhausted = true;
      break;
    }
    ++w_.stats.hits_traversed;
    if (partitions_) {
      if (!w_.group.empty() && h.t != w_.group.front().t) flush_group();
      if (h.t > ray_.tmax) {  // the full line runs on; the ray ends inside the open partition
        if (w_.builder.partition_open()) {
          Partition& p = w_.parts.partitions.back();
          consume(p.t_in, ray_.tmax, w_.parts.solids_of(p));
          p.t_out = ray_.tmax;
          p.out_hit = Hit{};
          consumed_ = w_.parts.partitions.size();
        }
        beyond = true;
        break;
      }
      if (unsettled_ == 0) break;
      w_.group.push_back(h);
    }
    if (h.t >= ray_.tmin && h.t <= ray_.tmax) on_hit(h);
  }
  if (partitions_ && exhausted) {
    flush_group();
    w_.builder.finish(w_.parts);  // drops what an open mesh leaves unclosed
  }
  if (!exhausted && !beyond) ++w_.stats.rays_settled_early;
  if (partitions_) {
    w_.stats.unclosed += w_.parts.unclosed;
    w_.stats.unmatched_leaves += w_.parts.unmatched_leaves;
  }
  if (cfg_.on(Effect::classification))
    watch_.run(secs_[idx(Effect::classification)], [&] { finish_classification(); });
  store();
  if (timed_) {
    ++w_.stats.timed_rays;
    w_.stats.seconds_traversal += secs_traversal_;
    w_.stats.seconds_partitions += secs_partitions_;
    for (std::size_t e = 0; e < kEffectCount; ++e) w_.stats.seconds_effect[e] += secs_[e];
  }
}

void RayWalk::store() {
  const std::size_t i = index_;
  if (cfg_.on(Effect::first_hit)) {
    res_.first_t[i] = first_t_;
    res_.first_geom[i] = first_geom_;
    res_.first_obliquity[i] = first_obl_;
  }
  if (cfg_.on(Effect::thickness)) {
    res_.thick_geom[i] = std::isnan(thick_los_) ? kInvalidId : thick_geom_;
    res_.thick_los[i] = thick_los_;
    res_.thick_normal[i] = thick_normal_;
  }
  if (cfg_.on(Effect::transparency)) {
    const Vec3d c = color_ + cfg_.background * (1 - alpha_);
    res_.rgba[4 * i + 0] = float(c.x);
    res_.rgba[4 * i + 1] = float(c.y);
    res_.rgba[4 * i + 2] = float(c.z);
    res_.rgba[4 * i + 3] = float(alpha_);
  }
  if (cfg_.on(Effect::xray)) {
    res_.transmission[i] = std::exp(-tau_);
    res_.xray_settled[i] = xray_settled_;
  }
  if (cfg_.on(Effect::penetration)) {
    res_.energy[i] = energy_;
    res_.stop_distance[i] = stop_distance_;
    res_.stop_geom[i] = stop_geom_;
  }
  if (cfg_.on(Effect::overlaps)) {
    res_.overlap_count[i] = overlap_count_;
    res_.overlap_max_depth[i] = overlap_max_;
  }
}

void allocate(EffectsResult& r, const EffectsConfig& cfg, std::size_t n) {
  r.rays = n;
  if (cfg.on(Effect::first_hit)) {
    r.first_t.assign(n, kNaN);
    r.first_geom.assign(n, kInvalidId);
    r.first_obliquity.assign(n, kNaN);
  }
  if (cfg.on(Effect::thickness)) {
    r.thick_geom.assign(n, kInvalidId);
    r.thick_los.assign(n, kNaN);
    r.thick_normal.assign(n, kNaN);
  }
  if (cfg.on(Effect::transparency)) r.rgba.assign(4 * n, 0.f);
  if (cfg.on(Effect::xray)) {
    r.transmission.assign(n, 1.0);
    r.xray_settled.assign(n, 0);
  }
  if (cfg.on(Effect::penetration)) {
    r.energy.assign(n, cfg.penetration_energy);
    r.stop_distance.assign(n, kNaN);
    r.stop_geom.assign(n, kInvalidId);
  }
  if (cfg.on(Effect::overlaps)) {
    r.overlap_count.assign(n, 0);
    r.overlap_max_depth.assign(n, 0);
  }
  if (cfg.on(Effect::classification)) {
    r.areal_density.assign(n, kNaN);
    r.class_los.assign(n, 0);
  }
}

}  // namespace

bool needs_partitions(Effect e) {
  return e == Effect::xray || e == Effect::penetration || e == Effect::overlaps || e == Effect::classification;
}

void validate(const EffectsConfig& cfg, const Scene& scene) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("effects: " + what); };
  if (!is_exact(cfg.kernel)) fail("kernel '" + std::string(kernel_name(cfg.kernel)) + "' is not exact");
  if (!(cfg.xray_threshold > 0 && cfg.xray_threshold < 1)) fail("xray threshold must be in (0, 1)");
  if (!(cfg.alpha_saturation > 0 && cfg.alpha_saturation <= 1)) fail("transparency saturation must be in (0, 1]");
  if (!(cfg.penetration_energy > 0) || !std::isfinite(cfg.penetration_energy))
    fail("penetration energy must be a finite number > 0");
  if (!(cfg.tie_tolerance_rel >= 0)) fail("tie tolerance must be >= 0");
  if (cfg.timing_stride < 0) fail("timing stride must be >= 0");
  if (cfg.solid_material.size() != scene.geometries().size())
    fail("solid_material has " + std::to_string(cfg.solid_material.size()) + " entries for " +
         std::to_string(scene.geometries().size()) + " solids");
  for (const Material& m : cfg.materials) {
    if (!(m.density >= 0) || !(m.mu >= 0) || !(m.energy_loss >= 0) || !std::isfinite(m.density) ||
        !std::isfinite(m.mu) || !std::isfinite(m.energy_loss))
      fail("material '" + m.name + "': density, mu and energy_loss must be finite and >= 0");
    if (!(m.opacity >= 0 && m.opacity <= 1)) fail("material '" + m.name + "': opacity must be in [0, 1]");
    for (std::size_t c = 0; c < 3; ++c)
      if (!(m.color[c] >= 0 && m.color[c] <= 1)) fail("material '" + m.name + "': colour channels must be in [0, 1]");
  }
  const bool need_material = cfg.on(Effect::xray) || cfg.on(Effect::transparency) || cfg.on(Effect::penetration);
  std::string missing;
  std::size_t missing_count = 0;
  for (std::size_t g = 0; g < cfg.solid_material.size(); ++g) {
    const std::int32_t m = cfg.solid_material[g];
    if (m >= std::int32_t(cfg.materials.size())) fail("solid " + std::to_string(g) + ": material index out of range");
    if (m < 0 && need_material && missing_count++ < 10) {
      if (!missing.empty()) missing += ", ";
      missing += label(scene, std::uint32_t(g));
    }
  }
  if (missing_count)
    fail(std::to_string(missing_count) + " solid(s) without a material, needed by xray/transparency/penetration: " +
         missing + (missing_count > 10 ? ", ..." : ""));
}

EffectsResult run_effects(const Accel& accel, const std::vector<Ray>& rays, const EffectsConfig& cfg,
                          const Progress& progress) {
  const Scene& scene = accel.scene();
  validate(cfg, scene);
  const auto t0 = Clock::now();
  EffectsResult res;
  allocate(res, cfg, rays.size());
  const SolidProps props(cfg, scene.geometries().size());
  const bool lists = cfg.on(Effect::overlaps) || cfg.on(Effect::classification);
  std::vector<RayLists> per_ray(lists ? rays.size() : 0);
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker(accel, cfg); });
  res.completed = parallel_for_items(rays.size(), 64, workers, progress, [&](Worker& w, std::size_t i) {
    const bool timed = cfg.timing_stride > 0 && i % std::size_t(cfg.timing_stride) == 0;
    RayWalk walk(cfg, props, scene, w, rays[i], std::uint32_t(i), timed, res, lists ? per_ray[i] : w.no_lists);
    walk.run();
    ++w.stats.rays;
  });

  EffectsStats& s = res.stats;
  for (const Worker& w : workers) {
    const EffectsStats& x = w.stats;
    s.rays += x.rays, s.hits_traversed += x.hits_traversed, s.hits_existing += x.hits_existing;
    s.rays_settled_early += x.rays_settled_early, s.partition_groups += x.partition_groups;
    s.partitions_consumed += x.partitions_consumed, s.csg_evaluations += x.csg_evaluations;
    for (std::size_t e = 0; e < kEffectCount; ++e) s.updates[e] += x.updates[e], s.seconds_effect[e] += x.seconds_effect[e];
    s.unclosed += x.unclosed, s.unmatched_leaves += x.unmatched_leaves, s.timed_rays += x.timed_rays;
    s.seconds_audit += x.seconds_audit, s.seconds_traversal += x.seconds_traversal;
    s.seconds_partitions += x.seconds_partitions;
  }
  if (s.timed_rays > 0) {  // extrapolate the timed rays to all rays
    const double scale = double(s.rays) / double(s.timed_rays);
    s.seconds_traversal *= scale;
    s.seconds_partitions *= scale;
    for (double& e : s.seconds_effect) e *= scale;
  }
  for (RayLists& l : per_ray) {
    res.overlap_intervals.insert(res.overlap_intervals.end(), l.overlaps.begin(), l.overlaps.end());
    const auto base = std::uint32_t(res.class_solids.size());
    for (ClassInterval c : l.intervals) {
      c.first += base;
      res.class_intervals.push_back(c);
    }
    res.class_solids.insert(res.class_solids.end(), l.solids.begin(), l.solids.end());
  }
  s.seconds_wall = std::chrono::duration<double>(Clock::now() - t0).count();
  return res;
}

}  // namespace pierce::analysis
