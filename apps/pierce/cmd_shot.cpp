// `pierce shot MODEL... (--from X,Y,Z --dir DX,DY,DZ | --grid SPEC | --rays SPEC) [--csg EXPR]`:
// shotlines as BRL-CAD nirt prints them: per ray, the solids (or CSG regions) it passes through with
// entry/exit points, line-of-sight length, obliquities and normal thickness, and the gaps and
// overlaps between them. A table by default, or CSV / JSON.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "csv_text.h"
#include "command.h"
#include "interrupt.h"
#include "json_text.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/analysis/shotline.h"
#include "pierce/error.h"
#include "pierce/io/ray_source.h"
#include "progress.h"

namespace pierce::cli {

namespace {

using namespace pierce::analysis;

struct ShotCli {
  ModelArgs model;
  std::string from, dir, grid, rays, csg;
  std::string format = "table";
  std::string kernel{kernel_name(kDefaultKernel)};
  std::string out;
  bool force = false, progress = false;
};

// "X,Y,Z" -> vector; `what` names the option in errors.
Vec3d parse_vec3(const std::string& text, const std::string& what) {
  Vec3d v;
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = text.find(',', pos);
    const bool last = i == 2;
    if (last != (end == std::string::npos))
      throw InputError(what + " '" + text + "': expected three comma-separated numbers X,Y,Z");
    const std::string field = text.substr(pos, last ? std::string::npos : end - pos);
    char* stop = nullptr;
    const double x = std::strtod(field.c_str(), &stop);
    if (field.empty() || stop == field.c_str() || *stop != '\0' || !std::isfinite(x))
      throw InputError(what + " '" + text + "': component " + std::to_string(i + 1) + " ('" + field +
                       "') is not a finite number");
    v[std::size_t(i)] = x;
    pos = end + 1;
  }
  return v;
}

std::vector<Ray> make_rays(const ShotCli& o, const Scene& scene) {
  const int sources = int(!o.from.empty() || !o.dir.empty()) + int(!o.grid.empty()) + int(!o.rays.empty());
  if (sources != 1) throw InputError("give exactly one of --from/--dir, --grid or --rays");
  if (!o.grid.empty()) return load_rays(o.grid.rfind("grid", 0) == 0 ? o.grid : "grid:" + o.grid, scene);
  if (!o.rays.empty()) return load_rays(o.rays, scene);
  if (o.from.empty() || o.dir.empty()) throw InputError("--from and --dir go together");
  const Ray r{parse_vec3(o.from, "--from"), parse_vec3(o.dir, "--dir")};
  if (length(r.dir) == 0) throw InputError("--dir '" + o.dir + "': the direction is zero");
  return {r};
}

std::string solids_text(const Scene& s, const ShotRow& r, const CsgExpr* csg, const char* sep) {
  if (r.kind == ShotKind::region) return csg->text;
  std::string t;
  for (std::size_t i = 0; i < r.solids.size(); ++i) {
    if (i) t += sep;
    t += solid_label(s, r.solids[i]);
  }
  return t;
}

std::string short_num(double v) {
  if (std::isnan(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string point(Vec3d p) { return short_num(p.x) + " " + short_num(p.y) + " " + short_num(p.z); }

void write_table(std::FILE* f, const Scene& s, const std::vector<Ray>& rays, const ShotResult& r, const CsgExpr* csg) {
  std::size_t row = 0, overlaps = 0, gaps = 0;
  for (std::uint32_t i = 0; i < rays.size(); ++i) {
    const std::size_t first = row;
    while (row < r.rows.size() && r.rows[row].ray == i) ++row;
    if (first == row && rays.size() > 1) continue;  // grids: only rays that hit something
    std::fprintf(f, "ray %u: origin (%s) direction (%s)%s\n", i, point(rays[i].org).c_str(), point(rays[i].dir).c_str(),
                 first == row ? ": no hits" : "");
    if (first == row) continue;
    std::fprintf(f, "  %-8s %-24s %-32s %-32s %10s %8s %8s %10s\n", "kind", "solid", "in", "out", "los", "obl_in",
                 "obl_out", "normal_th");
    for (std::size_t k = first; k < row; ++k) {
      const ShotRow& x = r.rows[k];
      overlaps += x.kind == ShotKind::overlap;
      gaps += x.kind == ShotKind::gap;
      std::fprintf(f, "  %-8s %-24s %-32s %-32s %10s %8s %8s %10s\n", std::string(shot_kind_name(x.kind)).c_str(),
                   solids_text(s, x, csg, x.kind == ShotKind::gap ? " | " : "+").c_str(), point(x.in_point).c_str(),
                   point(x.out_point).c_str(), short_num(x.los).c_str(), short_num(x.obliquity_in).c_str(),
                   short_num(x.obliquity_out).c_str(), short_num(x.normal_thickness).c_str());
    }
  }
  std::fprintf(f, "%zu rays, %zu hit something; %zu overlap and %zu gap intervals\n", r.rays, r.rays_hitting, overlaps,
               gaps);
}

void write_csv(std::FILE* f, const Scene& s, const ShotResult& r, const CsgExpr* csg) {
  std::fputs("ray,kind,solids,in_x,in_y,in_z,out_x,out_y,out_z,los,obliquity_in,obliquity_out,normal_thickness,t_in,"
             "t_out\n",
             f);
  for (const ShotRow& x : r.rows)
    std::fprintf(f, "%u,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", x.ray,
                 std::string(shot_kind_name(x.kind)).c_str(), csv_field(solids_text(s, x, csg, "+")).c_str(),
                 exact_number(x.in_point.x).c_str(), exact_number(x.in_point.y).c_str(),
                 exact_number(x.in_point.z).c_str(), exact_number(x.out_point.x).c_str(),
                 exact_number(x.out_point.y).c_str(), exact_number(x.out_point.z).c_str(), exact_number(x.los).c_str(),
                 exact_number(x.obliquity_in).c_str(), exact_number(x.obliquity_out).c_str(),
                 exact_number(x.normal_thickness).c_str(), exact_number(x.t_in).c_str(), exact_number(x.t_out).c_str());
}

void write_json(std::FILE* f, const Scene& s, const std::vector<Ray>& rays, const ShotResult& r, const CsgExpr* csg) {
  nlohmann::ordered_json j;
  if (csg) j["csg"] = csg->text;
  auto& jr = j["rays"] = nlohmann::ordered_json::array();
  std::size_t row = 0;
  for (std::uint32_t i = 0; i < rays.size(); ++i) {
    nlohmann::ordered_json ray = {
        {"ray", i}, {"origin", json_point(rays[i].org)}, {"direction", json_point(rays[i].dir)}};
    auto& rows = ray["rows"] = nlohmann::ordered_json::array();
    for (; row < r.rows.size() && r.rows[row].ray == i; ++row) {
      const ShotRow& x = r.rows[row];
      nlohmann::ordered_json names = nlohmann::ordered_json::array();
      if (x.kind == ShotKind::region) names.push_back(csg->text);
      else
        for (std::uint32_t g : x.solids) names.push_back(solid_label(s, g));
      rows.push_back({{"kind", shot_kind_name(x.kind)},
                      {"solids", names},
                      {"solid_ids", x.solids},
                      {"in", json_point(x.in_point)},
                      {"out", json_point(x.out_point)},
                      {"los", x.los},
                      {"obliquity_in", json_or_null(x.obliquity_in)},
                      {"obliquity_out", json_or_null(x.obliquity_out)},
                      {"normal_thickness", json_or_null(x.normal_thickness)},
                      {"t_in", x.t_in},
                      {"t_out", x.t_out}});
    }
    jr.push_back(std::move(ray));
  }
  j["summary"] = {{"rays", r.rays},
                  {"rays_hitting", r.rays_hitting},
                  {"unmatched_leaves", r.unmatched_leaves},
                  {"unclosed", r.unclosed}};
  write_json_document(f, j);
}

int run_shot(const ShotCli& o) {
  InterruptGuard guard;
  check_report_format(o.format);
  OutputFile::check_target(o.out, o.force);
  const KernelKind kernel = exact_kernel_option(o.kernel);

  Scene scene;
  load_models(scene, o.model);
  if (interrupted()) return cancelled();
  const std::vector<Ray> rays = make_rays(o, scene);
  std::optional<CsgExpr> csg;
  if (!o.csg.empty()) csg = parse_csg(o.csg, scene);
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  ShotOptions so;
  so.kernel = kernel;
  so.csg = csg ? &*csg : nullptr;
  ProgressBar bar("shot", rays.size(), o.progress);
  const ShotResult r = shoot(accel, rays, so, [&](std::size_t done, std::size_t) { return bar.update(done); });
  bar.finish();
  if (!r.completed || interrupted()) return cancelled();
  if (r.unmatched_leaves || r.unclosed)
    std::cerr << "pierce: warning: " << r.unmatched_leaves << " exits without entry and " << r.unclosed
              << " entries without exit (open or inverted meshes): those crossings claim nothing\n";

  return write_file(o.out, o.force, [&](std::FILE* out) {
    if (o.format == "table") write_table(out, scene, rays, r, so.csg);
    else if (o.format == "csv") write_csv(out, scene, r, so.csg);
    else write_json(out, scene, rays, r, so.csg);
  });
}

}  // namespace

std::function<int()> register_shot(CLI::App& app) {
  const auto [o, cmd] = add_model_command<ShotCli>(app,
      "shot", "Shotlines (like BRL-CAD nirt): solids along rays with in/out points, line of sight, obliquity, "
              "normal thickness, gaps and overlaps");
  cmd->add_option("--from", o->from, "Ray origin X,Y,Z (with --dir)");
  cmd->add_option("--dir", o->dir, "Ray direction DX,DY,DZ (with --from; need not be unit length)");
  cmd->add_option("--grid", o->grid, "Grid of parallel rays over the model: axis=x|y|z,n=N[,dir=+|-]");
  cmd->add_option("--rays", o->rays, "Rays from a CSV file ox,oy,oz,dx,dy,dz[,tmin,tmax] or random:n=N[,seed=S]");
  cmd->add_option("--csg", o->csg,
                  "CSG expression over solid names, e.g. 'difference(union(a, b), c)' (docs/CSG.md): report its "
                  "intervals instead of each solid's");
  cmd->add_option("--format", o->format, "table (default), csv or json")->capture_default_str();
  add_exact_kernel_option(cmd, o->kernel);
  cmd->add_option("-o,--out", o->out, "Write here instead of stdout");
  add_force_and_progress_flags(cmd, o->force, o->progress, "an existing output file");
  return [o] { return run_shot(*o); };
}

}  // namespace pierce::cli
