// `pierce thickness MODEL`: wall-thickness map per vertex or per face (ray, cone or sphere
// method), written as VTP (ParaView), CSV or JSON, with per-solid statistics on stdout.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <limits>
#include <tuple>
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
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/io/cad_surfaces.h"
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
  std::string method{enum_name(analysis::ThicknessOptions{}.method)}, per{enum_name(analysis::ThicknessOptions{}.per)},
      kernel{kernel_name(kDefaultKernel)};
  std::string origin_offsets = "auto", offset_set = "center";
  double min_thickness = 0;
  double max_thickness = std::numeric_limits<double>::infinity();
  double max_distance = std::numeric_limits<double>::infinity();
  int cone_rays = 30;
  double cone_angle = 120;
  std::vector<std::string> solids;
  std::string out;
  std::string at;  // --at points.csv
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

// One CSV line split into fields (RFC 4180 quotes allowed), spaces around fields trimmed.
std::vector<std::string> split_csv(const std::string& line, const std::string& where) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
      else if (c == '"') quoted = false;
      else cur += c;
    } else if (c == '"' && cur.find_first_not_of(" \t") == std::string::npos) {
      quoted = was_quoted = true;
      cur.clear();
    } else if (c == ',') {
      out.push_back(was_quoted ? cur : trim_text(cur));
      cur.clear();
      was_quoted = false;
    } else if (!(was_quoted && (c == ' ' || c == '\t'))) {
      cur += c;
    }
  }
  if (quoted) throw InputError(where + ": unterminated quote");
  out.push_back(was_quoted ? cur : trim_text(cur));
  return out;
}

struct AtPoints {
  std::vector<std::uint32_t> solids;
  std::vector<Vec3d> points, normals;  // normals empty when the file has none
};

// `--at` file: a header naming the columns solid,x,y,z and optionally nx,ny,nz (any order), then
// one point per line. Blank lines and lines starting with '#' are skipped. Every bad row is an
// InputError "FILE, line N: ...".
AtPoints read_at_points(const std::string& path, const Scene& scene) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the points file");
  std::string line;
  std::size_t n = 0;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    ++n;
    const std::string t = trim_text(line);
    if (t.empty() || t[0] == '#') continue;
    header = split_csv(t, path + ", line " + std::to_string(n));
  }
  if (header.empty()) throw InputError(path + ": no header (expected solid,x,y,z[,nx,ny,nz])");
  auto col = [&](const char* name) -> int {
    int found = -1;
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) {
        if (found >= 0) throw InputError(path + ", line " + std::to_string(n) + ": column '" + name + "' twice");
        found = int(i);
      }
    return found;
  };
  const int cs = col("solid"), cx = col("x"), cy = col("y"), cz = col("z");
  const int cnx = col("nx"), cny = col("ny"), cnz = col("nz");
  if (cs < 0 || cx < 0 || cy < 0 || cz < 0)
    throw InputError(path + ", line " + std::to_string(n) + ": header needs the columns solid,x,y,z (got '" +
                     trim_text(line) + "')");
  const bool with_normals = cnx >= 0 || cny >= 0 || cnz >= 0;
  if (with_normals && (cnx < 0 || cny < 0 || cnz < 0))
    throw InputError(path + ", line " + std::to_string(n) + ": give all of nx,ny,nz or none");
  AtPoints out;
  while (std::getline(in, line)) {
    ++n;
    const std::string t = trim_text(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = path + ", line " + std::to_string(n);
    const std::vector<std::string> f = split_csv(t, where);
    if (f.size() != header.size())
      throw InputError(where + ": " + std::to_string(f.size()) + " fields, the header has " +
                       std::to_string(header.size()));
    auto number = [&](int c, const char* what) {
      const std::string& v = f[std::size_t(c)];
      char* end = nullptr;
      errno = 0;
      const double d = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(d))
        throw InputError(where + ": " + what + " '" + v + "' is not a finite number");
      return d;
    };
    const std::string& solid = f[std::size_t(cs)];
    const std::vector<std::uint32_t> found = find_solids(scene, solid);  // name, #N or N (solid_reference.h)
    if (found.empty())
      throw InputError(where + ": no solid '" + solid + "' (known: " + known_solid_names(scene) + ")");
    if (found.size() > 1)
      throw InputError(where + ": " + std::to_string(found.size()) + " solids are named '" + solid +
                       "'; give the one meant as #N (its id in `pierce info`)");
    const std::uint32_t id = found.front();
    out.solids.push_back(id);
    out.points.push_back({number(cx, "x"), number(cy, "y"), number(cz, "z")});
    if (with_normals) {
      const Vec3d nv{number(cnx, "nx"), number(cny, "ny"), number(cnz, "nz")};
      if (!(length(nv) > 0)) throw InputError(where + ": the normal nx,ny,nz is zero");
      out.normals.push_back(nv);
    }
  }
  if (out.points.empty()) throw InputError(path + ": no points after the header");
  return out;
}

