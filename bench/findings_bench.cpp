// pierce_bench_findings: what the findings add to the analyses they come from, on the path the
// CLI takes. Thin regions (ThicknessOptions::min_thickness: grouping, exits and the refined
// area) on `pierce thickness`'s 1.64 M-triangle shell (gen::hollow_sphere(8, 7), per vertex) and
// on the same shell with its inner sphere off centre, at thresholds that flag 1 % and 50 % of
// the samples; and the contact / clash / clearance pairs (classify_solid_pairs with a clearance,
// without and with the per-triangle Clearance map) after `pierce overlaps`'s coplanar search and
// axis-grid rays on a 36-solid assembly (a row of face-touching boxes and 30 bumpy blobs that
// clash or nearly touch). Each job runs with and without its findings, interleaved repetition by
// repetition; medians and the ratios are printed. A benchmark: it reports, it never asserts a
// speed.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench_machine.h"
#include "bench_main.h"
#include "bench_timing.h"
#include "pierce/analysis/coplanar.h"
#include "pierce/analysis/ray_overlaps.h"
#include "pierce/analysis/solid_pairs.h"
#include "pierce/analysis/thickness.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce::bench {
namespace {

struct Options {
  int reps = 3;
  int threads = 0;  // 0: all
  bool quick = false;
};

struct Job {
  Job(std::string n, std::function<std::string()> r) : name(std::move(n)), run(std::move(r)) {}
  std::string name;
  std::function<std::string()> run;  // returns what it found, printed beside the time
  std::vector<double> seconds;
  std::string found;
};

// Runs every job once per repetition, in turn, so a slow stretch of the machine falls on all.
void run_interleaved(std::vector<Job>& jobs, int reps) {
  for (int r = 0; r < reps; ++r)
    for (Job& j : jobs) {
      const auto t0 = Clock::now();
      j.found = j.run();
      j.seconds.push_back(seconds_since(t0));
    }
}

void print_jobs(const std::vector<Job>& jobs) {
  const double base = median(jobs.front().seconds);
  std::printf("    %-44s %10s %8s   %s\n", "job", "s", "ratio", "found");
  for (const Job& j : jobs) {
    const double s = median(j.seconds);
    std::printf("    %-44s %10.3f %8.2f   %s\n", j.name.c_str(), s, s / base, j.found.c_str());
  }
}

// The value below which `share` of the finite thicknesses lie.
double threshold_at(const analysis::ThicknessResult& r, double share) {
  std::vector<double> t;
  for (double v : r.thickness)
    if (std::isfinite(v)) t.push_back(v);
  std::sort(t.begin(), t.end());
  return t.empty() ? 0.0 : t[std::min(t.size() - 1, std::size_t(share * double(t.size())))];
}

// Thin regions on one shell at thresholds that flag 1 % and 50 % of its samples.
void bench_regions(const std::string& what, const gen::Mesh& shell, int reps) {
  const Scene scene = gen::to_scene({shell});
  const Accel accel(scene);
  analysis::ThicknessOptions plain;
  const analysis::ThicknessResult first = analysis::compute_thickness(accel, plain);
  std::printf("\nthin regions: %s, %zu triangles, %zu samples per vertex\n", what.c_str(), scene.triangle_count(),
              first.size());
  std::vector<Job> jobs;
  jobs.emplace_back("thickness", [&] {
                    const analysis::ThicknessResult r = analysis::compute_thickness(accel, plain);
                    return std::to_string(r.size()) + " samples";
                  });
  for (const double share : {0.01, 0.5}) {
    analysis::ThicknessOptions with = plain;
    with.min_thickness = threshold_at(first, share);
    char name[96];
    std::snprintf(name, sizeof name, "thickness + regions, T = %.6g (%g %% thin)", with.min_thickness, 100 * share);
    jobs.emplace_back(name, [&accel, with] {
                      const analysis::ThicknessResult r = analysis::compute_thickness(accel, with);
                      return std::to_string(r.thin_regions.size()) + " thin regions";
                    });
  }
  run_interleaved(jobs, reps);
  print_jobs(jobs);
}

void bench_regions(const Options& o) {
  const int outer = o.quick ? 5 : 8, inner = o.quick ? 4 : 7;
  // A uniform 0.05 wall: its thickness varies only with the inner sphere's facets, so a threshold
  // inside that variation flags scattered spots, the most regions for the samples.
  bench_regions("hollow sphere, uniform wall (faceting spots)", gen::hollow_sphere(outer, inner), o.reps);
  // The inner sphere moved off centre: the wall runs from 0.02 to 0.08, and a threshold flags a cap.
  gen::Mesh offset = gen::merged(gen::icosphere(outer), gen::flipped(gen::icosphere(inner, 0.95, {0.03, 0, 0})));
  bench_regions("hollow sphere, wall 0.02 to 0.08 (a thin cap)", offset, o.reps);
}

// 6 face-touching boxes in a row, then 30 blobs on a 2.1 grid: radius 1 with bumps of up to a
// quarter, so neighbours clash or pass within the clearance.
std::vector<gen::Mesh> assembly(bool quick) {
  std::vector<gen::Mesh> solids;
  constexpr double kPitch = 2.1;
  for (int i = 0; i < 6; ++i)
    solids.push_back(gen::box({kPitch * i - 1, -1, -1}, {kPitch * (i + 1) - 1, 1, 1}, "box" + std::to_string(i)));
  for (int j = 1; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      gen::Mesh b = gen::translated(gen::blob(quick ? 2 : 4, std::uint64_t(6 * j + i)), {kPitch * i, kPitch * j, 0});
      b.name = "blob" + std::to_string(6 * j + i);
      solids.push_back(std::move(b));
    }
  return solids;
}

void bench_pairs(const Options& o) {
  const Scene scene = gen::to_scene(assembly(o.quick));
  const Accel accel(scene);
  const int grid_n = o.quick ? 32 : 128;  // `pierce overlaps`' default rays: axes:n=128
  const std::vector<Ray> rays = analysis::axis_grid_rays(scene.bounds(), grid_n);
  constexpr double kClearance = 0.2;
  std::printf("\ncontact / clash / clearance: %zu solids, %zu triangles, %zu rays (axes:n=%d), clearance %g\n",
              scene.geometries().size(), scene.triangle_count(), rays.size(), grid_n, kClearance);
  auto overlaps = [&] {
    const analysis::CoplanarReport cop = analysis::find_coplanar_overlaps(scene, {});
    const analysis::RayOverlapReport rep = analysis::analyse_ray_overlaps(accel, rays, {});
    return std::pair(cop, rep);
  };
  std::vector<Job> jobs;
  jobs.emplace_back("overlaps (coplanar search + rays)", [&] {
                    const auto [cop, rep] = overlaps();
                    return std::to_string(rep.interferences.size()) + " interfering pairs";
                  });
  auto pairs_job = [&](bool triangle_clearance) {
    return [&, triangle_clearance] {
      const auto [cop, rep] = overlaps();
      const analysis::SolidPairReport pairs =
          analysis::classify_solid_pairs(accel, cop, rep, grid_n, kClearance, triangle_clearance);
      std::size_t count[3] = {};
      for (const analysis::SolidPair& p : pairs.pairs) ++count[int(p.kind)];
      return std::to_string(count[int(analysis::PairKind::clash)]) + " clash, " +
             std::to_string(count[int(analysis::PairKind::contact)]) + " contact, " +
             std::to_string(count[int(analysis::PairKind::clearance)]) + " clearance";
    };
  };
  jobs.emplace_back("overlaps + pairs", pairs_job(false));
  jobs.emplace_back("overlaps + pairs + Clearance map", pairs_job(true));
  run_interleaved(jobs, o.reps);
  print_jobs(jobs);
}

int run(int argc, char** argv) {
  CLI::App app{"What thin regions and solid pairs add to pierce thickness and pierce overlaps"};
  Options o;
  app.add_option("--reps", o.reps, "Repetitions per job (medians)")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--threads", o.threads, "Threads (0 = all)")->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_flag("--quick", o.quick, "Small models, one repetition (a smoke run)");
  CLI11_PARSE(app, argc, argv);
  if (o.quick) o.reps = 1;
  if (o.threads == 0) o.threads = tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(o.threads));
  std::printf("pierce_bench_findings\nmachine: %s, %d threads used, load average %s\n", cpu_model().c_str(),
              o.threads, load_average().c_str());
  const StealMeter steal;
  bench_regions(o);
  bench_pairs(o);
  std::printf("\n");
  print_run_end(steal);
  return 0;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
