// `pierce run SCENE.json`: runs the effects a scene file asks for (and only those), stopping each
// ray once its effects are settled; writes per-ray results, interval lists, images and a report
// (hits traversed vs hits existing, time per effect).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <set>

#include <nlohmann/json.hpp>

#include "command.h"
#include "csv_text.h"
#include "effect_scene.h"
#include "interrupt.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/error.h"
#include "pierce/render/image_writer.h"
#include "progress.h"

namespace pierce::cli {

namespace {

using namespace pierce::analysis;

struct RunCli {
  std::string scene;
  std::string kernel;
  std::string out_dir;
  std::string report;
  bool audit = false, force = false, progress = false;
};

std::string id(std::uint32_t g) { return g == kInvalidId ? "" : std::to_string(g); }

void write_rays_csv(std::FILE* f, const std::vector<Ray>& rays, const EffectsConfig& cfg, const EffectsResult& r) {
  std::string head = "ray,ox,oy,oz,dx,dy,dz";
  if (cfg.on(Effect::first_hit)) head += ",first_distance,first_solid,first_obliquity";
  if (cfg.on(Effect::thickness)) head += ",thickness_solid,thickness_los,thickness_normal";
  if (cfg.on(Effect::transparency)) head += ",red,green,blue,alpha";
  if (cfg.on(Effect::xray)) head += ",transmission,xray_settled";
  if (cfg.on(Effect::penetration)) head += ",energy,stop_distance,stop_solid";
  if (cfg.on(Effect::overlaps)) head += ",overlaps,overlap_max_depth";
  if (cfg.on(Effect::classification)) head += ",los,areal_density";
  std::fprintf(f, "%s\n", head.c_str());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray& q = rays[i];
    std::string row = std::to_string(i) + "," + exact_number(q.org.x) + "," + exact_number(q.org.y) + "," +
                      exact_number(q.org.z) + "," + exact_number(q.dir.x) + "," + exact_number(q.dir.y) + "," +
                      exact_number(q.dir.z);
    if (cfg.on(Effect::first_hit))
      row += "," + exact_number(r.first_t[i]) + "," + id(r.first_geom[i]) + "," + exact_number(r.first_obliquity[i]);
    if (cfg.on(Effect::thickness))
      row += "," + id(r.thick_geom[i]) + "," + exact_number(r.thick_los[i]) + "," + exact_number(r.thick_normal[i]);
    if (cfg.on(Effect::transparency))
      for (int c = 0; c < 4; ++c) row += "," + exact_number(r.rgba[4 * i + std::size_t(c)]);
    if (cfg.on(Effect::xray))
      row += "," + exact_number(r.transmission[i]) + "," + std::to_string(int(r.xray_settled[i]));
    if (cfg.on(Effect::penetration))
      row += "," + exact_number(r.energy[i]) + "," + exact_number(r.stop_distance[i]) + "," + id(r.stop_geom[i]);
    if (cfg.on(Effect::overlaps))
      row += "," + std::to_string(r.overlap_count[i]) + "," + exact_number(r.overlap_max_depth[i]);
    if (cfg.on(Effect::classification))
      row += "," + exact_number(r.class_los[i]) + "," + exact_number(r.areal_density[i]);
    std::fprintf(f, "%s\n", row.c_str());
  }
}

void write_intervals_csv(std::FILE* f, const Scene& s, const EffectsConfig& cfg, const EffectsResult& r) {
  std::fputs("ray,kind,solids,t_in,t_out,los\n", f);
  auto names = [&](std::span<const std::uint32_t> ids) {
    std::string t;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      if (k) t += '+';
      t += solid_label(s, ids[k]);
    }
    return csv_field(t);
  };
  for (const ClassInterval& c : r.class_intervals) {
    const bool region = cfg.classification_csg.has_value();
    const std::string who =
        region ? csv_field(cfg.classification_csg->text)
               : names(std::span<const std::uint32_t>(r.class_solids).subspan(c.first, c.count));
    std::fprintf(f, "%u,%s,%s,%s,%s,%s\n", c.ray, region ? "region" : "partition", who.c_str(),
                 exact_number(c.t_in).c_str(), exact_number(c.t_out).c_str(), exact_number(c.los).c_str());
  }
  for (const OverlapInterval& o : r.overlap_intervals) {
    const std::uint32_t pair[2] = {o.a, o.b};
    std::fprintf(f, "%u,overlap,%s,%s,%s,%s\n", o.ray, names(pair).c_str(), exact_number(o.t_in).c_str(),
                 exact_number(o.t_out).c_str(), exact_number(o.depth).c_str());
  }
}

