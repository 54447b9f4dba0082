// `pierce classify MODEL... (--point X,Y,Z ... | --points FILE.csv) [--csg EXPR]...`: inside / outside
// / on of points with respect to every solid, or to CSG expressions, by the ray-partition machinery
// of `shot` and `gqa` (analysis::PointClassifier). A table by default, or CSV / JSON.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "csv_text.h"
#include "command.h"
#include "interrupt.h"
#include "json_text.h"
#include "model_args.h"
#include "output_file.h"
#include "pierce/analysis/csg.h"
#include "pierce/error.h"
#include "progress.h"

namespace pierce::cli {

namespace {

using namespace pierce::analysis;

struct ClassifyCli {
  ModelArgs model;
  std::vector<std::string> points;  // --point X,Y,Z (repeatable)
  std::string points_file;
  std::vector<std::string> csg;
  std::string format;  // table | csv | json; empty: from -o's extension
  std::string kernel{kernel_name(kDefaultKernel)};
  double tol = 1e-6;
  std::string out;
  bool force = false, progress = false;
};

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// "X,Y,Z" -> point; throws InputError starting with `where` ("--point '1,2'", "pts.csv, line 3").
Vec3d parse_point(const std::string& text, const std::string& where) {
  std::vector<std::string> fields;
  std::size_t pos = 0;
  while (true) {
    const std::size_t end = text.find(',', pos);
    fields.push_back(trim(text.substr(pos, end == std::string::npos ? std::string::npos : end - pos)));
    if (end == std::string::npos) break;
    pos = end + 1;
  }
  if (fields.size() != 3)
    throw InputError(where + ": expected three comma-separated numbers x,y,z, found " + std::to_string(fields.size()) +
                     " field" + (fields.size() == 1 ? "" : "s"));
  Vec3d p;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string& f = fields[i];
    char* stop = nullptr;
    const double v = std::strtod(f.c_str(), &stop);
    if (f.empty() || stop == f.c_str() || *stop != '\0')
      throw InputError(where + ": field " + std::to_string(i + 1) + " ('" + f + "') is not a number");
    if (!std::isfinite(v))
      throw InputError(where + ": field " + std::to_string(i + 1) + " ('" + f + "') is not finite");
    p[i] = v;
  }
  return p;
}

// Points from a CSV file: one x,y,z per line; an optional header line "x,y,z"; blank lines and
// lines starting with '#' are skipped.
std::vector<Vec3d> read_points_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the points file");
  std::vector<Vec3d> pts;
  std::string line;
  for (std::size_t n = 1; std::getline(in, line); ++n) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    if (pts.empty() && n == 1) {
      std::string lower;
      for (char c : t)
        if (c != ' ' && c != '\t') lower += char(std::tolower(static_cast<unsigned char>(c)));
      if (lower == "x,y,z") continue;
    }
    pts.push_back(parse_point(t, path + ", line " + std::to_string(n)));
  }
  if (in.bad()) throw InputError(path + ": read error");
  if (pts.empty()) throw InputError(path + ": no points (expected lines x,y,z)");
  return pts;
}

struct Target {
  std::string label;  // solid label or the expression as written
  CsgExpr expr;
};

std::string short_num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// classes[p * targets.size() + t]
void write_table(std::FILE* f, const std::vector<Vec3d>& pts, const std::vector<Target>& targets,
                 const std::vector<PointClass>& classes) {
  for (std::size_t p = 0; p < pts.size(); ++p) {
    std::fprintf(f, "point %zu (%s %s %s):", p, short_num(pts[p].x).c_str(), short_num(pts[p].y).c_str(),
                 short_num(pts[p].z).c_str());
    for (std::size_t t = 0; t < targets.size(); ++t)
      std::fprintf(f, "%s %s %s", t ? "," : "", targets[t].label.c_str(),
                   std::string(point_class_name(classes[p * targets.size() + t])).c_str());
    std::fputc('\n', f);
  }
}

void write_csv(std::FILE* f, const std::vector<Vec3d>& pts, const std::vector<Target>& targets,
               const std::vector<PointClass>& classes) {
  std::fputs("point,x,y,z,target,class\n", f);
  for (std::size_t p = 0; p < pts.size(); ++p)
    for (std::size_t t = 0; t < targets.size(); ++t)
      std::fprintf(f, "%zu,%s,%s,%s,%s,%s\n", p, exact_number(pts[p].x).c_str(), exact_number(pts[p].y).c_str(),
                   exact_number(pts[p].z).c_str(), csv_field(targets[t].label).c_str(),
                   std::string(point_class_name(classes[p * targets.size() + t])).c_str());
}

