// `pierce overlaps MODEL`: coplanar overlapping faces (exact and within --tol), Gribble et al.'s
// coplanar-hit statistic, solid-solid interference along rays, per solid pair, and every pair of
// solids within --clearance classified as clash, contact or clearance; per-triangle heat-map arrays
// in VTP.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>

#include <nlohmann/json.hpp>

#include "csv_text.h"
#include "json_text.h"
#include "picture.h"
#include "command.h"
#include "interrupt.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/analysis/overlaps.h"
#include "pierce/analysis/solid_pairs.h"
#include "pierce/error.h"
#include "pierce/io/ray_source.h"
#include "pierce/render/false_colour.h"
#include "progress.h"
#include "vtp_writer.h"

namespace pierce::cli {

namespace {

using namespace pierce::analysis;

struct OverlapsCli {
  ModelArgs model;
  double tol = 0;
  double clearance = 0;
  std::string rays = "axes:n=128";
  double ray_eps = 1e-5;
  std::string kernel{kernel_name(kDefaultKernel)};
  std::string out;
  std::string png, png_size = "800x600", png_view = "-1,-1,-1";
  bool force = false, progress = false;
};

// N of `axes:n=N`, 0 for a spec not starting with `axes`.
int axes_grid_n(const std::string& spec) {
  const std::string prefix = "axes:n=";
  if (spec.rfind("axes", 0) != 0) return 0;
  char* end = nullptr;
  const long n = spec.rfind(prefix, 0) == 0 ? std::strtol(spec.c_str() + prefix.size(), &end, 10) : 0;
  if (!end || *end != '\0' || n <= 0 || n > 32768)
    throw InputError("--rays '" + spec + "': expected axes:n=N with 0 < N <= 32768");
  return int(n);
}

// `axes:n=N`: N x N parallel rays along each of x, y and z; anything else as `pierce hits --rays`.
std::vector<Ray> make_rays(const std::string& spec, const Scene& scene) {
  const int n = axes_grid_n(spec);
  return n > 0 ? axis_grid_rays(scene.bounds(), n) : load_rays(spec, scene);
}

// A pair's point as [x, y, z], or null where it does not apply to the pair's kind (NaN).
nlohmann::ordered_json json_point_or_null(Vec3d p) { return std::isnan(p.x) ? nlohmann::ordered_json() : json_point(p); }

void write_csv(std::FILE* f, const Scene& s, const CoplanarReport& c, const RayOverlapReport& r) {
  std::fputs("kind,solid_a,name_a,solid_b,name_b,count,exact,same_facing,opposite_facing,area,max_depth,penetration,x,y,z\n", f);
  auto names = [&](std::uint32_t a, std::uint32_t b) {
    return std::to_string(a) + "," + csv_field(s.geometry(a).name) + "," + std::to_string(b) + "," +
           csv_field(s.geometry(b).name);
  };
  for (const InterferencePair& p : r.interferences)
    std::fprintf(f, "interference,%s,%zu,,,,,%s,%s,%s,%s,%s\n", names(p.a, p.b).c_str(), p.count,
                 exact_number(p.max_depth).c_str(), exact_number(p.penetration).c_str(),
                 exact_number(p.max_depth_entry.x).c_str(), exact_number(p.max_depth_entry.y).c_str(),
                 exact_number(p.max_depth_entry.z).c_str());
  for (const ContactPair& p : r.contacts)
    std::fprintf(f, "contact,%s,%zu,,,,,,,%s,%s,%s\n", names(p.a, p.b).c_str(), p.count,
                 exact_number(p.where.x).c_str(), exact_number(p.where.y).c_str(), exact_number(p.where.z).c_str());
  for (const CoplanarSolidPair& p : c.solid_pairs)
    std::fprintf(f, "coplanar,%s,%zu,%zu,%zu,%zu,%s,,,%s,%s,%s\n", names(p.a, p.b).c_str(), p.pairs, p.exact_pairs,
                 p.same_facing, p.opposite_facing, exact_number(p.area).c_str(), exact_number(p.where.x).c_str(),
                 exact_number(p.where.y).c_str(), exact_number(p.where.z).c_str());
}

void write_json(std::FILE* f, const Scene& s, const OverlapsCli& o, const CoplanarReport& c, const RayOverlapReport& r,
                const SolidPairReport& sp) {
  nlohmann::ordered_json j;
  j["models"] = o.model.models;
  j["solids"] = nlohmann::ordered_json::array();
  for (std::uint32_t g = 0; g < s.geometries().size(); ++g)
    j["solids"].push_back({{"id", g}, {"name", s.geometry(g).name}, {"source", s.geometry(g).source}});
  j["rays"] = o.rays;
  j["coplanar_hits"] = {{"rays", r.coplanar.rays},
                        {"rays_hitting", r.coplanar.rays_hitting},
                        {"rays_equal_t", r.coplanar.rays_equal_t},
                        {"rays_within_epsilon", r.coplanar.rays_within_eps},
                        {"epsilon", r.coplanar.epsilon},
                        {"share_equal_t", r.coplanar.share_equal()},
                        {"share_within_epsilon", r.coplanar.share_within_eps()}};
  auto& inter = j["interferences"] = nlohmann::ordered_json::array();
  for (const InterferencePair& p : r.interferences)
    inter.push_back({{"solid_a", p.a},
                     {"solid_b", p.b},
                     {"count", p.count},
                     {"max_depth", p.max_depth},
                     {"max_depth_entry", json_point(p.max_depth_entry)},
                     {"max_depth_ray", p.max_depth_ray},
                     {"axis_max_depth",
                      {json_or_null(p.axis_max_depth[0]), json_or_null(p.axis_max_depth[1]),
                       json_or_null(p.axis_max_depth[2])}},
                     {"penetration", json_or_null(p.penetration)}});
  auto& cont = j["contacts"] = nlohmann::ordered_json::array();
  for (const ContactPair& p : r.contacts)
    cont.push_back({{"solid_a", p.a}, {"solid_b", p.b}, {"rays", p.count}, {"where", json_point(p.where)}});
  j["coplanar_tolerance"] = c.tolerance;
  auto& cop = j["coplanar"] = nlohmann::ordered_json::array();
  for (const CoplanarSolidPair& p : c.solid_pairs)
    cop.push_back({{"solid_a", p.a}, {"solid_b", p.b}, {"triangle_pairs", p.pairs}, {"exact", p.exact_pairs},
                   {"same_facing", p.same_facing}, {"opposite_facing", p.opposite_facing}, {"area", p.area},
                   {"where", json_point(p.where)}});
  auto& pairs = j["coplanar_triangle_pairs"] = nlohmann::ordered_json::array();
  for (const CoplanarPair& p : c.pairs)
    pairs.push_back({{"solid_a", p.geom_a}, {"triangle_a", p.prim_a}, {"solid_b", p.geom_b}, {"triangle_b", p.prim_b},
                     {"area", p.area}, {"exact", p.exact}, {"same_facing", p.same_facing},
                     {"centroid", json_point(p.centroid)}});
  auto& iv = j["interference_intervals"] = nlohmann::ordered_json::array();
  for (const Interference& x : r.intervals)
    iv.push_back({{"ray", x.ray}, {"solid_a", x.a}, {"solid_b", x.b}, {"depth", x.depth},
                  {"entry", json_point(x.entry)}, {"exit", json_point(x.exit)}});
  j["clearance"] = sp.clearance;
  auto& solid_pairs = j["pairs"] = nlohmann::ordered_json::array();
  for (const SolidPair& p : sp.pairs)
    solid_pairs.push_back({{"solid_a", p.solid_a},
                           {"solid_b", p.solid_b},
                           {"kind", enum_name(p.kind)},
                           {"gap", json_or_null(p.gap)},
                           {"depth", json_or_null(p.depth)},
                           {"overlap_length", json_or_null(p.overlap_length)},
                           {"volume", json_or_null(p.volume)},
                           {"point", json_point_or_null(p.point)},
                           {"point_b", json_point_or_null(p.point_b)}});
  write_json_document(f, j);
}

void write_vtp_result(std::FILE* f, const Scene& s, const TriangleOverlapArrays& a, const SolidPairReport& sp) {
  PolyData d;
  for (const Geometry& g : s.geometries()) {
    const auto base = std::uint32_t(d.points.size());
    d.points.insert(d.points.end(), g.vertices.begin(), g.vertices.end());
    for (const Tri& t : g.triangles) d.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  std::vector<std::int32_t> solid(a.solid.begin(), a.solid.end());
  d.cell_data.emplace_back("OverlapCount", a.overlap_count);
  d.cell_data.emplace_back("CoplanarPartner", a.coplanar_partner);
  d.cell_data.emplace_back("SolidId", std::move(solid));
  d.cell_data.emplace_back("CoplanarCount", a.coplanar_count);
  d.cell_data.emplace_back("CoplanarHits", a.coplanar_hits);
  d.cell_data.emplace_back("InterferenceHits", a.interference_hits);
  d.cell_data.emplace_back("Clearance", sp.triangle_clearance);
  if (!write_vtp(f, d)) throw std::runtime_error("write error");
}

void print_summary(const Scene& s, const CoplanarReport& c, const RayOverlapReport& r, const OverlapsCli& o) {
  std::printf("%zu rays (%s), %zu hit something: %.3f%% meet crossings at equal t, %.3f%% within %g\n",
              r.coplanar.rays, o.rays.c_str(), r.coplanar.rays_hitting, 100 * r.coplanar.share_equal(),
              100 * r.coplanar.share_within_eps(), r.coplanar.epsilon);
  if (r.interferences.empty()) std::printf("no interference between solids along the rays\n");
  for (const InterferencePair& p : r.interferences) {
    std::printf("INTERFERENCE %s <-> %s: %zu ray intervals, max depth %g at (%g, %g, %g)", solid_label(s, p.a).c_str(),
                solid_label(s, p.b).c_str(), p.count, p.max_depth, p.max_depth_entry.x, p.max_depth_entry.y,
                p.max_depth_entry.z);
    if (!std::isnan(p.penetration)) std::printf(", penetration ~%g (smallest per-axis depth)", p.penetration);
    std::printf("\n");
  }
  for (const ContactPair& p : r.contacts)
    std::printf("contact %s <-> %s: touching faces crossed by %zu rays, e.g. at (%g, %g, %g)\n",
                solid_label(s, p.a).c_str(), solid_label(s, p.b).c_str(), p.count, p.where.x, p.where.y, p.where.z);
  for (const CoplanarSolidPair& p : c.solid_pairs) {
    const bool self = p.a == p.b;
    std::printf("coplanar %s%s%s: %zu triangle pairs (%zu exact), %zu same-facing (duplicated faces), %zu opposite "
                "(contact), area %g, e.g. at (%g, %g, %g)\n",
                solid_label(s, p.a).c_str(), self ? " (within itself)" : " <-> ",
                self ? "" : solid_label(s, p.b).c_str(), p.pairs, p.exact_pairs, p.same_facing, p.opposite_facing,
                p.area, p.where.x, p.where.y, p.where.z);
  }
  if (r.rays_ending_inside)
    std::printf("note: %zu rays ended inside a solid (open mesh?): see `pierce info`\n", r.rays_ending_inside);
}

// One line of counts per kind, then one row per pair ("-" where a field does not apply).
void print_pairs(const Scene& s, const SolidPairReport& r) {
  std::size_t count[3] = {0, 0, 0};
  for (const SolidPair& p : r.pairs) ++count[int(p.kind)];
  std::printf("pairs within clearance %g: %zu clash, %zu contact, %zu clearance\n", r.clearance, count[0], count[1],
              count[2]);
  if (r.pairs.empty()) return;
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return std::isnan(v) ? std::string("-") : std::string(b);
  };
  auto point = [](Vec3d p) {
    char b[96];
    std::snprintf(b, sizeof b, "(%g, %g, %g)", p.x, p.y, p.z);
    return std::isnan(p.x) ? std::string("-") : std::string(b);
  };
  std::printf("%-9s %-20s %-20s %10s %10s %10s %10s  %s  %s\n", "kind", "solid_a", "solid_b", "gap", "depth",
              "overlap", "volume", "point", "point_b");
  for (const SolidPair& p : r.pairs)
    std::printf("%-9s %-20s %-20s %10s %10s %10s %10s  %s  %s\n", std::string(enum_name(p.kind)).c_str(),
                solid_label(s, p.solid_a).c_str(), solid_label(s, p.solid_b).c_str(), num(p.gap).c_str(),
                num(p.depth).c_str(), num(p.overlap_length).c_str(), num(p.volume).c_str(), point(p.point).c_str(),
                point(p.point_b).c_str());
}

// False-colour picture of OverlapCount per triangle (blue: none); false if cancelled.
bool write_png(const Accel& accel, const TriangleOverlapArrays& a, const OverlapsCli& o) {
  const Scene& scene = accel.scene();
  ElementField field;
  field.at = ElementField::At::face;
  field.values.resize(scene.geometries().size());
  std::uint32_t most = 0;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    auto& vals = field.values[g];
    vals.resize(scene.geometry(g).triangles.size());
    for (std::size_t p = 0; p < vals.size(); ++p) {
      const std::uint32_t count = a.overlap_count[a.tri_offset[g] + p];
      vals[p] = double(count);
      most = std::max(most, count);
    }
  }
  FalseColourOptions fo;
  parse_picture_size("--png-size", o.png_size, fo.width, fo.height);
  fo.view_dir = parse_view_direction("--png-view", o.png_view);
  fo.map = ColourMap::cool_warm;
  fo.range_min = 0;
  fo.range_max = std::max<std::uint32_t>(most, 1);
  const auto img = write_picture(accel, field, fo, o.png, o.force, o.progress);
  if (!img) return false;
  std::printf("picture %s: %dx%d, OverlapCount 0 (blue) .. %g (red)\n", o.png.c_str(), img->width, img->height,
              img->range_max);
  return true;
}

int run_overlaps(const OverlapsCli& o) {
  InterruptGuard guard;
  const Format format = format_of(o.out);
  OutputFile::check_target(o.out, o.force);
  const KernelKind kernel = exact_kernel_option(o.kernel);
  if (!(o.tol >= 0) || !std::isfinite(o.tol)) throw InputError("--tol must be a finite number >= 0");
  if (!(o.clearance >= 0) || !std::isfinite(o.clearance))
    throw InputError("--clearance must be a finite number >= 0");
  check_picture_options(o.png, o.out, o.force, o.png_size, o.png_view);

  Scene scene;
  load_models(scene, o.model);
  if (interrupted()) return cancelled();
  const std::vector<Ray> rays = make_rays(o.rays, scene);
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  CoplanarOptions copts;
  copts.tolerance = o.tol;
  LazyProgressBar cop_bar("coplanar", o.progress);
  const CoplanarReport cop = find_coplanar_overlaps(scene, copts, std::ref(cop_bar));
  cop_bar.finish();
  if (!cop.completed || interrupted()) return cancelled();

  RayOverlapOptions ropts;
  ropts.kernel = kernel;
  ropts.epsilon_rel = o.ray_eps;
  LazyProgressBar ray_bar("rays", o.progress);
  const RayOverlapReport rep = analyse_ray_overlaps(accel, rays, ropts, std::ref(ray_bar));
  ray_bar.finish();
  if (!rep.completed || interrupted()) return cancelled();

  // The pairs reuse the interference of an axis grid; other rays leave them a grid of their own.
  LazyProgressBar pair_bar("pairs", o.progress);
  const int grid_n = axes_grid_n(o.rays);
  SolidPairOptions popts;
  popts.clearance = o.clearance;
  popts.kernel = kernel;
  popts.triangle_clearance = format == Format::vtp;  // the one output holding the map
  const SolidPairReport pairs =
      grid_n > 0 ? classify_solid_pairs(accel, cop, rep, grid_n, o.clearance, popts.triangle_clearance, std::ref(pair_bar))
                 : analyse_solid_pairs(accel, popts, std::ref(pair_bar));
  pair_bar.finish();
  if (!pairs.completed || interrupted()) return cancelled();

  print_summary(scene, cop, rep, o);
  print_pairs(scene, pairs);
  std::fflush(stdout);
  if (!o.png.empty() && !write_png(accel, triangle_overlap_arrays(scene, &cop, &rep), o)) return cancelled();
  std::fflush(stdout);
  return write_output(o.out, format, o.force, [&](Format f, std::FILE* out) {
    switch (f) {
      case Format::vtp: write_vtp_result(out, scene, triangle_overlap_arrays(scene, &cop, &rep), pairs); break;
      case Format::csv: write_csv(out, scene, cop, rep); break;
      case Format::json: write_json(out, scene, o, cop, rep, pairs); break;
      case Format::none: break;
    }
  });
}

}  // namespace

