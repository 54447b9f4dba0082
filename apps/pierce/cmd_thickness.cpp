// `pierce thickness MODEL`: wall-thickness map per vertex or per face (ray, cone or sphere
// method), written as VTP (ParaView), CSV or JSON, with per-solid statistics on stdout.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>

#include <nlohmann/json.hpp>

#include "csv_text.h"
#include "picture.h"
#include "command.h"
#include "interrupt.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/render/false_colour.h"
#include "pierce/solid_reference.h"
#include "progress.h"
#include "vtp_writer.h"

namespace pierce::cli {

namespace {

using analysis::SampleAt;
using analysis::ThicknessMethod;
using analysis::ThicknessResult;

struct ThicknessCli {
  ModelArgs model;
  std::string method = "ray", per = "vertex", kernel = "queue";
  std::string origin_offsets = "auto", offset_set = "center";
  double min_thickness = 0;
  double max_distance = std::numeric_limits<double>::infinity();
  int cone_rays = 30;
  double cone_angle = 120;
  std::vector<std::string> solids;
  std::string out;
  std::string png, png_size = "800x600", png_view = "-1,-1,-1";
  bool force = false, progress = false;
};

// Solids by name, #N or N (solid_reference.h).
std::vector<std::uint32_t> resolve_solids(const Scene& scene, const std::vector<std::string>& wanted) {
  std::vector<std::uint32_t> ids;
  for (const std::string& w : wanted) {
    const std::vector<std::uint32_t> found = find_solids(scene, w);
    if (found.empty())
      throw InputError("--solid '" + w + "': no solid with that name or id (" +
                       std::to_string(scene.geometries().size()) + " solids; see `pierce info`)");
    ids.insert(ids.end(), found.begin(), found.end());
  }
  return ids;
}

void write_csv(std::FILE* f, const Scene& scene, const ThicknessResult& r) {
  std::fputs("id,solid,element,x,y,z,thickness,thin,status,name\n", f);
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec3d p = r.point[i];
    std::fprintf(f, "%zu,%u,%u,%s,%s,%s,%s,%d,%s,%s\n", i, r.solid[i], r.element[i], exact_number(p.x).c_str(),
                 exact_number(p.y).c_str(), exact_number(p.z).c_str(), exact_number(r.thickness[i]).c_str(),
                 int(r.thin[i]), std::string(analysis::status_name(r.status[i])).c_str(),
                 csv_field(scene.geometry(r.solid[i]).name).c_str());
  }
}

nlohmann::ordered_json solid_stats_json(const analysis::SolidThickness& s, const Scene& scene) {
  nlohmann::ordered_json j{{"solid", s.geom},       {"name", s.name},           {"source", scene.geometry(s.geom).source},
                           {"elements", s.elements}, {"valid", s.valid},         {"no_exit", s.no_exit},
                           {"no_normal", s.no_normal}, {"thin", s.thin}};
  if (s.valid > 0) {
    j["min"] = s.summary.min;
    j["max"] = s.summary.max;
    j["mean"] = s.summary.mean;
    nlohmann::ordered_json p;
    for (auto [q, v] : s.summary.percentiles) p["p" + exact_number(q)] = v;
    j["percentiles"] = p;
    j["histogram"] = {{"edges", s.summary.histogram.edges}, {"counts", s.summary.histogram.counts}};
  }
  return j;
}

void write_json(std::FILE* f, const Scene& scene, const ThicknessResult& r, const ThicknessCli& o,
                const analysis::ThicknessOptions& opts) {
  nlohmann::ordered_json j;
  j["models"] = o.model.models;
  j["method"] = o.method;
  j["per"] = o.per;
  j["min_thickness"] = opts.min_thickness;
  if (std::isfinite(opts.max_distance)) j["max_distance"] = opts.max_distance;
  j["kernel"] = o.kernel;
  j["solids"] = nlohmann::ordered_json::array();
  for (const auto& s : r.solids) j["solids"].push_back(solid_stats_json(s, scene));
  auto& el = j["elements"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec3d p = r.point[i];
    nlohmann::ordered_json e{{"id", i}, {"solid", r.solid[i]}, {"element", r.element[i]}, {"x", p.x}, {"y", p.y}, {"z", p.z}};
    e["thickness"] = std::isnan(r.thickness[i]) ? nlohmann::ordered_json() : nlohmann::ordered_json(r.thickness[i]);
    e["thin"] = bool(r.thin[i]);
    e["status"] = analysis::status_name(r.status[i]);
    el.push_back(std::move(e));
  }
  const std::string text = j.dump(1);
  std::fwrite(text.data(), 1, text.size(), f);
  std::fputc('\n', f);
}

void write_vtp_result(std::FILE* f, const Scene& scene, const ThicknessResult& r) {
  PolyData d;
  std::vector<std::int32_t> cell_solid;
  std::vector<std::int32_t> point_solid;
  // The sampled solids, in result order, each once.
  std::vector<std::uint32_t> solids;
  for (const auto& s : r.solids) solids.push_back(s.geom);
  for (std::uint32_t g : solids) {
    const Geometry& geo = scene.geometry(g);
    const auto base = std::uint32_t(d.points.size());
    d.points.insert(d.points.end(), geo.vertices.begin(), geo.vertices.end());
    point_solid.insert(point_solid.end(), geo.vertices.size(), std::int32_t(g));
    for (const Tri& t : geo.triangles) d.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    cell_solid.insert(cell_solid.end(), geo.triangles.size(), std::int32_t(g));
  }
  std::vector<std::uint8_t> status(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) status[i] = std::uint8_t(r.status[i]);
  auto& target = r.per == SampleAt::vertex ? d.point_data : d.cell_data;
  target.emplace_back("Thickness", r.thickness);
  target.emplace_back("Thin", r.thin);
  target.emplace_back("Status", std::move(status));
  d.point_data.emplace_back("SolidId", std::move(point_solid));
  d.cell_data.emplace_back("SolidId", std::move(cell_solid));
  if (!write_vtp(f, d)) throw std::runtime_error("write error");
}

void print_summary(const Scene& scene, const ThicknessResult& r, const analysis::ThicknessOptions& opts) {
  const char* what = r.per == SampleAt::vertex ? "vertices" : "faces";
  for (const auto& s : r.solids) {
    std::printf("solid %u %s: %zu %s, %zu measured", s.geom, solid_label(scene, s.geom).c_str(), s.elements, what,
                s.valid);
    if (s.no_exit) std::printf(", %zu without exit (open mesh or beyond max distance)", s.no_exit);
    if (s.no_normal) std::printf(", %zu without normal", s.no_normal);
    std::printf("\n");
    if (s.valid == 0) continue;
    auto pct = [&](double q) {
      for (auto [k, v] : s.summary.percentiles)
        if (k == q) return v;
      return std::numeric_limits<double>::quiet_NaN();
    };
    std::printf("  min %g  p5 %g  median %g  p95 %g  max %g  mean %g\n", s.summary.min, pct(5), pct(50), pct(95),
                s.summary.max, s.summary.mean);
    if (opts.min_thickness > 0) std::printf("  thin (< %g): %zu\n", opts.min_thickness, s.thin);
  }
}

// The thickness per vertex or face of each sampled solid (NaN elsewhere), thin elements marked.
ElementField thickness_field(const Scene& scene, const ThicknessResult& r) {
  ElementField field;
  field.at = r.per == SampleAt::vertex ? ElementField::At::vertex : ElementField::At::face;
  field.values.resize(scene.geometries().size());
  field.marked.resize(scene.geometries().size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Geometry& g = scene.geometry(r.solid[i]);
    const std::size_t n = r.per == SampleAt::vertex ? g.vertices.size() : g.triangles.size();
    auto& vals = field.values[r.solid[i]];
    auto& marks = field.marked[r.solid[i]];
    if (vals.empty()) vals.assign(n, std::numeric_limits<double>::quiet_NaN()), marks.assign(n, 0);
    vals[r.element[i]] = r.thickness[i];
    marks[r.element[i]] = r.thin[i];
  }
  return field;
}

// False-colour picture of the thickness map; false if cancelled.
bool write_png(const Accel& accel, const ThicknessResult& r, const ThicknessCli& o) {
  FalseColourOptions fo;
  parse_picture_size("--png-size", o.png_size, fo.width, fo.height);
  fo.view_dir = parse_view_direction("--png-view", o.png_view);
  const auto img = write_picture(accel, thickness_field(accel.scene(), r), fo, o.png, o.force, o.progress);
  if (!img) return false;
  std::printf("picture %s: %dx%d, colour range %g .. %g (grey: no thickness%s)\n", o.png.c_str(), img->width,
              img->height, img->range_min, img->range_max, o.min_thickness > 0 ? ", red: thin" : "");
  return true;
}

int run_thickness(const ThicknessCli& o) {
  InterruptGuard guard;
  const Format format = format_of(o.out);
  OutputFile::check_target(o.out, o.force);  // before any long work
  const KernelKind kernel = exact_kernel_option(o.kernel);
  check_picture_options(o.png, o.out, o.force, o.png_size, o.png_view);

  Scene scene;
  load_models(scene, o.model);
  if (interrupted()) return cancelled();
  analysis::ThicknessOptions opts;
  opts.method = parse_enum_or_throw<ThicknessMethod>(o.method);
  opts.per = parse_enum_or_throw<SampleAt>(o.per);
  opts.min_thickness = o.min_thickness;
  opts.max_distance = o.max_distance;
  opts.cone_rays = o.cone_rays;
  opts.cone_angle_deg = o.cone_angle;
  opts.kernel = kernel;
  // `auto` is the library's default, which is off (see --origin-offsets' help).
  opts.origin_offsets = o.origin_offsets == "on" ? analysis::OffsetMode::on : analysis::OffsetMode::off;
  opts.offset_set = parse_hemisphere_set(o.offset_set).value_or(HemisphereSet::center);
  opts.solids = resolve_solids(scene, o.solids);
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  LazyProgressBar bar("thickness", o.progress);
  const ThicknessResult r = analysis::compute_thickness(accel, opts, std::ref(bar));
  bar.finish();
  if (!r.completed || interrupted()) return cancelled();

  print_summary(scene, r, opts);
  std::fflush(stdout);
  if (!o.png.empty() && !write_png(accel, r, o)) return cancelled();
  std::fflush(stdout);
  return write_output(o.out, format, o.force, [&](Format f, std::FILE* out) {
    switch (f) {
      case Format::vtp: write_vtp_result(out, scene, r); break;
      case Format::csv: write_csv(out, scene, r); break;
      case Format::json: write_json(out, scene, r, o, opts); break;
      case Format::none: break;
    }
  });
}

}  // namespace

