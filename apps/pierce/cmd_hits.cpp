// `pierce hits MODEL... --rays RAYS --kernel K`: every hit of every ray, as CSV; with `--kernel all`,
// a table comparing every kernel with the exact consensus.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

#include "command.h"
#include "hit_diff.h"
#include "hits_csv.h"
#include "interrupt.h"
#include "model_args.h"
#include "output_file.h"
#include "picture.h"
#include "pierce/error.h"
#include "pierce/io/ray_source.h"
#include "pierce/kernel.h"
#include "pierce/kernel_names.h"
#include "progress.h"

namespace pierce::cli {

namespace {

struct HitsOptions {
  ModelArgs model;
  std::string rays;
  std::string kernel;
  std::size_t max_hits = 0;
  std::string out;
  std::string json;  // --kernel all: the table as JSON (bench/plot_cost.py draws it)
  bool force = false;
  bool progress = false;
  // --heatmap: one ray per pixel, coloured by its traversal work (Gribble 2016), instead of --rays.
  std::string heatmap, heatmap_count = "steps", png_size = "800x600", png_view = "-1,-1,-1";
};

// Exit code when an exact kernel disagrees with the consensus.
constexpr int kExitExactDisagreement = 3;

using Results = HitBatch;

std::string kernel_list() { return kernel_name_list() + ", all"; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs one kernel over all rays with a progress bar; false if cancelled.
bool trace(const Accel& accel, KernelKind kind, const std::vector<Ray>& rays, const HitsOptions& o, Results& out,
           double& secs) {
  ProgressBar bar(std::string(kernel_name(kind)), rays.size(), o.progress);
  const auto t0 = std::chrono::steady_clock::now();
  const bool done = trace_batch(accel, kind, rays, o.max_hits, out, {}, [&](std::size_t n, std::size_t) { return bar.update(n); });
  secs = seconds_since(t0);
  bar.finish();
  return done && !interrupted();
}

// Writes results as CSV to o.out (or stdout); false if cancelled.
bool write_csv(const HitsOptions& o, std::size_t ray_count, const std::function<std::span<const Hit>(std::size_t)>& hits_of) {
  OutputFile out(o.out, o.force);
  if (!write_hits_csv(out.stream(), ray_count, hits_of, [] { return !interrupted(); })) return false;
  out.commit();
  return true;
}

int run_single(const Accel& accel, KernelKind kind, const std::vector<Ray>& rays, const HitsOptions& o) {
  Results results;
  double secs = 0;
  if (!trace(accel, kind, rays, o, results, secs)) return cancelled();
  if (!write_csv(o, rays.size(), [&](std::size_t i) { return results.of(i); })) return cancelled();
  return 0;
}

struct Row {
  KernelKind kind = KernelKind::restart;
  double secs = 0;
  std::size_t hits = 0;
  HitDiff diff;
};

// Rays on which one exact kernel's lists differ from the reference kernel's, sorted by ray.
using Deviations = std::vector<std::pair<std::size_t, std::vector<Hit>>>;

const std::vector<Hit>* find_deviation(const Deviations& d, std::size_t ray) {
  auto it = std::lower_bound(d.begin(), d.end(), ray, [](const auto& e, std::size_t r) { return e.first < r; });
  return it != d.end() && it->first == ray ? &it->second : nullptr;
}

void print_table(const std::vector<Row>& rows, std::size_t ray_count) {
  std::printf("%-16s %5s %9s %9s %10s %11s %8s %7s %10s %12s %9s\n", "kernel", "exact", "time(s)", "Mrays/s", "hits",
              "rays-differ", "missing", "extra", "duplicated", "out-of-order", "t-differs");
  for (const Row& r : rows) {
    const double mrays = r.secs > 0 ? double(ray_count) / r.secs * 1e-6 : 0.0;
    std::printf("%-16s %5s %9.3f %9.2f %10zu %11zu %8zu %7zu %10zu %12zu %9zu\n",
                std::string(kernel_name(r.kind)).c_str(), is_exact(r.kind) ? "yes" : "no", r.secs, mrays, r.hits,
                r.diff.rays_differ, r.diff.missing, r.diff.extra, r.diff.duplicated, r.diff.out_of_order,
                r.diff.t_differs);
  }
}

// The table of run_all as JSON: per kernel its time and its differences from the consensus.
void write_table_json(const HitsOptions& o, const std::vector<Row>& rows, std::size_t ray_count,
                      std::size_t consensus_hits) {
  nlohmann::ordered_json j;
  j["source"] = "pierce hits --kernel all";
  j["rays"] = ray_count;
  j["max_hits"] = o.max_hits == 0 ? nlohmann::ordered_json("all") : nlohmann::ordered_json(o.max_hits);
  j["consensus_hits"] = consensus_hits;
  j["kernels"] = nlohmann::ordered_json::array();
  for (const Row& r : rows)
    j["kernels"].push_back({{"kernel", kernel_name(r.kind)},
                            {"exact", is_exact(r.kind)},
                            {"seconds", r.secs},
                            {"ns_per_ray", ray_count ? r.secs * 1e9 / double(ray_count) : 0.0},
                            {"hits", r.hits},
                            {"rays_differ", r.diff.rays_differ},
                            {"missing", r.diff.missing},
                            {"extra", r.diff.extra},
                            {"duplicated", r.diff.duplicated},
                            {"out_of_order", r.diff.out_of_order},
                            {"t_differs", r.diff.t_differs}});
  OutputFile out(o.json, o.force);
  const std::string text = j.dump(2) + "\n";
  if (std::fwrite(text.data(), 1, text.size(), out.stream()) != text.size())
    throw std::runtime_error("--json " + o.json + ": write failed");
  out.commit();
}

// Every kernel on the same rays. The consensus per ray is the list most exact kernels return.
// Memory stays near two kernels' results: the first exact kernel's results are the reference,
// later exact kernels keep only the rays where they deviate from it, and inexact kernels are
// compared as soon as they finish.
int run_all(const Accel& accel, const std::vector<Ray>& rays, const HitsOptions& o) {
  std::vector<KernelKind> exact, inexact;
  for (KernelKind k : kAllKernels) {
    if (const std::string why = unsupported_reason(accel, k); !why.empty()) {
      std::fprintf(stderr, "pierce hits: skipping %s\n", why.c_str());
      continue;
    }
    (is_exact(k) ? exact : inexact).push_back(k);
  }
  const std::size_t n = rays.size();
  std::vector<Row> rows;
  Results reference;
  std::vector<Deviations> deviations(exact.size());
  for (std::size_t e = 0; e < exact.size(); ++e) {
    Results res;
    Row row;
    row.kind = exact[e];
    if (!trace(accel, exact[e], rays, o, res, row.secs)) return cancelled();
    row.hits = res.hits.size();
    rows.push_back(row);
    if (e == 0) {
      reference = std::move(res);
      continue;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (!same_hits(reference.of(i), res.of(i))) deviations[e].emplace_back(i, std::vector<Hit>(res.of(i).begin(), res.of(i).end()));
  }

  // Consensus where some exact kernel deviates from the reference.
  std::vector<std::size_t> contested;
  for (const Deviations& d : deviations)
    for (const auto& [ray, list] : d) contested.push_back(ray);
  std::sort(contested.begin(), contested.end());
  contested.erase(std::unique(contested.begin(), contested.end()), contested.end());
  std::vector<std::pair<std::size_t, std::vector<Hit>>> overrides;  // consensus != reference, by ray
  std::size_t no_majority = 0;
  auto list_of = [&](std::size_t e, std::size_t ray) -> std::span<const Hit> {
    const std::vector<Hit>* d = find_deviation(deviations[e], ray);
    return d ? std::span<const Hit>(*d) : reference.of(ray);
  };
  for (std::size_t ray : contested) {
    std::vector<std::span<const Hit>> lists;
    for (std::size_t e = 0; e < exact.size(); ++e) lists.push_back(list_of(e, ray));
    bool majority = false;
    const std::size_t winner = consensus_index(lists, majority);
    no_majority += !majority;
    if (!same_hits(lists[winner], reference.of(ray)))
      overrides.emplace_back(ray, std::vector<Hit>(lists[winner].begin(), lists[winner].end()));
  }
  auto consensus = [&](std::size_t ray) -> std::span<const Hit> {
    const std::vector<Hit>* c = find_deviation(overrides, ray);
    return c ? std::span<const Hit>(*c) : reference.of(ray);
  };

  // Exact kernels can only differ from the consensus on contested rays.
  for (std::size_t e = 0; e < exact.size(); ++e) {
    rows[e].diff.rays = n;
    for (std::size_t ray : contested) {
      HitDiff d;
      diff_hits(consensus(ray), list_of(e, ray), d);
      d.rays = 0;
      rows[e].diff += d;
    }
  }
  for (KernelKind k : inexact) {
    Results res;
    Row row;
    row.kind = k;
    if (!trace(accel, k, rays, o, res, row.secs)) return cancelled();
    row.hits = res.hits.size();
    for (std::size_t i = 0; i < n; ++i) diff_hits(consensus(i), res.of(i), row.diff);
    rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    auto pos = [](KernelKind k) { return std::find(std::begin(kAllKernels), std::end(kAllKernels), k) - std::begin(kAllKernels); };
    return pos(a.kind) < pos(b.kind);
  });

  std::size_t consensus_hits = reference.hits.size();
  for (const auto& [ray, list] : overrides) consensus_hits += list.size() - reference.of(ray).size();
  std::printf("%zu rays, exact consensus %zu hits (majority of %zu exact kernels)\n", n, consensus_hits, exact.size());
  print_table(rows, n);
  if (no_majority) std::printf("%zu rays have no majority among the exact kernels\n", no_majority);
  std::string disagreeing;
  for (const Row& r : rows)
    if (is_exact(r.kind) && !r.diff.clean()) disagreeing += (disagreeing.empty() ? "" : ", ") + std::string(kernel_name(r.kind));
  if (disagreeing.empty())
    std::printf("all %zu exact kernels agree on all %zu rays\n", exact.size(), n);
  else
    std::printf("EXACT KERNELS DISAGREE: %s\n", disagreeing.c_str());
  std::fflush(stdout);

  if (!o.json.empty()) write_table_json(o, rows, n, consensus_hits);
  if (!o.out.empty() && !write_csv(o, n, consensus)) return cancelled();
  return disagreeing.empty() ? 0 : kExitExactDisagreement;
}

std::string cost_metric_list() { return enum_name_list<CostMetric>(); }

// --heatmap: the kernel's counting variant on one ray per pixel.
int run_heatmap(const Accel& accel, KernelKind kind, CostMetric metric, const FalseColourOptions& fo,
                const HitsOptions& o) {
  HeatmapStats stats;
  const auto img = write_picture(o.heatmap, o.force, o.progress, fo.height, [&](const Progress& p) {
    return render_cost_heatmap(accel, kind, o.max_hits, metric, fo, stats, p);
  });
  if (!img) return cancelled();
  const std::string hits = o.max_hits == 0 ? "all hits" : "up to " + std::to_string(o.max_hits) + " hits";
  std::printf("heat map %s: %dx%d, kernel %s, %s per ray; %s per ray: mean %.2f (%.2f over the %zu rays "
              "that do work), max %.0f; colour range %g .. %g (white: no work)\n",
              o.heatmap.c_str(), img->width, img->height, std::string(kernel_name(kind)).c_str(), hits.c_str(),
              std::string(cost_metric_name(metric)).c_str(), stats.mean, stats.mean_over_scene, img->pixels_hit,
              stats.max, img->range_min, img->range_max);
  if (uses_embree(kind))
    std::printf("note: %s runs in Embree, whose node visits are not visible: its steps are rtcIntersect1 calls, its "
                "primitive tests Pierce's exact tests in Embree's callbacks\n",
                std::string(kernel_name(kind)).c_str());
  return 0;
}

int run_hits(const HitsOptions& o) {
  InterruptGuard guard;
  const bool all = o.kernel == "all";
  const std::optional<KernelKind> kind = parse_kernel(o.kernel);
  if (!all && !kind) throw InputError("unknown kernel '" + o.kernel + "' (expected one of: " + kernel_list() + ")");
  const bool heatmap = !o.heatmap.empty();
  if (heatmap == !o.rays.empty())
    throw InputError(heatmap ? "--heatmap shoots its own rays (one per pixel): drop --rays"
                             : "--rays is required (or --heatmap FILE.png for a traversal heat map)");
  std::optional<CostMetric> metric;
  FalseColourOptions fo;
  if (heatmap) {
    if (all) throw InputError("--heatmap shows one kernel's work: choose it with --kernel (not all)");
    if (!o.out.empty() || !o.json.empty()) throw InputError("--heatmap writes a picture; drop --out and --json");
    metric = parse_cost_metric(o.heatmap_count);
    if (!metric)
      throw InputError("--heatmap-count '" + o.heatmap_count + "': expected one of " + cost_metric_list());
    parse_picture_size("--png-size", o.png_size, fo.width, fo.height);
    fo.view_dir = parse_view_direction("--png-view", o.png_view);
    OutputFile::check_target(o.heatmap, o.force);
  }
  OutputFile::check_target(o.out, o.force);  // before any long work
  if (!o.json.empty()) {
    if (!all) throw InputError("--json is the table of --kernel all; use --out for one kernel's hits");
    OutputFile::check_target(o.json, o.force);
  }

  Scene scene;
  load_models(scene, o.model);
  if (interrupted()) return cancelled();
  const std::vector<Ray> rays = heatmap ? std::vector<Ray>{} : load_rays(o.rays, scene);
  if (interrupted()) return cancelled();
  const auto t0 = std::chrono::steady_clock::now();
  const Accel accel(scene);
  if (heatmap) {
    if (std::string why = unsupported_reason(accel, *kind); !why.empty()) throw InputError(why);
    return run_heatmap(accel, *kind, *metric, fo, o);
  }
  if (all)
    std::printf("%zu geometries, %zu triangles (%zu degenerate); Pierce's BVH built in %.3f s (Embree's scenes on first use)\n",
                scene.geometries().size(), scene.triangle_count(), scene.degenerate_count(), seconds_since(t0));
  if (interrupted()) return cancelled();
  return all ? run_all(accel, rays, o) : run_single(accel, *kind, rays, o);
}

}  // namespace

std::function<int()> register_hits(CLI::App& app) {
  // Geometry ids follow argument order: one per OBJ o/g group, one per CAD solid.
  const auto [opts, cmd] = add_model_command<HitsOptions>(
      app, "hits", "Every surface each ray crosses, in order (CSV: ray,t,geom,prim,u,v,enter)");
  cmd->add_option("--rays", opts->rays,
                  "CSV file ox,oy,oz,dx,dy,dz[,tmin,tmax], or grid:axis=x|y|z,n=N[,dir=-], or random:n=N[,seed=S] "
                  "(required unless --heatmap)");
  cmd->add_option("--kernel", opts->kernel, "Kernel: " + kernel_list())->required();
  cmd->add_option("--max-hits", opts->max_hits, "At most N hits per ray (0 = all)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", opts->out, "Write the CSV here instead of stdout (with --kernel all: the consensus hits)");
  cmd->add_option("--json", opts->json,
                  "With --kernel all: also write the table (time and differences per kernel) as JSON here");
  add_force_and_progress_flags(cmd, opts->force, opts->progress, "an existing --out, --json or --heatmap file");
  cmd->add_option("--heatmap", opts->heatmap,
                  "Instead of --rays: a PNG heat map of the kernel's traversal work, one ray per pixel "
                  "(Gribble 2016), for --max-hits hits per ray");
  cmd->add_option("--heatmap-count", opts->heatmap_count, "What the heat map counts: " + cost_metric_list())
      ->capture_default_str();
  add_camera_options(cmd, opts->png_size, opts->png_view, "Heat map");
  return [opts] { return run_hits(*opts); };
}

}  // namespace pierce::cli
