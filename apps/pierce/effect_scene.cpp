#include "effect_scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "pierce/error.h"
#include "pierce/io/ray_source.h"
#include "pierce/solid_reference.h"

namespace pierce::cli {

using namespace pierce::analysis;

namespace {

using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

// Reads values out of the document, naming the key path in every error.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file_ + ": " + (where.empty() ? "" : where + ": ") + what);
  }

  static std::string join(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }

  static std::string type_of(const json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    return "an object";
  }

  void expect_object(const json& v, const std::string& where) const {
    if (!v.is_object()) fail(where, "expected an object, got " + type_of(v));
  }

  // Keys outside `allowed` (and not starting with '_', kept for comments) are errors: a typo
  // must not silently drop a setting.
  void check_keys(const json& obj, const std::string& where, std::initializer_list<std::string_view> allowed) const {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      const std::string& k = it.key();
      if (k.starts_with("_")) continue;
      bool ok = false;
      for (std::string_view a : allowed) ok = ok || a == k;
      if (ok) continue;
      std::string list;
      for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(where, "unknown key '" + k + "' (expected " + list + ")");
    }
  }

  std::string string(const json& v, const std::string& where) const {
    if (!v.is_string()) fail(where, "expected a string, got " + type_of(v));
    return v.get<std::string>();
  }

  double number(const json& v, const std::string& where, double lo, double hi, bool lo_open = false,
                bool hi_open = false) const {
    if (!v.is_number()) fail(where, "expected a number, got " + type_of(v));
    const double x = v.get<double>();
    const bool ok = std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
    if (!ok) {
      std::ostringstream range;
      range << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
      std::ostringstream got;
      got << x;
      fail(where, "must be in " + range.str() + ", got " + got.str());
    }
    return x;
  }

  Vec3d vec3(const json& v, const std::string& where, double lo, double hi) const {
    if (!v.is_array() || v.size() != 3) fail(where, "expected an array of three numbers");
    Vec3d r;
    for (std::size_t i = 0; i < 3; ++i) r[i] = number(v[i], where + "[" + std::to_string(i) + "]", lo, hi);
    return r;
  }

  int positive_int(const json& v, const std::string& where, int hi) const {
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > hi)
      fail(where, "expected an integer in [1, " + std::to_string(hi) + "]");
    return v.get<int>();
  }

 private:
  std::string file_;
};

std::string resolve(const std::string& base, const std::string& p) {
  if (p.empty()) return p;
  const fs::path path(p);
  return path.is_absolute() || base.empty() ? p : (fs::path(base) / path).lexically_normal().string();
}

Material read_material(const Reader& r, const json& v, const std::string& where, std::string name) {
  r.expect_object(v, where);
  r.check_keys(v, where, {"density", "mu", "opacity", "color", "energy_loss"});
  constexpr double kBig = 1e300;
  Material m;
  m.name = std::move(name);
  if (v.contains("density")) m.density = r.number(v["density"], Reader::join(where, "density"), 0, kBig);
  if (v.contains("mu")) m.mu = r.number(v["mu"], Reader::join(where, "mu"), 0, kBig);
  if (v.contains("opacity")) m.opacity = r.number(v["opacity"], Reader::join(where, "opacity"), 0, 1);
  if (v.contains("color")) m.color = r.vec3(v["color"], Reader::join(where, "color"), 0, 1);
  if (v.contains("energy_loss")) m.energy_loss = r.number(v["energy_loss"], Reader::join(where, "energy_loss"), 0, kBig);
  return m;
}

CameraSpec read_camera(const Reader& r, const json& v, const std::string& where) {
  r.expect_object(v, where);
  r.check_keys(v, where, {"center", "direction", "up", "size", "pixels"});
  constexpr double kBig = 1e300;
  CameraSpec c;
  if (!v.contains("center")) r.fail(where, "missing 'center' (centre of the image plane)");
  c.center = r.vec3(v["center"], Reader::join(where, "center"), -kBig, kBig);
  if (v.contains("direction")) c.direction = r.vec3(v["direction"], Reader::join(where, "direction"), -kBig, kBig);
  if (v.contains("up")) c.up = r.vec3(v["up"], Reader::join(where, "up"), -kBig, kBig);
  if (length(c.direction) == 0) r.fail(Reader::join(where, "direction"), "the direction is zero");
  if (length(cross(c.direction, c.up)) <= 1e-12 * length(c.direction) * length(c.up))
    r.fail(Reader::join(where, "up"), "must not be zero or parallel to the direction");
  if (v.contains("size")) {
    const json& s = v["size"];
    if (!s.is_array() || s.size() != 2) r.fail(Reader::join(where, "size"), "expected [width, height]");
    c.width = r.number(s[0], Reader::join(where, "size[0]"), 0, kBig, true);
    c.height = r.number(s[1], Reader::join(where, "size[1]"), 0, kBig, true);
  }
  if (v.contains("pixels")) {
    const json& p = v["pixels"];
    if (!p.is_array() || p.size() != 2) r.fail(Reader::join(where, "pixels"), "expected [columns, rows]");
    c.pixels_x = r.positive_int(p[0], Reader::join(where, "pixels[0]"), 16384);
    c.pixels_y = r.positive_int(p[1], Reader::join(where, "pixels[1]"), 16384);
  }
  return c;
}