std::function<int()> register_thickness(CLI::App& app) {
  auto o = std::make_shared<ThicknessCli>();
  CLI::App* cmd = app.add_subcommand("thickness", "Wall-thickness map per vertex or face (VTP, CSV or JSON)");
  add_model_args(cmd, o->model, false);
  cmd->add_option("--method", o->method,
                  "ray: along the inward normal to where the ray leaves the solid; cone: shape diameter function "
                  "over --cone-rays rays; sphere: diameter of the largest inscribed ball touching the point")
      ->check(CLI::IsMember(enum_names<ThicknessMethod>()))
      ->capture_default_str();
  cmd->add_option("--per", o->per, "Sample at every vertex or every face (triangle centroid)")
      ->check(CLI::IsMember(enum_names<SampleAt>()))
      ->capture_default_str();
  cmd->add_option("--min", o->min_thickness, "Thin flag: thickness below this")->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-distance", o->max_distance, "Search no farther; beyond it: no thickness (status no_exit)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--cone-rays", o->cone_rays, "Cone method: rays per sample")->check(CLI::Range(1, 10000))->capture_default_str();
  cmd->add_option("--cone-angle", o->cone_angle, "Cone method: full opening angle, degrees")
      ->check(CLI::Range(0.1, 179.0))
      ->capture_default_str();
  cmd->add_option("--solid", o->solids, "Only these solids (name, #N or N for geometry id N; repeatable); the others still bound rays");
  add_exact_kernel_option(cmd, o->kernel);
  cmd->add_option("--origin-offsets", o->origin_offsets,
                  "Start face-sample rays where they leave an empty hemisphere on their triangle (Zoet); "
                  "results are identical, only the work changes. auto: where the bench shows it pays "
                  "(docs/BENCHMARKS.md; currently nowhere, so auto = off)")
      ->check(CLI::IsMember({"on", "off", "auto"}))
      ->capture_default_str();
  cmd->add_option("--offset-set", o->offset_set, "Hemisphere set for --origin-offsets")
      ->check(CLI::IsMember({"center", "vertex", "median", "median+center", "polygon", "random"}))
      ->capture_default_str();
  cmd->add_option("-o,--out", o->out, "Output file: .vtp (ParaView), .csv or .json; without it only the summary");
  cmd->add_option("--png", o->png,
                  "Also render a false-colour picture of the map to this PNG (grey: no thickness; red: thin)");
  add_camera_options(cmd, o->png_size, o->png_view, "Picture");
  add_force_and_progress_flags(cmd, o->force, o->progress, "existing output files");
  return [o] { return run_thickness(*o); };
}

}  // namespace pierce::cli
