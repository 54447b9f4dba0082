#include "pierce/analysis/mesh_topology.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <unordered_map>

namespace pierce::analysis {

namespace {

struct PositionKey {
  std::uint64_t x, y, z;
  bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= k.y + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= k.z + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return std::size_t(h);
  }
};

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v); }

std::array<std::uint32_t, 3> welded(const Tri& t, const std::vector<std::uint32_t>& weld) {
  return {weld[t[0]], weld[t[1]], weld[t[2]]};
}

}  // namespace

std::vector<std::uint32_t> weld_by_position(const std::vector<Vec3d>& vertices) {
  std::vector<std::uint32_t> rep(vertices.size());
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> first;
  first.reserve(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec3d& p = vertices[i];
    rep[i] = first.try_emplace(PositionKey{bits(p.x), bits(p.y), bits(p.z)}, std::uint32_t(i)).first->second;
  }
  return rep;
}

EdgeStats edge_stats(const Geometry& g, const std::vector<std::uint32_t>& weld) {
  // (key, direction): key = (min, max) welded ids, direction 0 if the triangle runs min -> max.
  std::vector<std::pair<std::uint64_t, std::uint8_t>> half;
  half.reserve(g.triangles.size() * 3);
  for (const Tri& t : g.triangles) {
    const auto w = welded(t, weld);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = w[k], b = w[(k + 1) % 3];
      if (a == b) continue;
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      half.emplace_back(key, a < b ? 0 : 1);
    }
  }
  std::sort(half.begin(), half.end());
  EdgeStats s;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    std::size_t forward = 0;
    while (j < half.size() && half[j].first == half[i].first) forward += half[j++].second == 0;
    const std::size_t n = j - i;
    ++s.edges;
    if (n == 1) ++s.boundary;
    else if (n > 2) ++s.non_manifold;
    else if (forward != 1) ++s.inconsistent;
    i = j;
  }
  return s;
}

std::size_t duplicate_triangles(const Geometry& g, const std::vector<std::uint32_t>& weld) {
  std::vector<std::array<std::uint32_t, 3>> keys;
  keys.reserve(g.triangles.size());
  for (const Tri& t : g.triangles) {
    auto w = welded(t, weld);
    std::sort(w.begin(), w.end());
    keys.push_back(w);
  }
  std::sort(keys.begin(), keys.end());
  std::size_t dup = 0;
  for (std::size_t i = 1; i < keys.size(); ++i) dup += keys[i] == keys[i - 1];
  return dup;
}

std::vector<std::uint32_t> first_occurrence(const Geometry& g, const std::vector<std::uint32_t>& weld) {
  std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> keys;
  keys.reserve(g.triangles.size());
  for (std::size_t i = 0; i < g.triangles.size(); ++i) {
    auto w = welded(g.triangles[i], weld);
    std::sort(w.begin(), w.end());
    keys.emplace_back(w, std::uint32_t(i));
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> first(g.triangles.size());
  for (std::size_t k = 0; k < keys.size(); ++k)
    first[keys[k].second] = k > 0 && keys[k].first == keys[k - 1].first ? first[keys[k - 1].second] : keys[k].second;
  return first;
}

Vec3d face_normal(const Geometry& g, std::size_t i) {
  const Tri& t = g.triangles[i];
  const Vec3d n = cross(g.vertices[t[1]] - g.vertices[t[0]], g.vertices[t[2]] - g.vertices[t[0]]);
  const double len = length(n);
  return len > 0 && std::isfinite(len) ? n * (1.0 / len) : Vec3d{};
}

std::vector<Vec3d> vertex_normals(const Geometry& g, const std::vector<std::uint32_t>& weld) {
  std::vector<Vec3d> acc(g.vertices.size());
  // Distinct welded triangles (any winding) contribute once; the first occurrence wins.
  const auto first = first_occurrence(g, weld);
  for (std::size_t i = 0; i < g.triangles.size(); ++i) {
    if (first[i] != i) continue;
    const Vec3d n = face_normal(g, i);
    if (n == Vec3d{}) continue;
    const Tri& t = g.triangles[i];
    for (int c = 0; c < 3; ++c) {
      const Vec3d p = g.vertices[t[c]];
      const Vec3d e1 = g.vertices[t[(c + 1) % 3]] - p, e2 = g.vertices[t[(c + 2) % 3]] - p;
      const double l1 = length(e1), l2 = length(e2);
      if (!(l1 > 0 && l2 > 0)) continue;
      const double angle = std::acos(std::clamp(dot(e1, e2) / (l1 * l2), -1.0, 1.0));
      acc[weld[t[c]]] = acc[weld[t[c]]] + n * angle;
    }
  }
  std::vector<Vec3d> out(g.vertices.size());
  for (std::size_t v = 0; v < g.vertices.size(); ++v) {
    const Vec3d a = acc[weld[v]];
    const double len = length(a);
    // Normals that (nearly) cancel give no usable direction.
    out[v] = len > 1e-12 ? a * (1.0 / len) : Vec3d{};
  }
  return out;
}

}  // namespace pierce::analysis