void write_json(std::FILE* f, const std::vector<Vec3d>& pts, const std::vector<Target>& targets,
                const std::vector<PointClass>& classes, bool csg, double tolerance) {
  nlohmann::ordered_json j;
  j["targets"] = nlohmann::ordered_json::array();
  for (const Target& t : targets) j["targets"].push_back(t.label);
  j["target_kind"] = csg ? "csg" : "solid";
  j["tolerance"] = tolerance;
  auto& jp = j["points"] = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < pts.size(); ++p) {
    nlohmann::ordered_json c = nlohmann::ordered_json::array();
    for (std::size_t t = 0; t < targets.size(); ++t)
      c.push_back(point_class_name(classes[p * targets.size() + t]));
    jp.push_back({{"point", p}, {"at", {pts[p].x, pts[p].y, pts[p].z}}, {"classes", std::move(c)}});
  }
  write_json_document(f, j);
}

std::string output_format(const ClassifyCli& o) {
  if (!o.format.empty()) {
    check_report_format(o.format);
    return o.format;
  }
  auto ends_with = [&](const char* ext) {
    std::string lower;
    for (char c : o.out) lower += char(std::tolower(static_cast<unsigned char>(c)));
    return lower.ends_with(ext);
  };
  if (ends_with(".json")) return "json";
  if (ends_with(".csv")) return "csv";
  return "table";
}

int run_classify(const ClassifyCli& o) {
  InterruptGuard guard;
  const std::string format = output_format(o);
  OutputFile::check_target(o.out, o.force);
  const KernelKind kernel = exact_kernel_option(o.kernel);
  if (!(o.tol >= 0) || !(o.tol < 1)) throw InputError("--tol must be in [0, 1)");
  if (o.points.empty() == o.points_file.empty()) throw InputError("give either --point (repeatable) or --points FILE");

  std::vector<Vec3d> pts;
  for (const std::string& p : o.points) pts.push_back(parse_point(p, "--point '" + p + "'"));
  if (!o.points_file.empty()) pts = read_points_file(o.points_file);

  Scene scene;
  load_models(scene, o.model);
  if (interrupted()) return cancelled();
  std::vector<Target> targets;
  if (o.csg.empty()) {
    for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
      targets.push_back({solid_label(scene, g), parse_csg("#" + std::to_string(g), scene)});
  } else {
    for (const std::string& e : o.csg) targets.push_back({e, parse_csg(e, scene)});
  }
  const Accel accel(scene);
  if (interrupted()) return cancelled();

  std::vector<std::unique_ptr<PointClassifier>> classifiers;
  for (const Target& t : targets) classifiers.push_back(std::make_unique<PointClassifier>(accel, t.expr, kernel, o.tol));
  std::vector<PointClass> classes(pts.size() * targets.size());
  ProgressBar bar("classify", pts.size(), o.progress);
  for (std::size_t p = 0; p < pts.size(); ++p) {
    for (std::size_t t = 0; t < targets.size(); ++t) classes[p * targets.size() + t] = classifiers[t]->classify(pts[p]);
    if (!bar.update(p + 1) || interrupted()) return cancelled();
  }
  bar.finish();

  return write_file(o.out, o.force, [&](std::FILE* out) {
    if (format == "table") write_table(out, pts, targets, classes);
    else if (format == "csv") write_csv(out, pts, targets, classes);
    else write_json(out, pts, targets, classes, !o.csg.empty(), classifiers.empty() ? 0 : classifiers[0]->tolerance());
  });
}

}  // namespace

std::function<int()> register_classify(CLI::App& app) {
  const auto [o, cmd] = add_model_command<ClassifyCli>(app,
      "classify", "Inside / outside / on of points for every solid or CSG expression (ray partitions)");
  // One value per occurrence, so `--point 1,2,3 MODEL` does not read MODEL as a point.
  cmd->add_option("--point", o->points, "A point X,Y,Z (repeatable)")->allow_extra_args(false);
  cmd->add_option("--points", o->points_file, "CSV file of points, one x,y,z per line (optional header x,y,z)");
  cmd->add_option("--csg", o->csg,
                  "Classify against this CSG expression instead of each solid (repeatable; docs/CSG.md)")
      ->allow_extra_args(false);
  cmd->add_option("--tol", o->tol,
                  "Relative tie tolerance: points within tol x (scene diagonal + largest coordinate) of a "
                  "surface are 'on'")
      ->capture_default_str();
  cmd->add_option("--format", o->format, "table, csv or json (default: from -o's extension, else table)");
  add_exact_kernel_option(cmd, o->kernel);
  cmd->add_option("-o,--out", o->out, "Write here instead of stdout");
  add_force_and_progress_flags(cmd, o->force, o->progress, "an existing output file");
  return [o] { return run_classify(*o); };
}

}  // namespace pierce::cli
