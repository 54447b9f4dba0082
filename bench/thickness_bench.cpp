// pierce_bench_thickness: `pierce thickness` end to end on a large closed shell, phase by phase
// (load, build, trace), and its peak memory against what the same mesh costs in plain Embree.
// The shell (gen::hollow_sphere(8, 7): two icospheres, wall 0.05, 1.64 M triangles) is written as
// a binary STL first, so loading is timed as a user's file would be. The Embree figure is measured
// in a child process (fork), so each peak is its process's own. A benchmark: it reports, it never
// asserts a speed.
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "bench_machine.h"
#include "bench_main.h"
#include "bench_stl.h"
#include "bench_timing.h"
#include "embree_reference.h"
#include "pierce/analysis/thickness.h"
#include "pierce/generators.h"
#include "pierce/io/mesh_io.h"
#include "pierce/kernel.h"

namespace pierce::bench {
namespace {

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

// Runs `fn` in a child process and waits; false if it failed. Keeps the child's memory out of this
// process's peak.
template <typename Fn>
bool in_child(Fn&& fn) {
  const pid_t pid = fork();
  if (pid == 0) {
    try {
      fn();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      _exit(1);
    }
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// Peak RSS of a child process that loads the STL and builds plain Embree's scene over it.
double embree_peak_rss_mb(const std::string& path) {
  int fd[2];
  if (pipe(fd) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    Scene scene;
    add_model_files(scene, {path});
    const EmbreeReference e(scene, ReferenceUse::first_hit);
    const double mb = peak_rss_mb();
    if (write(fd[1], &mb, sizeof mb) != sizeof mb) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  double mb = -1;
  if (read(fd[0], &mb, sizeof mb) != sizeof mb) mb = -1;
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return mb;
}

int run(int argc, char** argv) {
  CLI::App app{"pierce_bench_thickness: pierce thickness end to end (load, build, trace) on a 1.64 M-triangle shell"};
  int threads = 0, outer = 8, inner = 7;
  bool quick = false;
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  app.add_option("--outer", outer, "outer icosphere subdivision (default 8)")->check(CLI::Range(1, 9));
  app.add_option("--inner", inner, "inner icosphere subdivision (default 7)")->check(CLI::Range(1, 9));
  app.add_flag("--quick", quick, "a small shell (subdivisions 4 and 3), for the smoke test");
  CLI11_PARSE(app, argc, argv);
  if (quick) outer = 4, inner = 3;
  if (threads == 0) threads = tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("pierce_bench_thickness_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "shell.stl").string();
  std::size_t triangles = 0;
  if (!in_child([&] { write_binary_stl(gen::hollow_sphere(outer, inner, 0.95), path); }))
    throw std::runtime_error("cannot write the shell to " + path);
  triangles = 20 * ((std::size_t(1) << (2 * outer)) + (std::size_t(1) << (2 * inner)));

  const StealMeter steal;
  std::cout << "pierce_bench_thickness\nmachine: " << cpu_model() << ", " << threads << " threads used\n"
            << "load average at start: " << load_average() << "\n"
            << "model: gen::hollow_sphere(" << outer << ", " << inner << "), wall 0.05, " << triangles
            << " triangles, binary STL\n";
  const double embree_mb = embree_peak_rss_mb(path);
  const double rss_before = peak_rss_mb();

  const auto t0 = Clock::now();
  Scene scene;
  add_model_files(scene, {path});
  const double load_s = seconds_since(t0);
  const double rss_loaded = peak_rss_mb();
  const auto t1 = Clock::now();
  const Accel accel(scene);
  const double build_s = seconds_since(t1);
  const double rss_built = peak_rss_mb();
  const auto t2 = Clock::now();
  const analysis::ThicknessResult r = analysis::compute_thickness(accel, {});
  const double trace_s = seconds_since(t2);
  const double total = seconds_since(t0);
  const double pierce_mb = peak_rss_mb();
  std::filesystem::remove_all(dir);

  double min_t = std::numeric_limits<double>::infinity();
  std::size_t finite = 0;
  for (const double t : r.thickness)
    if (std::isfinite(t)) min_t = std::min(min_t, t), ++finite;
  std::printf("pierce thickness (per vertex, ray, kernel %s): %zu samples, %zu finite, min %.5f\n",
              std::string(kernel_name(analysis::ThicknessOptions{}.kernel)).c_str(), r.thickness.size(), finite, min_t);
  std::printf("end to end %.3f s = load %.3f s + build %.3f s + trace %.3f s\n", total, load_s, build_s, trace_s);
  std::printf("peak RSS: pierce %.0f MB (%.0f MB before loading, %.0f MB after loading, %.0f MB after the build; "
              "BVH %.0f MB); plain Embree loading the same file and building its scene %.0f MB; ratio %.2f\n",
              pierce_mb, rss_before, rss_loaded, rss_built, double(accel.memory_bytes()) / 1048576.0, embree_mb,
              embree_mb > 0 ? pierce_mb / embree_mb : 0.0);
  std::cout.flush();
  print_run_end(steal);
  return 0;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
