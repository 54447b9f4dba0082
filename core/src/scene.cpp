#include "pierce/scene.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "pierce/error.h"
#include "pierce/exact_sign.h"

namespace pierce {

namespace {

std::string where(const std::string& source, const std::string& name) {
  std::string w = source.empty() ? std::string("mesh") : source;
  if (!name.empty()) w += " (" + name + ")";
  return w;
}

// Exact zero-area test: the corners are collinear exactly when all three coordinate-plane
// projections have zero orientation, each decided exactly (exact_sign.h). A rounded cross
// product would call some slivers degenerate (and never hit them) in double precision.
template <typename T>
bool cross_is_zero(Vec3<T> a, Vec3<T> b, Vec3<T> c) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (exact::orient2d_sign(double(a[i]), double(a[j]), double(b[i]), double(b[j]), double(c[i]), double(c[j])) != 0)
      return false;
  }
  return true;
}

}  // namespace

bool is_degenerate(Vec3f a, Vec3f b, Vec3f c) { return cross_is_zero(a, b, c); }
bool is_degenerate(Vec3d a, Vec3d b, Vec3d c) { return cross_is_zero(a, b, c); }

std::uint32_t Scene::add_mesh(std::vector<Vec3d> vertices, std::vector<Tri> triangles, std::string name,
                              std::string source) {
  constexpr double kFloatMax = double(std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec3d& p = vertices[i];
    if (!all_finite(p)) {
      std::ostringstream m;
      m << where(source, name) << ": vertex " << i << " has a non-finite coordinate (" << p.x << ", " << p.y
        << ", " << p.z << ")";
      throw InputError(m.str());
    }
    if (max_abs(p) > kFloatMax) {
      std::ostringstream m;
      m << where(source, name) << ": vertex " << i << " is beyond single-precision range (" << p.x << ", "
        << p.y << ", " << p.z << ")";
      throw InputError(m.str());
    }
  }
  Geometry g;
  g.degenerate.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Tri& t = triangles[i];
    for (int k = 0; k < 3; ++k) {
      if (t[k] >= vertices.size()) {
        std::ostringstream m;
        m << where(source, name) << ": triangle " << i << " references vertex " << t[k] << " but the mesh has "
          << vertices.size() << " vertices";
        throw InputError(m.str());
      }
    }
    const Vec3f a(vertices[t[0]]), b(vertices[t[1]]), c(vertices[t[2]]);
    g.degenerate[i] = is_degenerate(a, b, c) ? 1 : 0;
  }
  for (const Vec3d& p : vertices) bounds_.extend(p);
  g.name = std::move(name);
  g.source = std::move(source);
  g.vertices = std::move(vertices);
  g.triangles = std::move(triangles);
  geoms_.push_back(std::move(g));
  return std::uint32_t(geoms_.size() - 1);
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const auto& g : geoms_) n += g.triangles.size();
  return n;
}

std::size_t Scene::degenerate_count() const {
  std::size_t n = 0;
  for (const auto& g : geoms_)
    for (auto d : g.degenerate) n += d;
  return n;
}

double Scene::scale() const {
  if (bounds_.empty()) return 1.0;
  const double d = length(bounds_.extent());
  return d > 0.0 ? d : std::max(1.0, bounds_.max_abs_coord());
}

}  // namespace pierce