std::function<int()> register_overlaps(CLI::App& app) {
  const auto [o, cmd] = add_model_command<OverlapsCli>(app,
      "overlaps", "Coplanar overlapping faces, coplanar-hit statistic and solid-solid interference along rays");
  cmd->add_option("--tol", o->tol,
                  "Also report faces within this distance of coplanar (model units); 0 = exactly coplanar only")
      ->capture_default_str();
  cmd->add_option("--clearance", o->clearance,
                  "Also report solid pairs closer than this (model units) as clearance; 0 = clash and contact only")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--rays", o->rays,
                  "Rays for the statistic and interference: axes:n=N (N x N along each axis), "
                  "grid:axis=x|y|z,n=N, random:n=N[,seed=S], or a CSV file")
      ->capture_default_str();
  cmd->add_option("--ray-eps", o->ray_eps, "Coplanar-hit epsilon, relative to the scene diagonal")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  add_exact_kernel_option(cmd, o->kernel);
  cmd->add_option("-o,--out", o->out, "Output file: .vtp (per-triangle arrays), .csv (per solid pair) or .json (all, with the pairs)");
  cmd->add_option("--png", o->png, "Also render a false-colour picture of OverlapCount per triangle to this PNG");
  add_camera_options(cmd, o->png_size, o->png_view, "Picture");
  add_force_and_progress_flags(cmd, o->force, o->progress, "existing output files");
  return [o] { return run_overlaps(*o); };
}

}  // namespace pierce::cli
