#include "pierce/analysis/mesh_topology.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "pierce/position_index.h"

namespace pierce::analysis {

namespace {

std::array<std::uint32_t, 3> welded(const Tri& t, const std::vector<std::uint32_t>& weld) {
  return {weld[t[0]], weld[t[1]], weld[t[2]]};
}

}  // namespace

std::vector<std::uint32_t> weld_by_position(const std::vector<Vec3d>& vertices) {
  return first_equal_keys<std::array<std::uint64_t, 3>>(
      vertices.size(), [&vertices](std::size_t i) { return position_key(vertices[i], PositionZeros::merged); });
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
  // Triangles with the same welded corners share their lowest corner: bucket the triangles by it
  // (a counting sort, in triangle order) and compare within each bucket, which is about a vertex's
  // valence long. Long buckets (fan centres) are sorted instead of compared pairwise.
  const std::size_t n = g.triangles.size();
  using Key = std::array<std::uint32_t, 3>;
  // The arrays in huge pages (huge_page_allocator.h): each is filled once, at once.
  std::vector<Key> keys = huge_vector<Key>(n);
  std::vector<std::uint32_t> start = huge_vector<std::uint32_t>(g.vertices.size() + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    Key& w = keys[i];
    w = welded(g.triangles[i], weld);
    std::sort(w.begin(), w.end());
    ++start[w[0] + 1];
  }
  for (std::size_t v = 0; v < g.vertices.size(); ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> bucket = huge_vector<std::uint32_t>(n);
  {
    std::vector<std::uint32_t> fill;
    reserve_huge(fill, start.size() - 1);
    fill.assign(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) bucket[fill[keys[i][0]]++] = std::uint32_t(i);
  }
  std::vector<std::uint32_t> first = huge_vector<std::uint32_t>(n);
  constexpr std::size_t kPairwise = 64;
  std::vector<std::uint32_t> order;
  for (std::size_t v = 0; v < g.vertices.size(); ++v) {
    const std::uint32_t* b = bucket.data() + start[v];
    const std::size_t m = start[v + 1] - start[v];
    if (m <= kPairwise) {
      for (std::size_t x = 0; x < m; ++x) {
        first[b[x]] = b[x];
        for (std::size_t y = 0; y < x; ++y)
          if (keys[b[y]] == keys[b[x]]) {
            first[b[x]] = first[b[y]];
            break;
          }
      }
      continue;
    }
    order.assign(b, b + m);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t p, std::uint32_t q) { return keys[p] != keys[q] ? keys[p] < keys[q] : p < q; });
    for (std::size_t x = 0; x < m; ++x)
      first[order[x]] = x > 0 && keys[order[x]] == keys[order[x - 1]] ? first[order[x - 1]] : order[x];
  }
  return first;
}

Vec3d face_normal(const Geometry& g, std::size_t i) {
  const Tri& t = g.triangles[i];
  const Vec3d n = cross(g.vertices[t[1]] - g.vertices[t[0]], g.vertices[t[2]] - g.vertices[t[0]]);
  const double len = length(n);
  return len > 0 && std::isfinite(len) ? n * (1.0 / len) : Vec3d{};
}

std::vector<Vec3d> vertex_normals(const Geometry& g, const std::vector<std::uint32_t>& weld) {
  std::vector<Vec3d> acc = huge_vector<Vec3d>(g.vertices.size());
  // Distinct welded triangles (any winding) contribute once; the first occurrence wins.
  const auto first = first_occurrence(g, weld);
  // Each corner adds the face normal weighted by its angle. The contributions (the acos is the
  // cost) are computed in parallel a block at a time and added in triangle order, so the sums
  // are the same bits on any thread count.
  constexpr std::size_t kBlock = 1 << 16;
  std::vector<std::array<Vec3d, 3>> contrib = huge_vector<std::array<Vec3d, 3>>(std::min(kBlock, g.triangles.size()));
  for (std::size_t b0 = 0; b0 < g.triangles.size(); b0 += kBlock) {
    const std::size_t b1 = std::min(g.triangles.size(), b0 + kBlock);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(b0, b1, 1024), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        std::array<Vec3d, 3>& out = contrib[i - b0];
        out = {};
        if (first[i] != i) continue;
        const Vec3d n = face_normal(g, i);
        if (n == Vec3d{}) continue;
        const Tri& t = g.triangles[i];
        for (int c = 0; c < 3; ++c) {
          const Vec3d p = g.vertices[t[c]];
          const Vec3d e1 = g.vertices[t[(c + 1) % 3]] - p, e2 = g.vertices[t[(c + 2) % 3]] - p;
          const double l1 = length(e1), l2 = length(e2);
          if (!(l1 > 0 && l2 > 0)) continue;
          out[std::size_t(c)] = n * std::acos(std::clamp(dot(e1, e2) / (l1 * l2), -1.0, 1.0));
        }
      }
    });
    for (std::size_t i = b0; i < b1; ++i) {
      if (first[i] != i) continue;
      const Tri& t = g.triangles[i];
      for (int c = 0; c < 3; ++c) acc[weld[t[c]]] = acc[weld[t[c]]] + contrib[i - b0][std::size_t(c)];
    }
  }
  // In place: every vertex welds to the lowest index at its position, whose sum is final (and
  // normalised first, since it comes first).
  for (std::size_t v = 0; v < g.vertices.size(); ++v) {
    if (weld[v] != v) {
      acc[v] = acc[weld[v]];
      continue;
    }
    const double len = length(acc[v]);
    // Normals that (nearly) cancel give no usable direction.
    acc[v] = len > 1e-12 ? acc[v] * (1.0 / len) : Vec3d{};
  }
  return acc;
}

}  // namespace pierce::analysis
