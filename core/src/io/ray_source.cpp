#include "pierce/io/ray_source.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include "io_util.h"

namespace pierce {

namespace {

// ---- CSV -------------------------------------------------------------------------------------

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> f;
  for (;;) {
    const std::size_t c = line.find(',');
    f.push_back(io::trim(line.substr(0, c)));
    if (c == std::string_view::npos) return f;
    line.remove_prefix(c + 1);
  }
}

std::vector<Ray> read_ray_csv(const std::string& path) {
  const io::FileBytes bytes = io::read_file(path);
  const std::string_view data(bytes.data(), bytes.size());
  std::vector<Ray> rays;
  io::LineCursor lines(data);
  std::string_view line;
  bool first_content = true;
  while (lines.next(line)) {
    const std::string_view t = io::trim(line);
    if (t.empty() || t.front() == '#') continue;
    const std::vector<std::string_view> f = split_fields(t);
    const std::size_t ln = lines.line();
    double v[8] = {0, 0, 0, 0, 0, 0, 0, std::numeric_limits<double>::infinity()};
    if (first_content) {
      first_content = false;
      // A header names the columns: none of its fields is a number (a typo in a data line is an error).
      if (std::none_of(f.begin(), f.end(), [](std::string_view x) { double d; return io::parse_double(x, d); }))
        continue;
    }
    if (f.size() != 6 && f.size() != 8)
      io::fail_at_line(path, ln, "expected 6 or 8 comma-separated values (ox,oy,oz,dx,dy,dz[,tmin,tmax]), found " +
                                     std::to_string(f.size()));
    static constexpr const char* kNames[] = {"ox", "oy", "oz", "dx", "dy", "dz", "tmin", "tmax"};
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (!io::parse_double(f[k], v[k]))
        io::fail_at_line(path, ln, std::string("bad number for ") + kNames[k] + ": " + io::quoted(f[k]));
      if (std::isnan(v[k])) io::fail_at_line(path, ln, std::string(kNames[k]) + " is NaN");
      const bool may_be_infinite = k == 7 && v[k] > 0;
      if (!may_be_infinite && !std::isfinite(v[k]))
        io::fail_at_line(path, ln, std::string(kNames[k]) + " is infinite" + (k == 7 ? " and negative" : ""));
      if (k < 6 && std::abs(v[k]) > double(std::numeric_limits<float>::max()))
        io::fail_at_line(path, ln, std::string(kNames[k]) + " is beyond single-precision range");
    }
    Ray r{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7]};
    if (Vec3f(r.dir) == Vec3f{})
      io::fail_at_line(path, ln, "direction is zero (or too small for single precision)");
    if (!(r.tmin <= r.tmax)) io::fail_at_line(path, ln, "tmin is greater than tmax");
    rays.push_back(r);
  }
  if (rays.empty()) io::fail(path, "no rays found");
  return rays;
}

// ---- generators ------------------------------------------------------------------------------

[[noreturn]] void spec_error(const std::string& spec, const std::string& what) {
  throw InputError("ray spec '" + spec + "': " + what);
}

using Params = std::map<std::string, std::string, std::less<>>;

Params parse_params(const std::string& spec, std::string_view body, std::initializer_list<std::string_view> allowed) {
  Params p;
  if (io::trim(body).empty()) return p;
  std::string keys;
  for (std::string_view k : allowed) keys += (keys.empty() ? "" : ", ") + std::string(k);
  for (std::string_view item : split_fields(body)) {
    if (item.empty()) spec_error(spec, "empty parameter (stray comma?)");
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) spec_error(spec, "parameter " + io::quoted(item) + " is not key=value");
    const std::string key(io::trim(item.substr(0, eq)));
    const std::string value(io::trim(item.substr(eq + 1)));
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      spec_error(spec, "unknown key " + io::quoted(key) + " (expected " + keys + ")");
    if (value.empty()) spec_error(spec, "no value for " + key);
    if (!p.emplace(key, value).second) spec_error(spec, "key " + key + " given twice");
  }
  return p;
}

std::int64_t positive_int(const std::string& spec, const Params& p, const std::string& key, std::int64_t max) {
  const auto it = p.find(key);
  if (it == p.end()) spec_error(spec, "missing " + key + "=...");
  std::int64_t n;
  if (!io::parse_int(it->second, n)) spec_error(spec, key + " must be an integer, got " + io::quoted(it->second));
  if (n <= 0) spec_error(spec, key + " must be positive, got " + it->second);
  if (n > max) spec_error(spec, key + " = " + it->second + " is too large (at most " + std::to_string(max) + ")");
  return n;
}

