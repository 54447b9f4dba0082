// pierce_bench_cad_refine: what thickness true to the B-rep costs. On CAD parts built with
// OpenCASCADE (the tests' model builder: the bent sheet, the filleted box, the hollow torus, the
// thin blended plate, the loft, written as BREP; the slotted sheet heatsink and the 33-solid
// connector assembly, written as STEP), `pierce thickness --per face` as the CLI runs it, once on
// the mesh only (the same tessellation, no exact surfaces) and once on the B-rep (samples
// projected onto their faces, exits refined by Newton steps). Prints per model the solids and
// triangles, the load (read, mesh, checks; wall time on --threads, best of --reps), both
// thickness times per sample (one thread, thread CPU time, best of --reps) and their ratio, the
// Newton steps alone per sample (projection plus exit refinement on the same samples, timed
// apart), and the end-to-end time (load, BVH, B-rep thickness; wall time on --threads, best of
// up to 3). A benchmark, not a test: it prints, it never asserts a speed.
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <string>
#include <tuple>
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

struct Model {
  const char* name;
  TopoDS_Shape (*make)();              // a solid written as BREP; null: `write` writes the file
  void (*write)(const std::string&);  // a STEP file
};

void write_heatsink(const std::string& path) { test_models::write_step(test_models::sheet_heatsink(), path); }