nlohmann::ordered_json report_json(const RunCli& o, const EffectSceneSpec& spec, const Scene& scene,
                                   const SceneRays& sr, const EffectsConfig& cfg, const EffectsResult& r) {
  const EffectsStats& s = r.stats;
  nlohmann::ordered_json j;
  j["scene"] = o.scene;
  j["models"] = spec.models;
  j["solids"] = scene.geometries().size();
  j["rays"] = sr.rays.size();
  if (sr.is_image()) j["image"] = {sr.width, sr.height};
  j["kernel"] = kernel_name(cfg.kernel);
  auto& eff = j["effects"] = nlohmann::ordered_json::array();
  for (Effect e : kAllEffects)
    if (cfg.on(e)) eff.push_back(effect_name(e));
  j["hits_traversed"] = s.hits_traversed;
  j["hits_existing"] = cfg.audit ? nlohmann::ordered_json(s.hits_existing) : nlohmann::ordered_json();
  j["rays_settled_early"] = s.rays_settled_early;
  j["work"] = {{"partition_groups", s.partition_groups},
               {"partitions_consumed", s.partitions_consumed},
               {"csg_evaluations", s.csg_evaluations}};
  auto& upd = j["work"]["effect_updates"] = nlohmann::ordered_json::object();
  for (Effect e : kAllEffects) upd[std::string(effect_name(e))] = s.updates[std::size_t(e)];
  j["seconds"] = {{"wall", s.seconds_wall},
                  {"audit", s.seconds_audit},
                  {"timed_rays", s.timed_rays},
                  {"traversal_cpu_estimate", s.seconds_traversal},
                  {"partitions_cpu_estimate", s.seconds_partitions}};
  auto& per = j["seconds"]["effect_cpu_estimate"] = nlohmann::ordered_json::object();
  for (Effect e : kAllEffects)
    if (cfg.on(e)) per[std::string(effect_name(e))] = s.seconds_effect[std::size_t(e)];
  j["bad_mesh"] = {{"unclosed", s.unclosed}, {"unmatched_leaves", s.unmatched_leaves}};
  if (cfg.on(Effect::xray)) {
    std::size_t settled = 0;
    double lo = 1, sum = 0;
    for (std::size_t i = 0; i < r.rays; ++i) settled += r.xray_settled[i], lo = std::min(lo, r.transmission[i]), sum += r.transmission[i];
    j["xray"] = {{"threshold", cfg.xray_threshold},
                 {"rays_below_threshold", settled},
                 {"min_transmission", lo},
                 {"mean_transmission", r.rays ? sum / double(r.rays) : 0.0}};
  }
  return j;
}

