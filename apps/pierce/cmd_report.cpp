// `pierce report MODEL... -o report.html`: one self-contained HTML file with the thickness map in
// an interactive 3D view, the findings (thin and thick walls; contact, clash and clearance
// pairs), per-solid statistics, the model's checks, what exactness cost on this model and how the
// report was made (docs/REPORT.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <optional>

#include <embree3/rtcore.h>
#include <nlohmann/json.hpp>
#include <tbb/version.h>

#include "command.h"
#include "csv_text.h"
#include "json_text.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/analysis/mesh_report.h"
#include "pierce/analysis/overlaps.h"
#include "pierce/analysis/solid_pairs.h"
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/io/cad_surfaces.h"
#include "pierce/version.h"
#include "progress.h"
#include "report_mesh.h"
#include "report_page.h"

namespace pierce::cli {

namespace {

using namespace pierce::analysis;

// Thickness rays traced twice, exact and epsilon, for "what exactness cost": a fixed budget, so
// that the comparison takes well under a second on any model.
constexpr std::size_t kExactnessRays = 20000;
// Rays of the interference grid along each axis (as `pierce overlaps`' default axes:n=128).
constexpr int kPairGrid = 128;

struct ReportCli {
  ModelArgs model;
  std::string method = "ray", per = "vertex", kernel{kernel_name(kDefaultKernel)};
  double min_thickness = 0;
  double max_thickness = std::numeric_limits<double>::infinity();
  double clearance = 0;
  std::size_t display_triangles = 400000;
  std::string title;
  std::string out;
  bool force = false, progress = false;
};

// The exact kernel and the epsilon baseline on the same thickness rays (ray_exit_distance on the
// mesh, one thread each, so the times compare): how long each took and where they differ.
struct ExactnessCost {
  std::size_t budget = kExactnessRays, rays = 0, stride = 1;
  double exact_ms = 0, epsilon_ms = 0, epsilon = 0, tolerance = 0;
  std::size_t wrong = 0, missed = 0, spurious = 0, off = 0;
  double max_error = 0, median_error = 0, max_relative_error = 0;
  std::string skipped;  // why no comparison was made, if none was
};

ExactnessCost measure_exactness_cost(const Accel& accel, const ThicknessResult& r, KernelKind exact) {
  ExactnessCost c;
  const Scene& scene = accel.scene();
  std::vector<std::size_t> samples;
  for (std::size_t i = 0; i < r.size(); ++i)
    if (length(r.normal[i]) > 0) samples.push_back(i);
  c.stride = std::max<std::size_t>(1, (samples.size() + kExactnessRays - 1) / kExactnessRays);
  std::vector<std::size_t> chosen;
  for (std::size_t k = 0; k < samples.size(); k += c.stride) chosen.push_back(samples[k]);
  c.rays = chosen.size();
  const KernelKind baseline{KernelId::epsilon, Precision::float32};
  c.skipped = unsupported_reason(accel, baseline);
  if (c.rays == 0 || !c.skipped.empty()) {
    c.rays = 0;
    return c;
  }
  KernelOptions ko;
  ko.order.tie = TieOrder::leave_before_enter;  // what ray_exit_distance requires
  c.tolerance = tie_distance(scene, ThicknessOptions{}.tie_tolerance_rel);
  c.epsilon = ko.epsilon_rel * length(scene.bounds().hi - scene.bounds().lo);
  const double inf = std::numeric_limits<double>::infinity();
  auto trace = [&](KernelKind kind, std::vector<double>& out) {
    HitIterator it(accel, kind, ko);  // builds what the kernel needs before the clock starts
    out.resize(chosen.size());
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      const std::size_t i = chosen[k];
      out[k] = ray_exit_distance(it, r.solid[i], r.point[i], r.normal[i] * -1.0, inf, c.tolerance);
    }
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<double> exact_t, epsilon_t;
  c.exact_ms = trace(exact, exact_t);
  c.epsilon_ms = trace(baseline, epsilon_t);
  std::vector<double> errors;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const double x = exact_t[k], e = epsilon_t[k];
    if (std::isnan(x) && std::isnan(e)) continue;
    if (std::isnan(e)) {
      ++c.missed;
    } else if (std::isnan(x)) {
      ++c.spurious;
    } else if (std::abs(e - x) > c.tolerance) {
      ++c.off;
      errors.push_back(std::abs(e - x));
      c.max_relative_error = std::max(c.max_relative_error, std::abs(e - x) / x);
    }
  }
  c.wrong = c.missed + c.spurious + c.off;
  if (!errors.empty()) {
    std::sort(errors.begin(), errors.end());
    c.max_error = errors.back();
    c.median_error = percentile_sorted(errors, 50);
  }
  return c;
}

nlohmann::ordered_json exactness_json(const ExactnessCost& c, KernelKind exact) {
  nlohmann::ordered_json j{{"budget", c.budget},     {"rays", c.rays},         {"stride", c.stride},
                           {"exact_kernel", kernel_name(exact)}, {"exact_ms", c.exact_ms},
                           {"epsilon_ms", c.epsilon_ms}, {"epsilon", c.epsilon}, {"tolerance", c.tolerance},
                           {"wrong", c.wrong},       {"missed", c.missed},     {"spurious", c.spurious},
                           {"off", c.off},           {"max_error", c.max_error}, {"median_error", c.median_error},
                           {"max_relative_error", c.max_relative_error}};
  if (!c.skipped.empty()) j["skipped"] = c.skipped;
  return j;
}

// Per-triangle kinds for the clearance / clash map.
void pair_map(const TriangleOverlapArrays& a, const SolidPairReport& pairs, DisplayInput& in) {
  in.tri_offset = a.tri_offset;
  in.pair_category.assign(a.size(), PairCategory::free);
  in.pair_gap.assign(a.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t t = 0; t < a.size(); ++t) {
    const double gap = pairs.triangle_clearance.empty() ? pairs.clearance : pairs.triangle_clearance[t];
    if (a.interference_hits[t] > 0) {
      in.pair_category[t] = PairCategory::clash;
    } else if (a.coplanar_partner[t] >= 0 && std::uint32_t(a.coplanar_partner[t]) != a.solid[t]) {
      in.pair_category[t] = PairCategory::contact;
    } else if (pairs.clearance > 0 && gap < pairs.clearance) {
      in.pair_category[t] = PairCategory::clearance;
      in.pair_gap[t] = gap;
    }
  }
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::ordered_json provenance_json(const ReportCli& o) {
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const std::string& m : o.model.models) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(m, ec);
    inputs.push_back({{"path", m}, {"bytes", ec ? nlohmann::ordered_json() : nlohmann::ordered_json(bytes)}});
  }
  return {{"command", command_line()},
          {"date", utc_now()},
          {"pierce_version", PIERCE_VERSION_STRING},
          {"dependencies",
           {{"Embree", RTC_VERSION_STRING},
            {"oneTBB", TBB_runtime_version()},
            {"OpenCASCADE", PIERCE_OPENCASCADE_VERSION},
            {"three.js", "r111"}}},
          {"inputs", inputs}};
}