const BBoxd& nonempty_bounds(const std::string& spec, const Scene& scene) {
  if (scene.geometries().empty() || scene.bounds().empty())
    spec_error(spec, "the scene is empty: generated rays need scene bounds");
  return scene.bounds();
}

std::vector<Ray> grid_rays(const std::string& spec, std::string_view body, const Scene& scene) {
  const Params p = parse_params(spec, body, {"axis", "n", "dir"});
  int axis = 2;
  if (auto it = p.find("axis"); it != p.end()) {
    if (it->second == "x") axis = 0;
    else if (it->second == "y") axis = 1;
    else if (it->second == "z") axis = 2;
    else spec_error(spec, "axis must be x, y or z, got " + io::quoted(it->second));
  }
  double sign = 1.0;
  if (auto it = p.find("dir"); it != p.end()) {
    if (it->second == "-") sign = -1.0;
    else if (it->second != "+") spec_error(spec, "dir must be + or -, got " + io::quoted(it->second));
  }
  const auto n = std::size_t(positive_int(spec, p, "n", std::int64_t(std::sqrt(double(kMaxGeneratedRays)))));
  const BBoxd& b = nonempty_bounds(spec, scene);
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  // Start a little outside the bounds so hits on the bounding faces are inside [tmin, tmax].
  const double margin = 0.05 * scene.scale();
  const Vec3d ext = b.extent();
  Ray proto;
  proto.dir[std::size_t(axis)] = sign;
  proto.org[std::size_t(axis)] = sign > 0 ? b.lo[std::size_t(axis)] - margin : b.hi[std::size_t(axis)] + margin;
  std::vector<Ray> rays;
  rays.reserve(n * n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      Ray r = proto;
      r.org[std::size_t(u)] = b.lo[std::size_t(u)] + ext[std::size_t(u)] * ((double(i) + 0.5) / double(n));
      r.org[std::size_t(v)] = b.lo[std::size_t(v)] + ext[std::size_t(v)] * ((double(j) + 0.5) / double(n));
      rays.push_back(r);
    }
  return rays;
}

// Uniform in [0, 1) from the top 53 bits.
double unit(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

std::vector<Ray> random_rays(const std::string& spec, std::string_view body, const Scene& scene) {
  const Params p = parse_params(spec, body, {"n", "seed"});
  const auto n = std::size_t(positive_int(spec, p, "n", std::int64_t(kMaxGeneratedRays)));
  std::uint64_t seed = 1;
  if (auto it = p.find("seed"); it != p.end()) {
    std::int64_t s;
    if (!io::parse_int(it->second, s) || s < 0)
      spec_error(spec, "seed must be a non-negative integer, got " + io::quoted(it->second));
    seed = std::uint64_t(s);
  }
  const BBoxd& b = nonempty_bounds(spec, scene);
  const Vec3d c = b.center(), ext = b.extent();
  const double radius = 0.75 * scene.scale();  // 1.5 x the half-diagonal (scale() > 0 when flat)
  std::mt19937_64 rng(seed);
  std::vector<Ray> rays;
  rays.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double z = 2.0 * unit(rng) - 1.0, phi = 6.283185307179586 * unit(rng);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3d org = c + Vec3d{s * std::cos(phi), s * std::sin(phi), z} * radius;
    const double tx = unit(rng), ty = unit(rng), tz = unit(rng);
    const Vec3d target{b.lo.x + ext.x * tx, b.lo.y + ext.y * ty, b.lo.z + ext.z * tz};
    const Vec3d d = target - org;
    rays.push_back({org, d * (1.0 / length(d)), 0.0, std::numeric_limits<double>::infinity()});
  }
  return rays;
}

bool looks_like_generator(std::string_view spec) {
  const std::size_t colon = spec.find(':');
  if (colon == 0 || colon == std::string_view::npos) return false;
  return std::all_of(spec.begin(), spec.begin() + std::ptrdiff_t(colon),
                     [](char ch) { return ch >= 'a' && ch <= 'z'; });
}

}  // namespace

std::vector<Ray> load_rays(const std::string& spec, const Scene& scene) {
  const std::string_view s(spec);
  if (s == "grid" || s.starts_with("grid:")) return grid_rays(spec, s.substr(std::min<std::size_t>(5, s.size())), scene);
  if (s == "random" || s.starts_with("random:"))
    return random_rays(spec, s.substr(std::min<std::size_t>(7, s.size())), scene);
  std::error_code ec;
  if (looks_like_generator(s) && !std::filesystem::exists(spec, ec))
    spec_error(spec, "unknown ray generator " + io::quoted(s.substr(0, s.find(':'))) +
                         " (expected grid:..., random:... or a CSV file)");
  return read_ray_csv(spec);
}

}  // namespace pierce