int run(int argc, char** argv) {
  CLI::App app("Cost of B-rep-true thickness (projection + Newton exit refinement) per sample");
  int reps = 5, threads = 2;
  double deflection = 0;
  double angle = TessellationOptions{}.angular_deflection_deg;
  bool quick = false;
  app.add_option("--reps", reps, "Timed repetitions (best is printed)")->check(CLI::Range(1, 1000));
  app.add_option("--deflection", deflection, "CAD linear deflection (0: 0.1% of the diagonal)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--angular-deflection", angle, "CAD angular deflection in degrees (finer: more triangles on curved faces)")
      ->check(CLI::Range(0.01, 179.0))
      ->capture_default_str();
  app.add_option("--threads", threads, "Threads of the end-to-end run (load and B-rep thickness)")
      ->check(CLI::Range(1, 1024));
  app.add_flag("--quick", quick, "One repetition, coarse meshes (smoke run)");
  std::string only, keep;
  app.add_option("--model", only, "Run only the model of this name");
  app.add_option("--keep", keep, "Write the models into this directory and keep them (for `pierce thickness`)");
  CLI11_PARSE(app, argc, argv);
  if (quick) reps = 1;
  Message::DefaultMessenger()->ChangePrinters().Clear();  // the STEP writer's statistics

  const std::filesystem::path dir =
      !keep.empty() ? std::filesystem::path(keep)
                    : std::filesystem::temp_directory_path() / ("pierce_bench_cad_refine_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Model models[] = {{"bent_sheet", test_models::bent_sheet, nullptr},
                          {"filleted_box", test_models::filleted_box, nullptr},
                          {"hollow_torus", test_models::hollow_torus, nullptr},
                          {"thin_blended_plate", test_models::thin_blended_plate, nullptr},
                          {"lofted_solid", test_models::lofted_solid, nullptr},
                          {"sheet_heatsink", nullptr, write_heatsink},
                          {"connector", nullptr, test_models::write_connector_assembly}};
  const StealMeter steal;
  std::printf("pierce_bench_cad_refine\nmachine: %s, load %s, best of %d\n", cpu_model().c_str(),
              load_average().c_str(), reps);
  std::printf("thickness --per face; mesh and B-rep: 1 thread, thread CPU time; load and end to end: %d threads, wall time\n",
              threads);
  std::printf("%-18s %6s %7s %7s %17s %9s %9s %9s %7s %7s\n", "model", "solids", "tris", "load[s]",
              "read/mesh/check", "mesh/smp", "B-rep/smp", "Newton", "ratio", "e2e[s]");
  int status = 0;
  for (const Model& m : models) {
    if (!only.empty() && only != m.name) continue;
    const std::string path = (dir / (std::string(m.name) + (m.make ? ".brep" : ".step"))).string();
    if (m.make) test_models::write_brep(m.make(), path);
    else m.write(path);
    TessellationOptions t;
    t.linear_deflection = deflection;
    t.angular_deflection_deg = quick ? 30 : angle;
    // Load (read, mesh, checks), wall time on `threads` threads, best of reps.
    double t_load = std::numeric_limits<double>::infinity();
    CadLoadTimes parts;  // of the fastest load
    Scene scene;
    std::vector<LoadedFile> files;
    {
      const tbb::global_control par(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      for (int r = 0; r < reps; ++r) {
        Scene sc;
        const auto t0 = Clock::now();
        std::vector<LoadedFile> f = add_any_model(sc, {path}, t);
        const double took = seconds_since(t0);
        if (took < t_load) t_load = took, parts = f.at(0).cad_times;
        if (r + 1 == reps) scene = std::move(sc), files = std::move(f);
      }
    }
    const auto exact = cad_surfaces(files, scene.geometries().size());
    const Accel accel(scene);
    std::size_t tris = 0;
    for (const Geometry& g : scene.geometries()) tris += g.triangles.size();
    analysis::ThicknessOptions o;
    o.per = analysis::SampleAt::face;
    analysis::ThicknessResult mesh, brep;
    double t_mesh = 0, t_brep = 0, t_e2e = std::numeric_limits<double>::infinity();
    {
      const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
      t_mesh = best_of(reps, [&] { mesh = analysis::compute_thickness(accel, o); });
      o.exact = exact.get();
      t_brep = best_of(reps, [&] { brep = analysis::compute_thickness(accel, o); });
    }
    // End to end: load, surfaces, BVH and the B-rep thickness map, wall time on `threads` threads,
    // each run from the file.
    {
      const tbb::global_control par(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      for (int r = 0; r < std::min(reps, 3); ++r) {
        const auto t0 = Clock::now();
        Scene sc;
        const std::vector<LoadedFile> f = add_any_model(sc, {path}, t);
        const auto ex = cad_surfaces(f, sc.geometries().size());
        const Accel ac(sc);
        analysis::ThicknessOptions oe = o;
        oe.exact = ex.get();
        const analysis::ThicknessResult res = analysis::compute_thickness(ac, oe);
        t_e2e = std::min(t_e2e, seconds_since(t0));
        if (res.size() != brep.size()) status = 1;
      }
    }
    // The Newton steps alone: the projection of every face centre and the refinement of its exit,
    // from the hits the mesh run found (re-traced here untimed).
    std::vector<std::tuple<std::uint32_t, std::uint32_t, Vec3d>> starts;
    for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
      const Geometry& geo = scene.geometry(g);
      for (std::uint32_t k = 0; k < geo.triangles.size(); ++k) {
        const Tri& tr = geo.triangles[k];
        starts.emplace_back(g, k, (geo.vertices[tr[0]] + geo.vertices[tr[1]] + geo.vertices[tr[2]]) * (1.0 / 3.0));
      }
    }
    volatile double sink = 0;
    double t_newton = 0;
    {
      const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
      t_newton = best_of(reps, [&] {
        double acc = 0;
        for (const auto& [g, k, c] : starts) {
          const auto p = exact->project(g, k, 1.0 / 3.0, 1.0 / 3.0, c);
          if (!p) continue;
          // A refinement on the start face itself (a Newton solve of the same size as an exit's).
          const auto x = exact->intersect(g, k, 1.0 / 3.0, 1.0 / 3.0, p->point + p->normal * 1e-3, p->normal * -1.0);
          acc += x ? x->t : 0.0;
        }
        sink = sink + acc;
      });
    }
    const double n = double(brep.size());
    std::printf("%-18s %6zu %7zu %7.3f %5.2f/%5.2f/%5.2f %6.2f us %6.2f us %6.2f us %6.1fx %7.3f\n", m.name,
                scene.geometries().size(), tris, t_load, parts.read, parts.mesh, parts.check, 1e6 * t_mesh / n,
                1e6 * t_brep / n, 1e6 * t_newton / n, t_brep / t_mesh, t_e2e);
    std::size_t valid = 0;
    for (const auto& s : brep.solids) valid += s.valid;
    if (brep.solids.empty() || valid == 0) status = 1;  // nothing measured: broken, not slow
  }
  std::error_code ec;
  if (keep.empty()) std::filesystem::remove_all(dir, ec);
  std::printf("CPU time stolen by the hypervisor during the run: %s\n", steal.percent().c_str());
  return status;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::run(argc, argv); }