nlohmann::ordered_json solid_json(const SolidReport& m, const TessellationCheck* check, const SolidThickness* t,
                                  std::size_t thick) {
  nlohmann::ordered_json j{{"id", m.geom}};
  nlohmann::ordered_json checks{{"source", m.source},
                                {"triangles", m.triangles},
                                {"closed", m.closed},
                                {"boundary_edges", m.boundary_edges},
                                {"non_manifold_edges", m.non_manifold_edges},
                                {"inconsistent_edges", m.inconsistent_edges},
                                {"degenerate_triangles", m.degenerate},
                                {"duplicate_triangles", m.duplicates}};
  if (check)
    checks["tessellation"] = {{"folded_triangles", check->folded},
                              {"sliver_triangles", check->slivers},
                              {"faces_remeshed", check->faces_remeshed}};
  if (t) {
    j["elements"] = t->elements;
    j["valid"] = t->valid;
    j["no_exit"] = t->no_exit;
    j["no_normal"] = t->no_normal;
    j["tessellation"] = t->tessellation;
    j["thin"] = t->thin;
    j["thick"] = thick;
    if (t->valid > 0) {
      nlohmann::ordered_json p;
      for (auto [q, v] : t->summary.percentiles) p["p" + exact_number(q)] = v;
      j["thickness"] = {{"min", t->summary.min}, {"max", t->summary.max}, {"mean", t->summary.mean}, {"percentiles", p}};
      j["histogram"] = {{"edges", t->summary.histogram.edges}, {"counts", t->summary.histogram.counts}};
    }
  }
  j["checks"] = checks;
  return j;
}