void read_effect(const Reader& r, EffectSceneSpec& spec, const std::string& name, const json& params,
                 const std::string& where) {
  const std::optional<Effect> e = parse_effect(name);
  if (!e) r.fail(where, "unknown effect '" + name + "' (expected " + enum_name_list<Effect>() + ")");
  EffectsConfig& cfg = spec.config;
  if (cfg.on(*e)) r.fail(where, "effect '" + name + "' requested twice");
  cfg.enable(*e);
  if (params.is_null()) return;
  r.expect_object(params, where);
  auto out = [&](const char* key) { return resolve(spec.base_dir, r.string(params[key], Reader::join(where, key))); };
  switch (*e) {
    case Effect::first_hit:
    case Effect::thickness:
    case Effect::overlaps: r.check_keys(params, where, {}); break;
    case Effect::classification:
      r.check_keys(params, where, {"csg"});
      if (params.contains("csg")) spec.csg = r.string(params["csg"], Reader::join(where, "csg"));
      break;
    case Effect::xray:
      r.check_keys(params, where, {"threshold", "image", "vti"});
      if (params.contains("threshold"))
        cfg.xray_threshold = r.number(params["threshold"], Reader::join(where, "threshold"), 0, 1, true, true);
      if (params.contains("image")) spec.xray_png = out("image");
      if (params.contains("vti")) spec.xray_vti = out("vti");
      break;
    case Effect::transparency:
      r.check_keys(params, where, {"saturation", "background", "image"});
      if (params.contains("saturation"))
        cfg.alpha_saturation = r.number(params["saturation"], Reader::join(where, "saturation"), 0, 1, true);
      if (params.contains("background")) cfg.background = r.vec3(params["background"], Reader::join(where, "background"), 0, 1);
      if (params.contains("image")) spec.transparency_png = out("image");
      break;
    case Effect::penetration:
      r.check_keys(params, where, {"energy"});
      if (params.contains("energy"))
        cfg.penetration_energy = r.number(params["energy"], Reader::join(where, "energy"), 0, 1e300, true);
      break;
  }
}

// Line and column (1-based) of a byte offset, for JSON syntax errors.
std::pair<std::size_t, std::size_t> line_col(std::string_view text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') ++line, col = 1;
    else ++col;
  }
  return {line, col};
}

bool is_generator(const std::string& s) { return s.rfind("grid", 0) == 0 || s.rfind("random", 0) == 0; }

}  // namespace

