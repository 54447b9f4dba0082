// pierce_bench_report: what `pierce report` costs over `pierce thickness` on a large model. The
// shell of pierce_bench_thickness (gen::hollow_sphere(8, 7): 1.64 M triangles, binary STL) is
// measured by the `pierce` binary twice, `pierce thickness shell.stl` and `pierce report shell.stl
// -o report.html`, each the run of least wall-clock time of --reps; printed: both times and their
// CPU times (all threads; steadier than wall-clock on a busy machine), their differences, the
// report's size and how many triangles its view shows. With --chromium the report
// is then opened in headless Chromium (SwiftShader WebGL) and whether its page built without a
// script error is printed, with the time that took. A benchmark: it reports, it never asserts a
// speed.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "bench_machine.h"
#include "bench_main.h"
#include "bench_stl.h"
#include "bench_timing.h"
#include "pierce/generators.h"

namespace pierce::bench {
namespace {

// The wall-clock and CPU (user + system, all threads) seconds of one run of a program.
struct RunTime {
  double wall = 0, cpu = 0;
};

// Runs `argv` with stdout to `stdout_path` (or /dev/null), stderr kept unless `quiet`; returns its
// times; throws if it fails.
RunTime timed_run(const std::vector<std::string>& argv, const std::string& stdout_path = "/dev/null",
                  bool quiet = false) {
  std::cout.flush();  // or the child would print what is buffered again
  std::fflush(stdout);
  const auto t0 = Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    if (!std::freopen(stdout_path.c_str(), "w", stdout)) _exit(126);
    if (quiet && !std::freopen("/dev/null", "w", stderr)) _exit(126);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  const double wall = seconds_since(t0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(argv[0] + " " + argv[1] + " failed (status " + std::to_string(status) + ")");
  auto seconds = [](timeval t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return {wall, seconds(usage.ru_utime) + seconds(usage.ru_stime)};
}

// The run with the least wall-clock time of `reps`.
RunTime best_of(int reps, const std::vector<std::string>& argv) {
  RunTime best{std::numeric_limits<double>::infinity(), 0};
  for (int r = 0; r < reps; ++r) {
    const RunTime t = timed_run(argv);
    if (t.wall < best.wall) best = t;
  }
  return best;
}

// The value of attribute `name` on the first <html ...> tag of a DOM dump, or "" if none.
std::string html_attribute(const std::string& dom, const std::string& name) {
  const std::size_t tag = dom.find("<html");
  if (tag == std::string::npos) return "";
  const std::string head = dom.substr(tag, dom.find('>', tag) - tag);
  const std::size_t at = head.find(" " + name + "=\"");
  if (at == std::string::npos) return "";
  const std::size_t from = at + name.size() + 3;
  return head.substr(from, head.find('"', from) - from);
}

int run(int argc, char** argv) {
  CLI::App app{"pierce report against pierce thickness on a 1.64 M-triangle shell"};
  int outer = 8, inner = 7, reps = 3;
  bool quick = false;
  std::string pierce = (std::filesystem::path(argv[0]).parent_path() / "pierce").string();
  std::string chromium;
  app.add_option("--pierce", pierce, "the pierce binary (default: next to this bench)");
  app.add_option("--chromium", chromium, "also open the report in this headless Chromium");
  app.add_option("--reps", reps, "runs of each command; the best is printed (default 3)")->check(CLI::Range(1, 100));
  app.add_option("--outer", outer, "outer icosphere subdivision (default 8)")->check(CLI::Range(1, 9));
  app.add_option("--inner", inner, "inner icosphere subdivision (default 7)")->check(CLI::Range(1, 9));
  app.add_flag("--quick", quick, "a small shell (subdivisions 4 and 3), one run each, for the smoke test");
  CLI11_PARSE(app, argc, argv);
  if (quick) outer = 4, inner = 3, reps = 1;

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("pierce_bench_report_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string stl = (dir / "shell.stl").string(), html = (dir / "report.html").string();
  write_binary_stl(gen::hollow_sphere(outer, inner, 0.95), stl);
  const std::size_t triangles = 20 * ((std::size_t(1) << (2 * outer)) + (std::size_t(1) << (2 * inner)));

  const StealMeter steal;
  std::cout << "pierce_bench_report\nmachine: " << cpu_model() << "\nload average at start: " << load_average()
            << "\nmodel: gen::hollow_sphere(" << outer << ", " << inner << "), wall 0.05, " << triangles
            << " triangles, binary STL; best of " << reps << " runs\n";
  // --min 0.04: no thin wall (the wall is 0.05), so the report's regions cost what a clean part's do.
  const RunTime thickness = best_of(reps, {pierce, "thickness", stl, "--min", "0.04"});
  const RunTime report = best_of(reps, {pierce, "report", stl, "--min", "0.04", "-o", html, "--force"});
  const std::string summary = (dir / "summary.txt").string();
  timed_run({pierce, "report", stl, "--min", "0.04", "-o", html, "--force"}, summary);
  std::printf("pierce thickness %.2f s (CPU %.2f s); pierce report %.2f s (CPU %.2f s): %+.2f s (CPU %+.2f s); "
              "report %.1f MB\n",
              thickness.wall, thickness.cpu, report.wall, report.cpu, report.wall - thickness.wall,
              report.cpu - thickness.cpu, double(std::filesystem::file_size(html)) / 1e6);
  if (std::FILE* f = std::fopen(summary.c_str(), "r")) {
    char line[512];
    while (std::fgets(line, sizeof line, f)) std::printf("  %s", line);
    std::fclose(f);
  }
  if (!chromium.empty()) {
    const std::string dom = (dir / "dom.html").string();
    const double open_s = timed_run({chromium, "--headless", "--no-sandbox", "--use-gl=swiftshader",
                                     "--enable-unsafe-swiftshader", "--user-data-dir=" + (dir / "profile").string(),
                                     "--window-size=1280,900", "--virtual-time-budget=30000",
                                     "--screenshot=" + (dir / "report.png").string(), "--dump-dom",
                                     "file://" + html},
                                    dom, /*quiet=*/true)
                              .wall;
    std::string text;
    if (std::FILE* f = std::fopen(dom.c_str(), "r")) {
      char buf[65536];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
      std::fclose(f);
    }
    std::printf("chromium (SwiftShader): page %s in %s ms (its script: data, view, tables, first drawing), %s "
                "script errors; %.1f s from start to screenshot\n",
                html_attribute(text, "data-ready") == "1" ? "built" : "NOT built",
                html_attribute(text, "data-build-ms").empty() ? "?" : html_attribute(text, "data-build-ms").c_str(),
                html_attribute(text, "data-errors").empty() ? "?" : html_attribute(text, "data-errors").c_str(),
                open_s);
  }
  std::filesystem::remove_all(dir);
  std::cout.flush();
  print_run_end(steal);
  return 0;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