// The findings, numbered from 1 in the order the page lists them: thin walls, thick walls, pairs.
nlohmann::ordered_json findings_json(const ThicknessResult& r, const SolidPairReport* pairs) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  auto region = [&](const ThicknessRegion& g) {
    a.push_back({{"n", a.size() + 1},
                 {"kind", g.thick ? "thick" : "thin"},
                 {"solid", g.solid},
                 {"thickness", g.thickness},
                 {"area", g.area},
                 {"samples", g.samples},
                 {"point", json_point(g.point)},
                 {"point_b", json_point(g.exit)}});
  };
  for (const ThicknessRegion& g : r.thin_regions) region(g);
  for (const ThicknessRegion& g : r.thick_regions) region(g);
  if (pairs)
    for (const SolidPair& p : pairs->pairs) {
      nlohmann::ordered_json f{{"n", a.size() + 1},
                               {"kind", enum_name(p.kind)},
                               {"solid", p.solid_a},
                               {"solid_b", p.solid_b},
                               {"gap", json_or_null(p.gap)},
                               {"depth", json_or_null(p.depth)},
                               {"volume", json_or_null(p.volume)},
                               {"point", json_point(p.point)}};
      if (!std::isnan(p.point_b.x)) f["point_b"] = json_point(p.point_b);
      a.push_back(std::move(f));
    }
  return a;
}

int run_report(const ReportCli& o) {
  InterruptGuard guard;
  OutputFile::check_target(o.out, o.force);  // before any long work
  const KernelKind kernel = exact_kernel_option(o.kernel);
  if (!(o.clearance >= 0) || !std::isfinite(o.clearance)) throw InputError("--clearance must be a finite number >= 0");
  if (o.min_thickness > 0 && o.max_thickness < o.min_thickness)
    throw InputError("--max must not be below --min (a sample cannot be both thin and thick)");

  Scene scene;
  const std::vector<LoadedFile> files = load_models(scene, o.model);
  if (interrupted()) return cancelled();
  const std::shared_ptr<const CadSurfaces> exact = cad_surfaces(files, scene.geometries().size());
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  ThicknessOptions opts;
  opts.method = parse_enum_or_throw<ThicknessMethod>(o.method);
  opts.per = parse_enum_or_throw<SampleAt>(o.per);
  opts.min_thickness = o.min_thickness;
  opts.max_thickness = o.max_thickness;
  opts.kernel = kernel;
  opts.exact = exact.get();
  LazyProgressBar bar("thickness", o.progress);
  const ThicknessResult r = compute_thickness(accel, opts, std::ref(bar));
  bar.finish();
  if (!r.completed || interrupted()) return cancelled();

  DisplayInput display;
  display.scene = &scene;
  display.per_vertex = r.per == SampleAt::vertex;
  display.thickness.resize(scene.geometries().size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Geometry& g = scene.geometry(r.solid[i]);
    auto& vals = display.thickness[r.solid[i]];
    if (vals.empty())
      vals.assign(display.per_vertex ? g.vertices.size() : g.triangles.size(), std::numeric_limits<double>::quiet_NaN());
    vals[r.element[i]] = r.thickness[i];
  }

  // Contact, clash and clearance between solids, as `pierce overlaps` finds them on its default grid.
  std::optional<SolidPairReport> pairs;
  if (scene.geometries().size() > 1) {
    LazyProgressBar pair_bar("pairs", o.progress);
    const CoplanarReport cop = find_coplanar_overlaps(scene, CoplanarOptions{}, std::ref(pair_bar));
    if (!cop.completed || interrupted()) return cancelled();
    RayOverlapOptions ropts;
    ropts.kernel = kernel;
    const RayOverlapReport rays =
        analyse_ray_overlaps(accel, axis_grid_rays(scene.bounds(), kPairGrid), ropts, std::ref(pair_bar));
    if (!rays.completed || interrupted()) return cancelled();
    pairs = classify_solid_pairs(accel, cop, rays, kPairGrid, o.clearance, /*triangle_clearance=*/true,
                                 std::ref(pair_bar));
    pair_bar.finish();
    if (!pairs->completed || interrupted()) return cancelled();
    pair_map(triangle_overlap_arrays(scene, &cop, &rays), *pairs, display);
  }

  const ExactnessCost cost = measure_exactness_cost(accel, r, kernel);
  if (interrupted()) return cancelled();
  const DisplayMesh mesh = make_display_mesh(display, o.display_triangles);

  nlohmann::ordered_json data;
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (const Geometry& g : scene.geometries()) names.push_back(g.name);
  data["solid_names"] = names;
  const BBoxd b = scene.bounds();
  data["bounds"] = {json_point(b.lo), json_point(b.hi)};
  data["options"] = {{"method", o.method},
                     {"per", o.per},
                     {"kernel", o.kernel},
                     {"min_thickness", o.min_thickness},
                     {"max_thickness", json_or_null(std::isfinite(o.max_thickness) ? o.max_thickness : std::nan(""))},
                     {"clearance", o.clearance}};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const SolidThickness& s : r.solids)
    if (s.valid > 0) lo = std::min(lo, s.summary.min), hi = std::max(hi, s.summary.max);
  data["thickness_range"] = lo <= hi ? nlohmann::ordered_json{lo, hi} : nlohmann::ordered_json();
  data["percentiles"] = opts.percentiles;
  std::vector<std::size_t> thick(scene.geometries().size(), 0);
  for (std::size_t i = 0; i < r.size(); ++i)
    if (r.region[i] >= 0 && std::size_t(r.region[i]) >= r.thin_regions.size()) ++thick[r.solid[i]];
  const std::vector<SolidReport> checks = mesh_report(scene);
  data["solids"] = nlohmann::ordered_json::array();
  for (const SolidReport& m : checks) {
    const SolidThickness* t = nullptr;
    for (const SolidThickness& s : r.solids)
      if (s.geom == m.geom) t = &s;
    data["solids"].push_back(solid_json(m, tessellation_check(files, m.geom), t, thick[m.geom]));
  }
  data["findings"] = findings_json(r, pairs ? &*pairs : nullptr);
  data["exactness"] = exactness_json(cost, kernel);
  nlohmann::ordered_json warnings = nlohmann::ordered_json::array();
  for (const LoadedFile& f : files)
    for (const std::string& w : f.warnings) warnings.push_back(f.path + ": " + w);
  data["warnings"] = warnings;
  data["provenance"] = provenance_json(o);
  data["mesh"] = display_mesh_json(mesh);

  std::string title = o.title;
  if (title.empty())
    for (const std::string& m : o.model.models)
      title += (title.empty() ? "" : ", ") + std::filesystem::path(m).filename().string();
  const std::string page = report_page(title, data);
  const int rc = write_file(o.out, o.force, [&](std::FILE* f) {
    if (std::fwrite(page.data(), 1, page.size(), f) != page.size()) throw std::runtime_error(o.out + ": write error");
  });
  if (rc != 0) return rc;
  std::size_t thin = 0, clash = 0;
  for (const auto& f : data["findings"]) thin += f["kind"] == "thin", clash += f["kind"] == "clash";
  std::printf("report %s: %zu bytes; %zu solids, %zu of %zu triangles shown; %zu thin regions, %zu clashes; "
              "exactness: %zu rays, exact %.3g ms, epsilon %.3g ms, %zu wrong\n",
              o.out.c_str(), page.size(), scene.geometries().size(), mesh.triangles_shown(), mesh.triangles_model, thin,
              clash, cost.rays, cost.exact_ms, cost.epsilon_ms, cost.wrong);
  return 0;
}

}  // namespace

