// pierce_bench_xray: the X-ray effect (Beer-Lambert with early exit) on absorbing plate stacks,
// traced with `queue` (resumable: stops where the ray's energy falls below the threshold),
// `filter` (all hits found up front, then consumed) and `restart` (re-traverses from the root for
// every hit), plus the other exact kernels for reference. Reports wall time (median of --reps),
// rays/s, hits traversed by the effect and hits existing along the rays.
// A benchmark, not a test: it reports, it never asserts a speed.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench_machine.h"
#include "bench_main.h"
#include "bench_timing.h"
#include "pierce/analysis/effects.h"
#include "pierce/generators.h"

namespace pierce::bench {
namespace {

using namespace pierce::analysis;

struct Case {
  std::string name;
  int plates;
  double mu;         // per unit length; plates are 0.1 thick
  double threshold;  // transmission below which a ray is settled
};

struct Row {
  std::string scene;
  KernelKind kernel;
  double seconds = 0;
  std::uint64_t rays = 0, traversed = 0, existing = 0, settled_early = 0;
};

std::vector<Ray> grid_rays(int n) {
  std::vector<Ray> rays;
  rays.reserve(std::size_t(n) * std::size_t(n));
  // Slightly oblique so rays cross plates at varying depths and some leave through the sides.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) rays.push_back(Ray{{(i + 0.5) / n, (j + 0.5) / n, -1}, {0.05, 0.02, 1}});
  return rays;
}

int run(int argc, char** argv) {
  CLI::App app{"X-ray effect with early exit: queue vs filter vs restart"};
  bool quick = false, force = false;
  int n = 512, reps = 3, threads = int(std::max(1u, std::thread::hardware_concurrency()));
  std::string json_path;
  app.add_option("--n", n, "rays per side of the ray grid (default 512; 32 with --quick)")->check(CLI::Range(1, 8192));
  app.add_option("--reps", reps, "timed repetitions, median reported (default 3; 1 with --quick)")->check(CLI::Range(1, 100));
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  app.add_flag("--quick", quick, "small grid, one repetition (smoke run)");
  app.add_option("--json", json_path, "also write every number to this JSON file");
  app.add_flag("--force", force, "overwrite the --json file if it exists");
  CLI11_PARSE(app, argc, argv);
  if (quick) n = std::min(n, 32), reps = 1;
  if (!json_path.empty() && std::filesystem::exists(json_path) && !force) {
    std::cerr << "pierce_bench_xray: " << json_path << " exists; use --force to overwrite\n";
    return 2;
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  const std::vector<Case> cases = {
      {"plates20 mu=5 T<1e-3", 20, 5.0, 1e-3},     // settles after ~14 of 20 plates
      {"plates200 mu=5 T<1e-3", 200, 5.0, 1e-3},   // settles after ~14 of 200 plates
      {"plates200 mu=0.1 T<1e-3", 200, 0.1, 1e-3}, // never settles: every hit is needed
  };
  const KernelKind kernels[] = {KernelKind::queue,    KernelKind::filter,        KernelKind::restart,
                                KernelKind::nodecull, KernelKind::embree_filter, KernelKind::embree_restart};
  const std::vector<Ray> rays = grid_rays(n);
  std::vector<Row> rows;
  std::printf("pierce_bench_xray: %d x %d rays, %d threads, median of %d, %s, load average %s\n", n, n, threads,
              reps, cpu_model().c_str(), load_average().c_str());
  std::printf("%-26s %-16s %9s %9s %14s %14s %7s %12s\n", "scene", "kernel", "time(s)", "Mrays/s", "hits traversed",
              "hits existing", "saved", "rays settled");
  for (const Case& c : cases) {
    const Scene scene = gen::to_scene(gen::stacked_plates(c.plates, 1.0, 0.1));
    const Accel accel(scene);
    EffectsConfig cfg;
    cfg.enable(Effect::xray);
    cfg.materials = {Material{"absorber", 1.0, c.mu, 0, {}, 0}};
    cfg.solid_material.assign(scene.geometries().size(), 0);
    cfg.xray_threshold = c.threshold;
    cfg.timing_stride = 0;  // no per-effect clocks in the timed runs
    // Hits existing: one audited run (not timed).
    cfg.audit = true;
    const std::uint64_t existing = run_effects(accel, rays, cfg).stats.hits_existing;
    cfg.audit = false;
    for (KernelKind k : kernels) {
      cfg.kernel = k;
      Row row{c.name, k};
      std::vector<double> times;
      for (int r = 0; r < reps; ++r) {
        const auto t0 = Clock::now();
        const EffectsResult res = run_effects(accel, rays, cfg);
        times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
        row.traversed = res.stats.hits_traversed;
        row.settled_early = res.stats.rays_settled_early;
      }
      row.seconds = median(times);
      row.rays = rays.size();
      row.existing = existing;
      rows.push_back(row);
      std::printf("%-26s %-16s %9.4f %9.3f %14llu %14llu %6.1f%% %12llu\n", c.name.c_str(),
                  std::string(kernel_name(k)).c_str(), row.seconds, double(row.rays) / row.seconds * 1e-6,
                  static_cast<unsigned long long>(row.traversed), static_cast<unsigned long long>(row.existing),
                  row.existing ? 100.0 * (1.0 - double(row.traversed) / double(row.existing)) : 0.0,
                  static_cast<unsigned long long>(row.settled_early));
      std::fflush(stdout);
    }
  }
  if (!json_path.empty()) {
    nlohmann::ordered_json j;
    j["grid"] = n;
    j["threads"] = threads;
    j["reps"] = reps;
    j["cpu"] = cpu_model();
    j["load_average_at_end"] = load_average();
    auto& out = j["results"] = nlohmann::ordered_json::array();
    for (const Row& r : rows)
      out.push_back({{"scene", r.scene},
                     {"kernel", kernel_name(r.kernel)},
                     {"seconds", r.seconds},
                     {"rays", r.rays},
                     {"hits_traversed", r.traversed},
                     {"hits_existing", r.existing},
                     {"rays_settled_early", r.settled_early}});
    std::ofstream(json_path) << j.dump(1) << "\n";
  }
  return 0;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
