// `pierce gqa MODEL... [--tol REL] [--json out.json]`: volume, centroid and surface crossings of
// every solid (and of --csg regions) from ray grids along x, y and z, refined until successive
// estimates agree within the tolerance; overlaps and gaps between solids (BRL-CAD gqa).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>

#include <nlohmann/json.hpp>

#include "command.h"
#include "interrupt.h"
#include "json_text.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/analysis/gqa.h"
#include "pierce/error.h"
#include "progress.h"

namespace pierce::cli {

namespace {

using namespace pierce::analysis;

struct GqaCli {
  ModelArgs model;
  double tol = 1e-3;
  int start_n = 0, max_n = 1024;
  std::uint64_t seed = 1;
  double gap_min = 0, gap_max = std::numeric_limits<double>::infinity();
  std::vector<std::string> csg;
  std::string kernel{kernel_name(kDefaultKernel)};
  std::string json;
  bool force = false, progress = false;
};

// A point, or null where there is none (the centroid of nothing).
nlohmann::ordered_json vec(Vec3d p) { return std::isfinite(p.x) ? json_point(p) : nlohmann::ordered_json(); }

nlohmann::ordered_json pair_json(const Scene& s, const GqaPair& p, bool overlap) {
  nlohmann::ordered_json j = {{"a", solid_label(s, p.a)},
                              {"b", solid_label(s, p.b)},
                              {"a_id", p.a},
                              {"b_id", p.b},
                              {"count", p.count},
                              {"max_depth", p.max_depth},
                              {"at", vec(p.at)},
                              {"axis_max_depth", p.axis_max_depth}};
  if (overlap) {
    j["penetration"] = p.penetration;
    j["volume"] = p.volume;
  }
  return j;
}

nlohmann::ordered_json quantities_json(const GqaQuantities& q) {
  return {{"name", q.name},
          {"volume", q.volume},
          {"centroid", vec(q.centroid)},
          {"axis_volume", q.axis_volume},
          {"crossings", q.crossings},
          {"change", json_or_null(q.change)},
          {"std_error", q.std_error}};
}

void write_json(std::FILE* f, const Scene& s, const GqaResult& r) {
  nlohmann::ordered_json j;
  j["tolerance"] = r.tolerance;
  j["converged"] = r.converged;
  j["grid_n"] = r.n;
  j["seed"] = r.seed;
  auto& passes = j["passes"] = nlohmann::ordered_json::array();
  for (const GqaPass& p : r.passes)
    passes.push_back({{"n", p.n},
                      {"rays", p.rays},
                      {"seconds", p.seconds},
                      {"worst_change", json_or_null(p.worst_change)},
                      {"worst", p.worst}});
  auto& solids = j["solids"] = nlohmann::ordered_json::array();
  for (std::uint32_t g = 0; g < r.solids.size(); ++g) {
    nlohmann::ordered_json q = quantities_json(r.solids[g]);
    q["name"] = solid_label(s, g);
    q["id"] = g;
    q["source"] = s.geometry(g).source;
    auto& ov = q["overlaps"] = nlohmann::ordered_json::array();
    for (const GqaPair& p : r.overlaps)
      if (p.a == g || p.b == g) ov.push_back(pair_json(s, p, true));
    solids.push_back(std::move(q));
  }
  auto& regions = j["regions"] = nlohmann::ordered_json::array();
  for (const GqaQuantities& q : r.regions) {
    nlohmann::ordered_json x = quantities_json(q);
    x["solid_ids"] = q.geoms;
    regions.push_back(std::move(x));
  }
  auto& ov = j["overlaps"] = nlohmann::ordered_json::array();
  for (const GqaPair& p : r.overlaps) ov.push_back(pair_json(s, p, true));
  auto& gaps = j["gaps"] = nlohmann::ordered_json::array();
  for (const GqaPair& p : r.gaps) gaps.push_back(pair_json(s, p, false));
  j["unmatched_leaves"] = r.unmatched_leaves;
  j["unclosed"] = r.unclosed;
  write_json_document(f, j);
}

void print_quantities(const char* kind, const std::string& name, const GqaQuantities& q) {
  std::printf("%-7s %-28s %14.8g  (%11.6g %11.6g %11.6g) %12llu %10.2e\n", kind, name.c_str(), q.volume, q.centroid.x,
              q.centroid.y, q.centroid.z, static_cast<unsigned long long>(q.crossings), q.change);
}

void print_report(const Scene& s, const GqaResult& r) {
  for (const GqaPass& p : r.passes)
    std::printf("pass n=%-5d %10llu rays %8.3f s  worst change %.3e%s%s\n", p.n,
                static_cast<unsigned long long>(p.rays), p.seconds, p.worst_change, p.worst.empty() ? "" : " (",
                p.worst.empty() ? "" : (p.worst + ")").c_str());
  std::printf("%-7s %-28s %14s  %-37s %12s %10s\n", "", "name", "volume", "centroid (x y z)", "crossings", "change");
  for (std::uint32_t g = 0; g < r.solids.size(); ++g) print_quantities("solid", solid_label(s, g), r.solids[g]);
  for (const GqaQuantities& q : r.regions) print_quantities("region", q.name, q);
  if (r.overlaps.empty()) std::printf("no overlaps\n");
  for (const GqaPair& p : r.overlaps)
    std::printf("OVERLAP %s <-> %s: %llu ray intervals, max depth %g at (%g, %g, %g), penetration ~%g, volume ~%g\n",
                solid_label(s, p.a).c_str(), solid_label(s, p.b).c_str(), static_cast<unsigned long long>(p.count),
                p.max_depth, p.at.x, p.at.y, p.at.z, p.penetration, p.volume);
  if (r.gaps.empty()) std::printf("no gaps\n");
  for (const GqaPair& p : r.gaps)
    std::printf("GAP %s <-> %s: %llu ray intervals, largest %g at (%g, %g, %g)\n", solid_label(s, p.a).c_str(),
                solid_label(s, p.b).c_str(), static_cast<unsigned long long>(p.count), p.max_depth, p.at.x, p.at.y,
                p.at.z);
  std::printf("%s: grid %d, tolerance %g\n", r.converged ? "converged" : "NOT CONVERGED", r.n, r.tolerance);
}

int run_gqa_cmd(const GqaCli& o) {
  InterruptGuard guard;
  OutputFile::check_target(o.json, o.force);
  if (!o.json.empty() && o.json == "-") throw InputError("--json needs a file name");
  const KernelKind kernel = exact_kernel_option(o.kernel);
  if (!(o.tol > 0) || !(o.tol < 1)) throw InputError("--tol must be in (0, 1)");
  if (o.start_n > o.max_n) throw InputError("--start-n must not exceed --max-n");

  Scene scene;
  load_models(scene, o.model);
  if (interrupted()) return cancelled();
  GqaOptions go;
  go.tolerance = o.tol;
  go.start_n = o.start_n;
  go.max_n = o.max_n;
  go.seed = o.seed;
  go.kernel = kernel;
  go.gap_min = o.gap_min;
  go.gap_max = o.gap_max;
  for (const std::string& e : o.csg) go.regions.push_back(parse_csg(e, scene));
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  // One bar per pass, replaced when the grid size changes.
  LazyProgressBar progress("gqa", o.progress);
  const GqaResult r = run_gqa(accel, go, [&](int n, std::size_t d, std::size_t t) {
    return progress.update("gqa n=" + std::to_string(n), d, t);
  });
  progress.finish();
  if (!r.completed || interrupted()) return cancelled();
  if (r.unmatched_leaves || r.unclosed)
    std::cerr << "pierce: warning: open or inverted meshes: " << r.unmatched_leaves << " exits without entry, "
              << r.unclosed << " entries without exit in the last pass (they claim no volume)\n";
  print_report(scene, r);
  std::fflush(stdout);
  if (!r.converged)
    std::cerr << "pierce: warning: not converged within --max-n " << o.max_n << " (last worst change "
              << r.passes.back().worst_change << " on " << r.passes.back().worst << ")\n";
  if (o.json.empty()) return 0;
  return write_file(o.json, o.force, [&](std::FILE* out) { write_json(out, scene, r); });
}

}  // namespace

std::function<int()> register_gqa(CLI::App& app) {
  const auto [o, cmd] = add_model_command<GqaCli>(app,
      "gqa", "Volume, centroid and surface crossings per solid from refined ray grids; overlaps and gaps (like "
             "BRL-CAD gqa)");
  cmd->add_option("--tol", o->tol,
                  "Relative tolerance: refine until volumes change by at most this between passes, the three axes "
                  "agree, 3 estimated standard errors fit in it and centroids move by at most tol x scene diagonal")
      ->capture_default_str();
  cmd->add_option("--start-n", o->start_n, "First grid size per axis (0 = from the thinnest solid)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--max-n", o->max_n, "Largest grid size per axis")->check(CLI::Range(1, 32768))->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the rays' random positions within their grid cells (same seed, same result)")
      ->capture_default_str();
  cmd->add_option("--csg", o->csg, "Also measure this CSG expression (repeatable; docs/CSG.md)");
  cmd->add_option("--gap-min", o->gap_min, "Report only gaps longer than this (model units)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--gap-max", o->gap_max, "Report only gaps no longer than this (model units)")
      ->check(CLI::NonNegativeNumber);
  add_exact_kernel_option(cmd, o->kernel);
  cmd->add_option("--json", o->json, "Write the results as JSON to this file");
  add_force_and_progress_flags(cmd, o->force, o->progress, "an existing --json file");
  return [o] { return run_gqa_cmd(*o); };
}

}  // namespace pierce::cli