void write_csv(std::FILE* f, const Scene& scene, const ThicknessResult& r) {
  std::fputs("id,solid,element,x,y,z,thickness,thin,status,name,region\n", f);
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec3d p = r.point[i];
    std::fprintf(f, "%zu,%u,%u,%s,%s,%s,%s,%d,%s,%s,%d\n", i, r.solid[i], r.element[i], exact_number(p.x).c_str(),
                 exact_number(p.y).c_str(), exact_number(p.z).c_str(), exact_number(r.thickness[i]).c_str(),
                 int(r.thin[i]), std::string(analysis::status_name(r.status[i])).c_str(),
                 csv_field(scene.geometry(r.solid[i]).name).c_str(), int(r.region[i]));
  }
}

nlohmann::ordered_json solid_stats_json(const analysis::SolidThickness& s, const Scene& scene) {
  nlohmann::ordered_json j{{"solid", s.geom},       {"name", s.name},           {"source", scene.geometry(s.geom).source},
                           {"elements", s.elements}, {"valid", s.valid},         {"no_exit", s.no_exit},
                           {"no_normal", s.no_normal}, {"thin", s.thin}};
  if (s.exact || s.tessellation > 0) {
    j["tessellation"] = s.tessellation;
    j["exact"] = s.exact;
    j["edge_samples"] = s.edge_samples;
  }
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

// The regions as JSON (thickness_regions.h): the extreme thickness under `extreme`.
nlohmann::ordered_json regions_json(const std::vector<analysis::ThicknessRegion>& regions, const char* extreme) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const analysis::ThicknessRegion& g : regions)
    a.push_back({{"solid", g.solid},
                 {extreme, g.thickness},
                 {"area", g.area},
                 {"area_sides", "both"},
                 {"point", json_point(g.point)},
                 {"exit", json_point(g.exit)},
                 {"samples", g.samples},
                 {"faces", g.faces}});
  return a;
}

