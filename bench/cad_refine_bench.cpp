// pierce_bench_cad_refine: what thickness true to the B-rep costs. On CAD solids built
// with OpenCASCADE (the tests' model builder: the bent sheet, the filleted box, the hollow torus,
// the thin blended plate, the loft), `pierce thickness --per face` as the CLI runs it, once on the
// mesh only (no exact surfaces) and once on the B-rep (samples projected onto their faces, exits refined by
// Newton steps). Prints per model the samples, both times (single thread, thread CPU time, best of
// --reps), the difference per sample, and the Newton steps alone per sample (projection plus exit
// refinement on the same samples, timed apart). A benchmark, not a test: it prints, it never
// asserts a speed.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

#include "bench_machine.h"
#include "bench_timing.h"
#include "pierce/analysis/thickness.h"
#include "pierce/io/cad_surfaces.h"
#include "pierce/io/model_io.h"
#include "step_assembly.h"

namespace pierce::bench {
namespace {

template <class F>
double best_of(int reps, F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < reps; ++r) {
    const double t0 = thread_seconds();
    f();
    best = std::min(best, thread_seconds() - t0);
  }
  return best;
}

int run(int argc, char** argv) {
  CLI::App app("Cost of B-rep-true thickness (projection + Newton exit refinement) per sample");
  int reps = 5;
  double deflection = 0;
  bool quick = false;
  app.add_option("--reps", reps, "Timed repetitions (best is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--deflection", deflection, "CAD linear deflection (0: 0.1% of the diagonal)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--quick", quick, "One repetition, coarse meshes (smoke run)");
  CLI11_PARSE(app, argc, argv);
  if (quick) reps = 1;
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pierce_bench_cad_refine_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  struct Model {
    const char* name;
    TopoDS_Shape (*make)();
  };
  const Model models[] = {{"bent_sheet", test_models::bent_sheet},
                          {"filleted_box", test_models::filleted_box},
                          {"hollow_torus", test_models::hollow_torus},
                          {"thin_blended_plate", test_models::thin_blended_plate},
                          {"lofted_solid", test_models::lofted_solid}};
  const StealMeter steal;
  std::printf("pierce_bench_cad_refine\nmachine: %s, 1 thread, load %s, best of %d\n", cpu_model().c_str(),
              load_average().c_str(), reps);
  std::printf("%-20s %9s %12s %12s %14s %14s\n", "model", "samples", "mesh [s]", "B-rep [s]", "extra/sample",
              "Newton/sample");
  int status = 0;
  for (const Model& m : models) {
    const std::string path = (dir / (std::string(m.name) + ".brep")).string();
    test_models::write_brep(m.make(), path);
    Scene scene;
    TessellationOptions t;
    t.linear_deflection = deflection;
    if (quick) t.angular_deflection_deg = 30;
    const std::vector<LoadedFile> files = add_any_model(scene, {path}, t);
    const auto exact = cad_surfaces(files, scene.geometries().size());
    const Accel accel(scene);
    analysis::ThicknessOptions o;
    o.per = analysis::SampleAt::face;
    analysis::ThicknessResult mesh, brep;
    const double t_mesh = best_of(reps, [&] { mesh = analysis::compute_thickness(accel, o); });
    o.exact = exact.get();
    const double t_brep = best_of(reps, [&] { brep = analysis::compute_thickness(accel, o); });
    // The Newton steps alone: the projection of every face centre and the refinement of its exit,
    // from the hits the mesh run found (re-traced here untimed).
    const Geometry& geo = scene.geometry(0);
    std::vector<std::pair<std::uint32_t, Vec3d>> starts;
    for (std::uint32_t k = 0; k < geo.triangles.size(); ++k) {
      const Tri& tr = geo.triangles[k];
      starts.emplace_back(k, (geo.vertices[tr[0]] + geo.vertices[tr[1]] + geo.vertices[tr[2]]) * (1.0 / 3.0));
    }
    volatile double sink = 0;
    const double t_newton = best_of(reps, [&] {
      double acc = 0;
      for (const auto& [k, c] : starts) {
        const auto p = exact->project(0, k, 1.0 / 3.0, 1.0 / 3.0, c);
        if (!p) continue;
        // A refinement on the start face itself (a Newton solve of the same size as an exit's).
        const auto x = exact->intersect(0, k, 1.0 / 3.0, 1.0 / 3.0, p->point + p->normal * 1e-3, p->normal * -1.0);
        acc += x ? x->t : 0.0;
      }
      sink = sink + acc;
    });
    const double n = double(brep.size());
    std::printf("%-20s %9zu %12.4f %12.4f %11.2f us %11.2f us\n", m.name, brep.size(), t_mesh, t_brep,
                1e6 * (t_brep - t_mesh) / n, 1e6 * t_newton / n);
    if (brep.solids.empty() || brep.solids[0].valid == 0) status = 1;  // nothing measured: broken, not slow
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::printf("CPU time stolen by the hypervisor during the run: %s\n", steal.percent().c_str());
  return status;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::run(argc, argv); }
