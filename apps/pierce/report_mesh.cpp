#include "report_mesh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "base64.h"

namespace pierce::cli {

namespace {

static_assert(std::endian::native == std::endian::little, "the report's page reads little-endian arrays");

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

// Shown vertices and triangles before quantisation.
struct Shown {
  std::vector<Vec3d> vertices;
  std::vector<float> vertex_thickness;
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint32_t> source_triangle;  // index over all of the scene's triangles
  std::vector<std::uint16_t> solid;
};

float thickness_of(const DisplayInput& in, std::uint32_t g, std::size_t element) {
  if (g >= in.thickness.size()) return kNaNf;
  const std::vector<double>& v = in.thickness[g];
  return element < v.size() ? float(v[element]) : kNaNf;
}

// Every triangle, one shown vertex per model vertex.
Shown all_triangles(const DisplayInput& in) {
  Shown s;
  std::size_t tri_base = 0;
  for (std::uint32_t g = 0; g < in.scene->geometries().size(); ++g) {
    const Geometry& geo = in.scene->geometry(g);
    const auto base = std::uint32_t(s.vertices.size());
    s.vertices.insert(s.vertices.end(), geo.vertices.begin(), geo.vertices.end());
    if (in.per_vertex)
      for (std::size_t v = 0; v < geo.vertices.size(); ++v) s.vertex_thickness.push_back(thickness_of(in, g, v));
    for (std::size_t p = 0; p < geo.triangles.size(); ++p) {
      for (int k = 0; k < 3; ++k) s.triangles.push_back(base + geo.triangles[p][k]);
      s.source_triangle.push_back(std::uint32_t(tri_base + p));
      s.solid.push_back(std::uint16_t(std::min<std::uint32_t>(g, 65535)));
    }
    tri_base += geo.triangles.size();
  }
  return s;
}

// The vertices of each solid clustered on a grid of cell `h` (see report_mesh.h).
Shown clustered(const DisplayInput& in, double h) {
  Shown s;
  const Vec3d lo = in.scene->bounds().lo;
  std::unordered_map<std::uint64_t, std::uint32_t> cell_vertex;
  std::vector<std::uint32_t> members;
  std::vector<std::uint32_t> vertex_of;
  std::size_t tri_base = 0;
  for (std::uint32_t g = 0; g < in.scene->geometries().size(); ++g) {
    const Geometry& geo = in.scene->geometry(g);
    cell_vertex.clear();
    vertex_of.resize(geo.vertices.size());
    const auto first = std::uint32_t(s.vertices.size());
    for (std::size_t v = 0; v < geo.vertices.size(); ++v) {
      const Vec3d q = (geo.vertices[v] - lo) * (1.0 / h);
      // 21 bits per axis: the cell is never smaller than the bounds' diagonal / 2^20.
      const auto ix = std::uint64_t(std::clamp(q.x, 0.0, 2097151.0)), iy = std::uint64_t(std::clamp(q.y, 0.0, 2097151.0)),
                 iz = std::uint64_t(std::clamp(q.z, 0.0, 2097151.0));
      const auto [it, added] = cell_vertex.try_emplace(ix | iy << 21 | iz << 42, std::uint32_t(s.vertices.size()));
      if (added) {
        s.vertices.push_back({0, 0, 0});
        members.push_back(0);
        if (in.per_vertex) s.vertex_thickness.push_back(kNaNf);
      }
      const std::uint32_t c = it->second;
      vertex_of[v] = c;
      s.vertices[c] = s.vertices[c] + geo.vertices[v];
      ++members[c];
      if (in.per_vertex) {
        const float t = thickness_of(in, g, v);
        float& shown = s.vertex_thickness[c];
        if (!std::isnan(t) && (std::isnan(shown) || t < shown)) shown = t;
      }
    }
    for (std::uint32_t c = first; c < s.vertices.size(); ++c) s.vertices[c] = s.vertices[c] * (1.0 / members[c]);
    for (std::size_t p = 0; p < geo.triangles.size(); ++p) {
      const std::uint32_t a = vertex_of[geo.triangles[p][0]], b = vertex_of[geo.triangles[p][1]],
                          c = vertex_of[geo.triangles[p][2]];
      if (a == b || b == c || a == c) continue;
      s.triangles.insert(s.triangles.end(), {a, b, c});
      s.source_triangle.push_back(std::uint32_t(tri_base + p));
      s.solid.push_back(std::uint16_t(std::min<std::uint32_t>(g, 65535)));
    }
    tri_base += geo.triangles.size();
  }
  return s;
}

template <class T>
std::string encode(const std::vector<T>& v) {
  return base64(reinterpret_cast<const unsigned char*>(v.data()), v.size() * sizeof(T));
}

}  // namespace

DisplayMesh make_display_mesh(const DisplayInput& in, std::size_t max_triangles) {
  const Scene& scene = *in.scene;
  DisplayMesh m;
  double area = 0;
  for (const Geometry& g : scene.geometries()) {
    m.triangles_model += g.triangles.size();
    for (const Tri& t : g.triangles)
      area += 0.5 * length(cross(g.vertices[t[1]] - g.vertices[t[0]], g.vertices[t[2]] - g.vertices[t[0]]));
  }
  Shown s;
  if (m.triangles_model <= max_triangles) {
    s = all_triangles(in);
  } else {
    // A closed surface of area A clustered with cell h keeps about 2 A / h^2 triangles; start
    // there and grow the cell until few enough remain.
    const Vec3d ext = scene.bounds().hi - scene.bounds().lo;
    const double floor_cell = length(ext) / double(1 << 20);
    double h = std::max(floor_cell, std::sqrt(2 * area / double(std::max<std::size_t>(max_triangles, 1))));
    for (int round = 0; round < 12; ++round) {
      s = clustered(in, h);
      if (s.triangles.size() / 3 <= max_triangles) break;
      h *= std::max(1.05, std::sqrt(double(s.triangles.size() / 3) / double(max_triangles)));
    }
    m.cell = h;
  }

  const BBoxd b = scene.bounds();
  m.origin = b.lo;
  auto step = [](double lo, double hi) { return hi > lo ? (hi - lo) / 65535.0 : 1.0; };
  m.scale = {step(b.lo.x, b.hi.x), step(b.lo.y, b.hi.y), step(b.lo.z, b.hi.z)};
  m.positions.reserve(3 * s.vertices.size());
  for (const Vec3d& v : s.vertices)
    for (int a = 0; a < 3; ++a)
      m.positions.push_back(std::uint16_t(std::clamp(std::lround((v[a] - m.origin[a]) / m.scale[a]), 0L, 65535L)));
  m.triangles = std::move(s.triangles);
  m.triangle_solid = std::move(s.solid);
  m.per_vertex = in.per_vertex;
  if (in.per_vertex) {
    m.thickness = std::move(s.vertex_thickness);
  } else {
    // Per face: each shown triangle keeps the value of the model triangle it comes from.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> owner;  // scene triangle -> (g, p)
    for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
      for (std::uint32_t p = 0; p < scene.geometry(g).triangles.size(); ++p) owner.emplace_back(g, p);
    m.thickness.reserve(s.source_triangle.size());
    for (std::uint32_t t : s.source_triangle) m.thickness.push_back(thickness_of(in, owner[t].first, owner[t].second));
  }
  if (!in.pair_category.empty()) {
    m.pair_category.reserve(s.source_triangle.size());
    for (std::uint32_t t : s.source_triangle) {
      m.pair_category.push_back(std::uint8_t(in.pair_category[t]));
      m.pair_gap.push_back(float(in.pair_gap[t]));
    }
  }
  return m;
}

nlohmann::ordered_json display_mesh_json(const DisplayMesh& m) {
  nlohmann::ordered_json j{{"triangles_model", m.triangles_model},
                           {"triangles_shown", m.triangles_shown()},
                           {"cell", m.cell},
                           {"origin", {m.origin.x, m.origin.y, m.origin.z}},
                           {"scale", {m.scale.x, m.scale.y, m.scale.z}},
                           {"positions", encode(m.positions)},
                           {"triangles", encode(m.triangles)},
                           {"triangle_solid", encode(m.triangle_solid)}};
  j["thickness"] = {{"at", m.per_vertex ? "vertex" : "face"}, {"values", encode(m.thickness)}};
  if (!m.pair_category.empty())
    j["pairs"] = {{"category", encode(m.pair_category)}, {"gap", encode(m.pair_gap)}};
  return j;
}

}  // namespace pierce::cli