void write_json(std::FILE* f, const Scene& scene, const ThicknessResult& r, const ThicknessCli& o,
                const analysis::ThicknessOptions& opts) {
  nlohmann::ordered_json j;
  j["models"] = o.model.models;
  j["method"] = o.method;
  j["per"] = o.at.empty() ? o.per : "point";
  j["min_thickness"] = opts.min_thickness;
  if (std::isfinite(opts.max_thickness)) j["max_thickness"] = opts.max_thickness;
  if (std::isfinite(opts.max_distance)) j["max_distance"] = opts.max_distance;
  j["kernel"] = o.kernel;
  j["solids"] = nlohmann::ordered_json::array();
  for (const auto& s : r.solids) j["solids"].push_back(solid_stats_json(s, scene));
  auto& el = j["elements"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec3d p = r.point[i];
    nlohmann::ordered_json e{{"id", i}, {"solid", r.solid[i]}, {"element", r.element[i]}, {"x", p.x}, {"y", p.y}, {"z", p.z}};
    e["thickness"] = json_or_null(r.thickness[i]);
    e["thin"] = bool(r.thin[i]);
    e["status"] = analysis::status_name(r.status[i]);
    if (!r.brep_faces.empty()) e["brep_faces"] = r.brep_faces[i];  // CAD: faces sampled, smallest kept
    e["region"] = r.region[i];
    el.push_back(std::move(e));
  }
  j["thin_regions"] = regions_json(r.thin_regions, "min_thickness");
  j["thick_regions"] = regions_json(r.thick_regions, "max_thickness");
  write_json_document(f, j);
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
  target.emplace_back("Region", r.region);  // -1: none; see ThicknessResult::region
  if (!r.brep_faces.empty()) target.emplace_back("BrepFaces", r.brep_faces);  // CAD: faces sampled per element
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
    if (s.tessellation)
      std::printf(", %zu excluded as tessellation artefacts (folded triangles, no exit in a closed solid or no "
                  "B-rep solution; status tessellation)",
                  s.tessellation);
    std::printf("\n");
    if (s.exact) {
      std::printf("  sampled on the exact B-rep, exits refined on it");
      if (s.edge_samples)
        std::printf("; %zu vertices on B-rep edges show the smaller of their per-face samples", s.edge_samples);
      std::printf("\n");
    }
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

// The ten thinnest regions as a table, and how many regions there are.
void print_regions(const Scene& scene, const ThicknessResult& r, const analysis::ThicknessOptions& opts) {
  if (opts.min_thickness > 0) {
    std::printf("thin regions (thickness < %g): %zu%s\n", opts.min_thickness, r.thin_regions.size(),
                r.thin_regions.size() > 10 ? ", the ten thinnest:" : "");
    if (!r.thin_regions.empty())
      std::printf("  %6s  %-20s %12s %12s %8s  %s\n", "region", "solid", "min", "area (both)", "samples", "point");
    for (std::size_t k = 0; k < std::min<std::size_t>(10, r.thin_regions.size()); ++k) {
      const analysis::ThicknessRegion& g = r.thin_regions[k];
      std::printf("  %6zu  %-20s %12g %12g %8zu  %g %g %g\n", k, solid_label(scene, g.solid).c_str(), g.thickness,
                  g.area, g.samples, g.point.x, g.point.y, g.point.z);
    }
  }
  if (std::isfinite(opts.max_thickness))
    std::printf("thick regions (thickness > %g): %zu\n", opts.max_thickness, r.thick_regions.size());
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
  // The default colour range of every front end (FreeCAD's legend, ParaView's ThicknessColorRange).
  std::tie(fo.range_min, fo.range_max) = analysis::default_color_range(r.thickness, o.min_thickness);
  const auto img = write_picture(accel, thickness_field(accel.scene(), r), fo, o.png, o.force, o.progress);
  if (!img) return false;
  const std::string how = o.min_thickness > 0
    ? "0 to " + exact_number(analysis::kColorRangeThinFactor) + " x --min"
    : "P" + exact_number(analysis::kColorRangePercentiles[0]) + " to P" + exact_number(analysis::kColorRangePercentiles[1]);
  std::printf("picture %s: %dx%d, colour range %g .. %g (%s; beyond it: the end's colour; grey: no thickness%s)\n",
              o.png.c_str(), img->width, img->height, img->range_min, img->range_max, how.c_str(),
              o.min_thickness > 0 ? ", red: thin" : "");
  return true;
}

int run_thickness(const ThicknessCli& o) {
  InterruptGuard guard;
  const Format format = format_of(o.out);
  OutputFile::check_target(o.out, o.force);  // before any long work
  const KernelKind kernel = exact_kernel_option(o.kernel);
  check_picture_options(o.png, o.out, o.force, o.png_size, o.png_view);

  if (!o.at.empty()) {
    if (format == Format::vtp) throw InputError("--at: write the values to .csv or .json (-o), not .vtp");
    if (!o.png.empty()) throw InputError("--at and --png cannot be combined");
  }

  Scene scene;
  const std::vector<LoadedFile> files = load_models(scene, o.model);
  if (interrupted()) return cancelled();
  const std::shared_ptr<const CadSurfaces> exact = cad_surfaces(files, scene.geometries().size());
  AtPoints at;
  if (!o.at.empty()) at = read_at_points(o.at, scene);
  analysis::ThicknessOptions opts;
  opts.method = parse_enum_or_throw<ThicknessMethod>(o.method);
  opts.per = parse_enum_or_throw<SampleAt>(o.per);
  opts.min_thickness = o.min_thickness;
  opts.max_thickness = o.max_thickness;
  if (o.min_thickness > 0 && o.max_thickness < o.min_thickness)
    throw InputError("--max must not be below --min (a sample cannot be both thin and thick)");
  opts.max_distance = o.max_distance;
  opts.cone_rays = o.cone_rays;
  opts.cone_angle_deg = o.cone_angle;
  opts.kernel = kernel;
  // `auto` is the library's default, which is off (see --origin-offsets' help).
  opts.origin_offsets = o.origin_offsets == "on" ? analysis::OffsetMode::on : analysis::OffsetMode::off;
  opts.offset_set = parse_hemisphere_set(o.offset_set).value_or(HemisphereSet::center);
  opts.solids = resolve_solids(scene, o.solids);
  opts.exact = exact.get();
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  LazyProgressBar bar("thickness", o.progress);
  const ThicknessResult r = o.at.empty()
                                ? analysis::compute_thickness(accel, opts, std::ref(bar))
                                : analysis::thickness_at(accel, at.solids, at.points, at.normals, opts, std::ref(bar));
  bar.finish();
  if (!r.completed || interrupted()) return cancelled();

  print_summary(scene, r, opts);
  if (o.at.empty()) print_regions(scene, r, opts);
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
  const auto [o, cmd] = add_model_command<ThicknessCli>(
      app, "thickness", "Wall-thickness map per vertex or face (VTP, CSV or JSON)", /*several=*/false);
  cmd->add_option("--method", o->method,
                  "ray: along the inward normal to where the ray leaves the solid; cone: shape diameter function "
                  "over --cone-rays rays; sphere: diameter of the largest inscribed ball touching the point")
      ->check(CLI::IsMember(enum_names<ThicknessMethod>()))
      ->capture_default_str();
  cmd->add_option("--per", o->per, "Sample at every vertex or every face (triangle centroid)")
      ->check(CLI::IsMember(enum_names<SampleAt>()))
      ->capture_default_str();
  cmd->add_option("--min", o->min_thickness,
                  "Thin: thickness strictly below T (a wall of exactly T is not thin); thin samples connected on a "
                  "solid's surface, both sides of a wall, are reported as regions")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max", o->max_thickness,
                  "Thick: thickness strictly above T2; thick samples are reported as regions like thin ones")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-distance", o->max_distance, "Search no farther; beyond it: no thickness (status no_exit)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--cone-rays", o->cone_rays, "Cone method: rays per sample")->check(CLI::Range(1, 10000))->capture_default_str();
  cmd->add_option("--cone-angle", o->cone_angle, "Cone method: full opening angle, degrees")
      ->check(CLI::Range(0.1, 179.0))
      ->capture_default_str();
  cmd->add_option("--at", o->at,
                  "Thickness at the points of this CSV file (header solid,x,y,z[,nx,ny,nz]; solid by name or id), "
                  "each projected onto its solid's boundary (--per does not apply); -o .csv/.json gets one row per input "
                  "row, in order (id = input row from 0)");
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