std::function<int()> register_report(CLI::App& app) {
  const auto [o, cmd] = add_model_command<ReportCli>(
      app, "report", "One self-contained HTML report: 3D thickness map, findings, statistics, checks, exactness cost");
  cmd->add_option("--method", o->method, "Thickness method, as `pierce thickness --method`")
      ->check(CLI::IsMember(enum_names<ThicknessMethod>()))
      ->capture_default_str();
  cmd->add_option("--per", o->per, "Sample at every vertex or every face (triangle centroid)")
      ->check(CLI::IsMember(enum_names<SampleAt>()))
      ->capture_default_str();
  cmd->add_option("--min", o->min_thickness, "Thin: thickness strictly below T; thin walls are listed as regions")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max", o->max_thickness, "Thick: thickness strictly above T2; thick walls are listed as regions")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--clearance", o->clearance,
                  "Also list solid pairs closer than this (model units) as clearance; 0 = clash and contact only")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  add_exact_kernel_option(cmd, o->kernel);
  cmd->add_option("--display-triangles", o->display_triangles,
                  "Show at most this many triangles in the 3D view (larger models are shown decimated; the tables "
                  "always hold the full results)")
      ->check(CLI::Range(std::size_t(1000), std::size_t(50000000)))
      ->capture_default_str();
  cmd->add_option("--title", o->title, "Title of the report (default: the model files' names)");
  cmd->add_option("-o,--out", o->out, "The report: one HTML file")->required();
  add_force_and_progress_flags(cmd, o->force, o->progress, "an existing report");
  return [o] { return run_report(*o); };
}

}  // namespace pierce::cli