EffectSceneSpec parse_effect_scene(std::string_view text, const std::string& path) {
  const Reader r(path);
  json doc;
  try {
    doc = json::parse(text.begin(), text.end(), nullptr, true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    const auto [line, col] = line_col(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    if (const std::size_t p = what.find("syntax error"); p != std::string::npos) what = what.substr(p);
    throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(col) + ": invalid JSON: " + what);
  }
  r.expect_object(doc, "");
  r.check_keys(doc, "", {"description", "models", "materials", "solids", "rays", "kernel", "tie_tolerance",
                         "effects", "output"});
  EffectSceneSpec spec;
  spec.path = path;
  spec.base_dir = fs::path(path).parent_path().string();

  if (!doc.contains("models")) r.fail("", "missing 'models' (the model files to load)");
  const json& models = doc["models"];
  if (models.is_string()) spec.models.push_back(resolve(spec.base_dir, models.get<std::string>()));
  else if (models.is_array() && !models.empty())
    for (std::size_t i = 0; i < models.size(); ++i)
      spec.models.push_back(resolve(spec.base_dir, r.string(models[i], "models[" + std::to_string(i) + "]")));
  else r.fail("models", "expected a file name or a non-empty array of file names");

  std::map<std::string, std::size_t> material_index;
  if (doc.contains("materials")) {
    r.expect_object(doc["materials"], "materials");
    for (auto it = doc["materials"].begin(); it != doc["materials"].end(); ++it) {
      if (it.key().starts_with("_")) continue;
      material_index[it.key()] = spec.materials.size();
      spec.materials.push_back(read_material(r, it.value(), "materials." + it.key(), it.key()));
    }
  }
  if (doc.contains("solids")) {
    r.expect_object(doc["solids"], "solids");
    for (auto it = doc["solids"].begin(); it != doc["solids"].end(); ++it) {
      const std::string where = "solids." + it.key();
      if (it.key().starts_with("_")) continue;
      if (it.value().is_object()) {  // inline material
        const std::string name = it.key() == "*" ? "(default)" : it.key();
        spec.materials.push_back(read_material(r, it.value(), where, name));
        spec.assignments.emplace_back(it.key(), spec.materials.size() - 1);
        continue;
      }
      const std::string mat = r.string(it.value(), where);
      if (!material_index.count(mat)) {
        std::string known;
        for (const auto& [k, v] : material_index) known += (known.empty() ? "" : ", ") + k;
        r.fail(where, "unknown material '" + mat + "' (defined: " + (known.empty() ? "none" : known) + ")");
      }
      spec.assignments.emplace_back(it.key(), material_index[mat]);
    }
  }

  if (!doc.contains("rays")) r.fail("", "missing 'rays' (a generator like \"grid:axis=z,n=64\", a CSV file, or {\"camera\": {...}})");
  const json& rays = doc["rays"];
  if (rays.is_string()) {
    spec.rays = rays.get<std::string>();
    if (!is_generator(spec.rays)) spec.rays = resolve(spec.base_dir, spec.rays);
  } else if (rays.is_object()) {
    r.check_keys(rays, "rays", {"camera"});
    if (!rays.contains("camera")) r.fail("rays", "expected {\"camera\": {...}}");
    spec.camera = read_camera(r, rays["camera"], "rays.camera");
  } else {
    r.fail("rays", "expected a string (generator or CSV file) or {\"camera\": {...}}, got " + Reader::type_of(rays));
  }

  if (doc.contains("kernel")) {
    const std::string k = r.string(doc["kernel"], "kernel");
    const std::optional<KernelKind> kind = parse_kernel(k);
    if (!kind || !is_exact(*kind)) r.fail("kernel", "'" + k + "' is not an exact kernel");
    spec.config.kernel = *kind;
  }
  if (doc.contains("tie_tolerance"))
    spec.config.tie_tolerance_rel = r.number(doc["tie_tolerance"], "tie_tolerance", 0, 1);

  if (!doc.contains("effects")) r.fail("", "missing 'effects' (which effects to run)");
  const json& effects = doc["effects"];
  if (effects.is_array()) {
    for (std::size_t i = 0; i < effects.size(); ++i) {
      const std::string where = "effects[" + std::to_string(i) + "]";
      read_effect(r, spec, r.string(effects[i], where), json(), where);
    }
  } else if (effects.is_object()) {
    for (auto it = effects.begin(); it != effects.end(); ++it)
      if (!it.key().starts_with("_")) read_effect(r, spec, it.key(), it.value(), "effects." + it.key());
  } else {
    r.fail("effects", "expected an array of effect names or an object of effect -> parameters");
  }
  bool any = false;
  for (bool b : spec.config.enabled) any = any || b;
  if (!any) r.fail("effects", "no effect requested");

  if (doc.contains("output")) {
    const json& o = doc["output"];
    r.expect_object(o, "output");
    r.check_keys(o, "output", {"rays", "intervals", "report"});
    if (o.contains("rays")) spec.rays_csv = resolve(spec.base_dir, r.string(o["rays"], "output.rays"));
    if (o.contains("intervals")) spec.intervals_csv = resolve(spec.base_dir, r.string(o["intervals"], "output.intervals"));
    if (o.contains("report")) spec.report_json = resolve(spec.base_dir, r.string(o["report"], "output.report"));
  }
  if (!spec.intervals_csv.empty() && !spec.config.on(Effect::classification) && !spec.config.on(Effect::overlaps))
    r.fail("output.intervals", "needs the classification or overlaps effect");
  return spec;
}

EffectSceneSpec load_effect_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the scene file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_effect_scene(ss.str(), path);
}

void redirect_outputs(EffectSceneSpec& spec, const std::string& out_dir) {
  const fs::path base = fs::path(spec.base_dir);
  for (std::string* p : {&spec.rays_csv, &spec.intervals_csv, &spec.report_json, &spec.xray_png, &spec.xray_vti,
                         &spec.transparency_png}) {
    if (p->empty()) continue;
    const fs::path rel = fs::path(*p).lexically_relative(base);
    const bool inside = !rel.empty() && *rel.begin() != "..";
    *p = (fs::path(out_dir) / (inside ? rel : fs::path(*p).filename())).lexically_normal().string();
  }
}

