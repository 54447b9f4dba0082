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
  std::vector<std::shared_ptr<const CadFaces>> faces;
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

std::int64_t register_cad_model(const std::string& path, const TessellationOptions& opts, const CadModel& model) {
  Registered entry;
  entry.key = key_of(path, opts);
  for (const CadSolid& s : model.solids) entry.faces.push_back(s.link.faces);
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  std::erase_if(r.models, [&](const Registered& m) { return m.key == entry.key; });
  r.models.push_back(std::move(entry));
  while (r.models.size() > kRegisteredCadModels) r.models.pop_front();
  return r.models.back().key;
}

std::vector<std::shared_ptr<const CadFaces>> registered_cad_faces(std::int64_t key) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  const auto found = std::find_if(r.models.begin(), r.models.end(), [&](const Registered& m) { return m.key == key; });
  return found == r.models.end() ? std::vector<std::shared_ptr<const CadFaces>>{} : found->faces;
}

}  // namespace pierce
