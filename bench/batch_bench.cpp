// pierce_bench_batch: the kernels where users call them. `pierce hits`, Python's `pierce.trace`
// and the VTK partitions filter all trace through trace_batch, which writes every ray's hits
// into one HitBatch. This bench times trace_batch with each exact own-BVH kernel and with
// `epsilon`, beside plain Embree code on the same rays (bench/embree_reference.h) that stores
// its answers the way a user's loop would (the first hit per ray in an array; all hits into one
// reused list per thread), and prints the ratios. Rows are interleaved repetition by repetition
// and medians are taken, so a slow stretch of the machine falls on every row alike.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "bench_machine.h"
#include "bench_main.h"
#include "bench_scenes.h"
#include "bench_timing.h"
#include "embree_reference.h"
#include "pierce/io/ray_source.h"
#include "pierce/kernel.h"

namespace pierce::bench {
namespace {

struct Options {
  std::vector<std::string> meshes;
  std::string ray_spec;  // rays as `pierce hits --rays` takes them, instead of the scene's random ones
  std::size_t rays = 200000;
  int reps = 5;
  int threads = 1;
  int blob_subdivisions = 6;
  bool quick = false;
};

struct Row {
  std::string name;
  std::size_t max_hits = 0;  // 0 = all
  bool reference = false;
  std::function<std::size_t()> run;  // returns the hits it found (so nothing is optimised away)
  std::vector<double> seconds;
};

constexpr std::size_t kGrain = 256;

// Plain Embree's first hit of every ray, stored per ray.
std::size_t reference_first_hits(const EmbreeReference& ref, const std::vector<Ray>& rays, std::vector<Hit>& out) {
  out.resize(rays.size());
  tbb::enumerable_thread_specific<std::size_t> found(0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), kGrain), [&](const auto& r) {
    std::size_t& n = found.local();
    for (std::size_t i = r.begin(); i != r.end(); ++i) n += ref.first_hit(rays[i], out[i]);
  });
  return found.combine([](std::size_t a, std::size_t b) { return a + b; });
}

// Plain Embree's all-hits filter on every ray, into one reused list per thread.
std::size_t reference_all_hits(const EmbreeReference& ref, const std::vector<Ray>& rays) {
  struct Local {
    std::vector<Hit> hits;
    std::size_t found = 0;
  };
  tbb::enumerable_thread_specific<Local> locals;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), kGrain), [&](const auto& r) {
    Local& l = locals.local();
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      l.hits.clear();
      ref.all_hits(rays[i], 0, l.hits);
      l.found += l.hits.size();
    }
  });
  std::size_t n = 0;
  for (const Local& l : locals) n += l.found;
  return n;
}

void bench_scene(BenchScene bs, const Options& o) {
  if (!o.ray_spec.empty()) {
    bs.rays = load_rays(o.ray_spec, bs.scene);
    bs.description += "; rays " + o.ray_spec;
  }
  const Accel accel(bs.scene);
  const EmbreeReference first(bs.scene, ReferenceUse::first_hit);
  const EmbreeReference filters(bs.scene, ReferenceUse::filters);
  std::vector<Hit> first_out;
  HitBatch batch;

  std::vector<Row> rows;
  rows.push_back({"embree first hit", 1, true, [&] { return reference_first_hits(first, bs.rays, first_out); }, {}});
  rows.push_back({"embree all-hits filter", 0, true, [&] { return reference_all_hits(filters, bs.rays); }, {}});
  for (const KernelKind k : kAllKernels) {
    if (uses_embree(k) && is_exact(k)) continue;  // the exact Embree kernels are not the product path
    for (const std::size_t n : {std::size_t(1), std::size_t(0)}) {
      if (!is_exact(k) && n == 0) continue;  // `epsilon` is compared on the first hit only
      rows.push_back({std::string(kernel_name(k)), n, false, [&accel, &bs, &batch, k, n] {
                        trace_batch(accel, k, bs.rays, n, batch);
                        return batch.hits.size();
                      },
                      {}});
    }
  }
  for (Row& r : rows) r.run();  // warm-up: builds what each kernel uses, touches the memory
  for (int rep = 0; rep < o.reps; ++rep)
    for (Row& r : rows) {
      const auto t0 = Clock::now();
      r.run();
      r.seconds.push_back(seconds_since(t0));
    }

  const double first_s = median(rows[0].seconds), all_s = median(rows[1].seconds);
  std::printf("\n%s: %s, %zu rays\n", bs.name.c_str(), bs.description.c_str(), bs.rays.size());
  std::printf("%-24s %8s %10s %10s %22s\n", "row", "N", "ms", "Mrays/s", "over plain Embree");
  for (const Row& r : rows) {
    const double s = median(r.seconds);
    const double over = r.reference ? 1.0 : s / (r.max_hits == 1 ? first_s : all_s);
    std::printf("%-24s %8s %10.2f %10.2f %13.2f (%s)\n", r.name.c_str(), r.max_hits == 0 ? "all" : "1", 1e3 * s,
                s > 0 ? double(bs.rays.size()) / s * 1e-6 : 0.0, over,
                r.max_hits == 1 ? "first hit" : "all-hits filter");
  }
}

int run(int argc, char** argv) {
  Options o;
  CLI::App app{"Times trace_batch, the path of `pierce hits`, pierce.trace and the VTK filters, beside plain "
               "Embree code on the same random rays"};
  app.add_option("--mesh", o.meshes, "Model files to time (STL, OBJ, OFF, PLY); without one, gen::blob");
  app.add_option("--rays", o.rays, "Random rays per scene")->capture_default_str();
  app.add_option("--ray-spec", o.ray_spec,
                 "Rays as `pierce hits --rays` takes them (a CSV file, 'random:n=N,seed=S', 'grid:...') "
                 "instead of random ones");
  app.add_option("--reps", o.reps, "Timed repetitions of every row (medians are printed)")->capture_default_str();
  app.add_option("--threads", o.threads, "Worker threads")->capture_default_str();
  app.add_option("--blob-subdivisions", o.blob_subdivisions, "Size of the default blob")->capture_default_str();
  app.add_flag("--quick", o.quick, "A smoke run: few rays, one repetition");
  CLI11_PARSE(app, argc, argv);
  if (o.quick) {
    o.rays = 2000;
    o.reps = 1;
    o.blob_subdivisions = 3;
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(std::max(1, o.threads)));
  StealMeter steal;
  std::printf("pierce_bench_batch: %s, %d thread(s), load %s\n", cpu_model().c_str(), o.threads,
              load_average().c_str());
  if (o.meshes.empty()) bench_scene(blob_scene(o.blob_subdivisions, o.rays, 1), o);
  for (const std::string& path : o.meshes) bench_scene(mesh_scene(path, o.rays, 1), o);
  std::printf("\nstolen by the hypervisor during the run: %s\n", steal.percent().c_str());
  return 0;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