void print_report(const EffectSceneSpec& spec, const Scene& scene, const SceneRays& sr, const EffectsConfig& cfg,
                  const EffectsResult& r) {
  const EffectsStats& s = r.stats;
  std::printf("scene %s: %zu solids, %zu rays", spec.path.c_str(), scene.geometries().size(), sr.rays.size());
  if (sr.is_image()) std::printf(" (%d x %d image)", sr.width, sr.height);
  std::printf(", kernel %s\n", std::string(kernel_name(cfg.kernel)).c_str());
  if (cfg.audit)
    std::printf("hits traversed: %llu of %llu existing (%.1f%%), %llu never traversed\n",
                static_cast<unsigned long long>(s.hits_traversed), static_cast<unsigned long long>(s.hits_existing),
                s.hits_existing ? 100.0 * double(s.hits_traversed) / double(s.hits_existing) : 100.0,
                static_cast<unsigned long long>(s.hits_existing - std::min(s.hits_existing, s.hits_traversed)));
  else
    std::printf("hits traversed: %llu (run with --audit to count the hits that exist)\n",
                static_cast<unsigned long long>(s.hits_traversed));
  std::printf("rays settled early: %llu of %llu\n", static_cast<unsigned long long>(s.rays_settled_early),
              static_cast<unsigned long long>(s.rays));
  std::printf("wall time %.4f s%s; CPU time estimated from %llu timed rays:\n", s.seconds_wall,
              cfg.audit ? " (including the audit traversal)" : "", static_cast<unsigned long long>(s.timed_rays));
  std::printf("  %-16s %12s %12s\n", "work", "updates", "cpu (s)");
  std::printf("  %-16s %12llu %12.4f\n", "traversal", static_cast<unsigned long long>(s.hits_traversed),
              s.seconds_traversal);
  std::printf("  %-16s %12llu %12.4f\n", "partitions", static_cast<unsigned long long>(s.partition_groups),
              s.seconds_partitions);
  for (Effect e : kAllEffects)
    if (cfg.on(e))
      std::printf("  %-16s %12llu %12.4f\n", std::string(effect_name(e)).c_str(),
                  static_cast<unsigned long long>(s.updates[std::size_t(e)]), s.seconds_effect[std::size_t(e)]);
  if (s.unclosed || s.unmatched_leaves)
    std::printf("warning: open or inverted meshes: %llu entries without exit, %llu exits without entry\n",
                static_cast<unsigned long long>(s.unclosed), static_cast<unsigned long long>(s.unmatched_leaves));
}

void write_bytes(const std::string& path, bool force, const std::string& bytes) {
  OutputFile out(path, force);
  if (std::fwrite(bytes.data(), 1, bytes.size(), out.stream()) != bytes.size())
    throw std::runtime_error(path + ": write error");
  out.commit();
}

