#include "pierce/io/cad_registry.h"

#include <algorithm>
#include <bit>
#include <deque>
#include <filesystem>
#include <mutex>
#include <utility>

namespace pierce {

namespace {

struct Registered {
  std::int64_t key = 0;
  std::shared_ptr<const RegisteredCadModel> model;
};

struct Registry {
  std::mutex mutex;
  std::deque<Registered> models;  // oldest first
};

// Never destroyed: the faces hold OpenCASCADE objects, which must not be released after
// OpenCASCADE's own libraries have shut down at exit.
Registry& registry() {
  static Registry* const r = new Registry;
  return *r;
}

// FNV-1a, 64 bits.
class Hash {
 public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) value_ = (value_ ^ bytes[i]) * 0x100000001b3ull;
  }
  template <class T>
  void add(const T& value) {
    add(&value, sizeof value);
  }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 0xcbf29ce484222325ull;
};

std::int64_t key_of(const std::string& path, const TessellationOptions& opts) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path absolute = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) absolute = path;
  Hash h;
  const std::string name = absolute.string();
  h.add(name.data(), name.size());
  const std::uintmax_t size = fs::file_size(absolute, ec);
  h.add(ec ? std::uintmax_t(0) : size);
  const auto modified = fs::last_write_time(absolute, ec);
  h.add(ec ? std::int64_t(0) : std::int64_t(modified.time_since_epoch().count()));
  h.add(std::bit_cast<std::uint64_t>(opts.linear_deflection));
  h.add(std::bit_cast<std::uint64_t>(opts.angular_deflection_deg));
  h.add(opts.fold_remesh_rounds);
  constexpr std::uint64_t kMask = (std::uint64_t(1) << 52) - 1;
  return std::int64_t(h.value() & kMask) + 1;
}

}  // namespace

std::uint64_t cad_triangle_hash(const std::array<Vec3d, 3>& corners, std::uint32_t face,
                                const std::array<double, 6>& uv) {
  Hash h;
  for (const Vec3d& c : corners) {
    h.add(std::bit_cast<std::uint64_t>(c.x));
    h.add(std::bit_cast<std::uint64_t>(c.y));
    h.add(std::bit_cast<std::uint64_t>(c.z));
  }
  h.add(face);
  for (const double x : uv) h.add(std::bit_cast<std::uint64_t>(x));
  return h.value();
}

std::int64_t register_cad_model(const std::string& path, const TessellationOptions& opts, const CadModel& model) {
  Registered entry;
  entry.key = key_of(path, opts);
  auto registered = std::make_shared<RegisteredCadModel>();
  for (const CadSolid& s : model.solids) {
    RegisteredCadModel::Solid& solid = registered->solids.emplace_back();
    solid.faces = s.link.faces;
    if (s.link.empty()) continue;
    solid.triangle_hash.reserve(s.triangles.size());
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      const Tri& tri = s.triangles[t];
      solid.triangle_hash.push_back(cad_triangle_hash({s.vertices[tri[0]], s.vertices[tri[1]], s.vertices[tri[2]]},
                                                      s.link.face[t], s.link.uv[t]));
    }
  }
  entry.model = std::move(registered);
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::erase_if(r.models, [&](const Registered& m) { return m.key == entry.key; });
  r.models.push_back(std::move(entry));
  while (r.models.size() > kRegisteredCadModels) r.models.pop_front();
  return r.models.back().key;
}

std::shared_ptr<const RegisteredCadModel> registered_cad_model(std::int64_t key) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  const auto found = std::find_if(r.models.begin(), r.models.end(), [&](const Registered& m) { return m.key == key; });
  return found == r.models.end() ? nullptr : found->model;
}

}  // namespace pierce