EffectsConfig bind_effect_scene(const EffectSceneSpec& spec, const Scene& scene) {
  EffectsConfig cfg = spec.config;
  cfg.materials = spec.materials;
  const std::size_t n = scene.geometries().size();
  cfg.solid_material.assign(n, -1);
  auto material_of = [](std::size_t m) { return std::int32_t(m); };
  std::vector<std::uint8_t> named(n, 0);
  std::string unknown;
  std::int32_t fallback = -1;
  for (const auto& [solid, mat] : spec.assignments) {
    if (solid == "*") {
      fallback = material_of(mat);
      continue;
    }
    // A name, #N or N, as everywhere solids are named (solid_reference.h).
    const std::vector<std::uint32_t> found = find_solids(scene, solid);
    for (const std::uint32_t g : found) {
      cfg.solid_material[g] = material_of(mat);
      named[g] = 1;
    }
    if (found.empty()) unknown += (unknown.empty() ? "'" : ", '") + solid + "'";
  }
  if (!unknown.empty()) {
    std::string known;
    for (std::uint32_t g = 0; g < n && g < 20; ++g) {
      if (g) known += ", ";
      if (scene.geometry(g).name.empty()) known.append("#").append(std::to_string(g));
      else known += scene.geometry(g).name;
    }
    if (n > 20) known += ", ...";
    throw InputError(spec.path + ": solids: no solid named " + unknown + " in the models (solids: " + known + ")");
  }
  for (std::uint32_t g = 0; g < n; ++g)
    if (!named[g]) cfg.solid_material[g] = fallback;
  if (!spec.csg.empty()) {
    try {
      cfg.classification_csg = parse_csg(spec.csg, scene);
    } catch (const InputError& e) {
      throw InputError(spec.path + ": effects.classification.csg: " + e.what());
    }
  }
  try {
    validate(cfg, scene);
  } catch (const std::invalid_argument& e) {
    throw InputError(spec.path + ": " + e.what());
  }
  return cfg;
}

std::vector<Ray> camera_rays(const CameraSpec& c) {
  const Vec3d d = c.direction * (1.0 / length(c.direction));
  Vec3d right = cross(d, c.up);
  right = right * (1.0 / length(right));
  const Vec3d up = cross(right, d);
  const double px = c.width / c.pixels_x, py = c.height / c.pixels_y;
  std::vector<Ray> rays;
  rays.reserve(std::size_t(c.pixels_x) * std::size_t(c.pixels_y));
  for (int j = 0; j < c.pixels_y; ++j)  // top row first
    for (int i = 0; i < c.pixels_x; ++i) {
      const double x = (i + 0.5) * px - 0.5 * c.width, y = 0.5 * c.height - (j + 0.5) * py;
      rays.push_back(Ray{c.center + right * x + up * y, d});
    }
  return rays;
}

SceneRays make_scene_rays(const EffectSceneSpec& spec, const Scene& scene) {
  SceneRays out;
  if (spec.camera) {
    const CameraSpec& c = *spec.camera;
    out.rays = camera_rays(c);
    out.width = c.pixels_x;
    out.height = c.pixels_y;
    out.plane_origin = {-0.5 * c.width + 0.5 * c.width / c.pixels_x, -0.5 * c.height + 0.5 * c.height / c.pixels_y, 0};
    out.plane_spacing = {c.width / c.pixels_x, c.height / c.pixels_y, 1};
    return out;
  }
  try {
    out.rays = load_rays(spec.rays, scene);
  } catch (const InputError& e) {
    throw InputError(spec.path + ": rays: " + e.what());
  }
  if (spec.rays.rfind("grid", 0) == 0) {  // N x N, ray j*N + i at cell (i, j) of the bounds' cross-section
    const auto n = int(std::llround(std::sqrt(double(out.rays.size()))));
    out.width = out.height = n;
    out.bottom_up = true;
    const Ray& r0 = out.rays.front();
    int axis = 0;
    for (int a = 0; a < 3; ++a)
      if (r0.dir[std::size_t(a)] != 0) axis = a;
    const std::size_t u = std::size_t((axis + 1) % 3), v = std::size_t((axis + 2) % 3);
    const Vec3d ext = scene.bounds().extent();
    out.plane_spacing = {ext[u] / n, ext[v] / n, 1};
    out.plane_origin = {r0.org[u], r0.org[v], 0};
  }
  return out;
}

}  // namespace pierce::cli