int run_scene(const RunCli& o) {
  InterruptGuard guard;
  EffectSceneSpec spec = load_effect_scene(o.scene);
  if (!o.out_dir.empty()) redirect_outputs(spec, o.out_dir);
  if (!o.report.empty()) spec.report_json = o.report;
  if (!o.kernel.empty()) {
    spec.config.kernel = exact_kernel_option(o.kernel);
  }
  spec.config.audit = o.audit;
  // Refuse clobbering before any long work, and two outputs with one name.
  std::set<std::string> seen;
  for (const std::string* p : {&spec.rays_csv, &spec.intervals_csv, &spec.report_json, &spec.xray_png,
                               &spec.xray_vti, &spec.transparency_png}) {
    if (p->empty()) continue;
    if (!seen.insert(std::filesystem::absolute(*p).lexically_normal().string()).second)
      throw InputError(o.scene + ": output '" + *p + "' is named twice");
    // Output directories named by the scene (or --out-dir) are created.
    const std::filesystem::path dir = std::filesystem::path(*p).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::exists(dir, ec) && !std::filesystem::create_directories(dir, ec))
      throw InputError(*p + ": cannot create directory " + dir.string() + ": " + ec.message());
    OutputFile::check_target(*p, o.force);
  }

  Scene scene;
  ModelArgs models;
  models.models = spec.models;
  load_models(scene, models);
  if (interrupted()) return cancelled();
  const EffectsConfig cfg = bind_effect_scene(spec, scene);
  const SceneRays sr = make_scene_rays(spec, scene);
  const bool images = !spec.xray_png.empty() || !spec.xray_vti.empty() || !spec.transparency_png.empty();
  if (images && !sr.is_image())
    throw InputError(o.scene + ": images need rays that form one: a grid generator or a camera");
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  ProgressBar bar("run", sr.rays.size(), o.progress);
  const EffectsResult r =
      run_effects(accel, sr.rays, cfg, [&](std::size_t done, std::size_t) { return bar.update(done); });
  bar.finish();
  if (!r.completed || interrupted()) return cancelled();
  print_report(spec, scene, sr, cfg, r);
  std::fflush(stdout);

  if (!spec.rays_csv.empty()) {
    OutputFile out(spec.rays_csv, o.force);
    write_rays_csv(out.stream(), sr.rays, cfg, r);
    out.commit();
  }
  if (!spec.intervals_csv.empty()) {
    OutputFile out(spec.intervals_csv, o.force);
    write_intervals_csv(out.stream(), scene, cfg, r);
    out.commit();
  }
  auto pixels = [&](int channels, const std::function<double(std::size_t ray, int c)>& value) {
    std::vector<double> v;
    v.reserve(std::size_t(sr.width) * std::size_t(sr.height) * std::size_t(channels));
    for (int row = 0; row < sr.height; ++row)
      for (int col = 0; col < sr.width; ++col)
        for (int c = 0; c < channels; ++c) v.push_back(value(sr.ray_of_pixel(col, row), c));
    return v;
  };
  if (!spec.xray_png.empty())
    write_bytes(spec.xray_png, o.force,
                encode_png(sr.width, sr.height, 1, 16, pixels(1, [&](std::size_t i, int) { return r.transmission[i]; })));
  if (!spec.xray_vti.empty()) {
    std::vector<VtiArray> arrays(2);
    arrays[0].name = "transmission";
    arrays[1].name = "settled";
    for (int row = sr.height - 1; row >= 0; --row)  // VTK counts rows from the bottom
      for (int col = 0; col < sr.width; ++col) {
        const std::size_t i = sr.ray_of_pixel(col, row);
        arrays[0].values.push_back(r.transmission[i]);
        arrays[1].values.push_back(r.xray_settled[i]);
      }
    write_bytes(spec.xray_vti, o.force,
                encode_vti(sr.width, sr.height, sr.plane_origin, sr.plane_spacing, arrays));
  }
  if (!spec.transparency_png.empty())
    write_bytes(spec.transparency_png, o.force,
                encode_png(sr.width, sr.height, 4, 8,
                           pixels(4, [&](std::size_t i, int c) { return double(r.rgba[4 * i + std::size_t(c)]); })));
  if (!spec.report_json.empty()) {
    const std::string text = report_json(o, spec, scene, sr, cfg, r).dump(1) + "\n";
    write_bytes(spec.report_json, o.force, text);
  }
  return interrupted() ? cancelled() : 0;
}

}  // namespace

std::function<int()> register_run(CLI::App& app) {
  const auto [o, cmd] = add_command<RunCli>(app,
      "run", "Run the effects a scene file requests (xray, transparency, penetration, thickness, overlaps, "
             "classification, first_hit), stopping each ray once they are settled (docs/CSG.md)");
  cmd->add_option("scene", o->scene, "Scene file (JSON)")->required();
  cmd->add_flag("--audit", o->audit,
                "Also count the hits that exist along the rays (a second, full traversal) to report the work saved");
  cmd->add_option("--kernel", o->kernel, "Exact kernel, overriding the scene's (default queue)");
  cmd->add_option("--out-dir", o->out_dir, "Write the scene's outputs under this directory instead of the scene's");
  cmd->add_option("--report", o->report, "Write the run report (JSON) here");
  add_force_and_progress_flags(cmd, o->force, o->progress, "existing output files");
  return [o] { return run_scene(*o); };
}

}  // namespace pierce::cli
