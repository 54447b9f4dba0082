#include "cad_split.h"

#include <gp_Pnt.hxx>

#include <algorithm>
#include <array>
#include <deque>
#include <unordered_map>
#include <vector>

#include "cad_faces.h"
#include "pierce/bbox.h"

namespace pierce {

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b);
}

}  // namespace

bool split_long_edges(CadSolid& s, double max_edge, std::size_t max_triangles) {
  if (!(max_edge > 0) || s.triangles.empty()) return true;
  const double limit2 = max_edge * max_edge;
  auto length2 = [&](std::uint32_t a, std::uint32_t b) {
    const Vec3d d = s.vertices[a] - s.vertices[b];
    return dot(d, d);
  };

  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> edge_triangles;
  // A mesh edge along a B-rep edge (its triangles on different faces) is split only where its
  // midpoint lies on every face's surface (a straight B-rep edge, as a flat face's outline):
  // the midpoint of a chord of a curved B-rep edge lies off the edge, outside one of the faces.
  const std::vector<CadFaces::Face>& faces = s.link.faces->faces;
  BBoxd box;
  for (const Vec3d& p : s.vertices) box.extend(p);
  const double on_surface = 1e-9 * std::max(length(box.extent()), box.max_abs_coord());
  auto splittable = [&](std::uint32_t a, std::uint32_t b) {
    const std::vector<std::uint32_t>& sharing = edge_triangles[edge_key(a, b)];
    bool one_face = true;
    for (const std::uint32_t x : sharing) one_face = one_face && s.link.face[x] == s.link.face[sharing.front()];
    if (one_face) return true;
    const Vec3d m = (s.vertices[a] + s.vertices[b]) * 0.5;
    for (const std::uint32_t x : sharing) {
      const Tri& tri = s.triangles[x];
      const CadFaces::Face& f = faces[s.link.face[x]];
      if (f.surface.IsNull()) return false;
      double u = 0, v = 0;
      for (int k = 0; k < 3; ++k)
        if (tri[std::size_t(k)] == a || tri[std::size_t(k)] == b) {
          u += 0.5 * s.link.uv[x][std::size_t(2 * k)];
          v += 0.5 * s.link.uv[x][std::size_t(2 * k + 1)];
        }
      const gp_Pnt p = f.surface->Value(u, v);
      if (length(Vec3d{p.X(), p.Y(), p.Z()} - m) > on_surface) return false;
    }
    return true;
  };
  auto link = [&](std::uint32_t t) {
    const Tri& tri = s.triangles[t];
    for (int k = 0; k < 3; ++k) edge_triangles[edge_key(tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)])].push_back(t);
  };
  auto unlink = [&](std::uint32_t t) {
    const Tri& tri = s.triangles[t];
    for (int k = 0; k < 3; ++k) {
      auto& list = edge_triangles[edge_key(tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)])];
      list.erase(std::find(list.begin(), list.end(), t));
    }
  };
  // The longest edge of triangle t that may be split, as its first corner k (edge k -> k+1), and
  // its squared length (-1: none); ties go to the edge with the smaller key, so both triangles
  // along an edge agree on it.
  auto longest = [&](std::size_t t) {
    const Tri& tri = s.triangles[t];
    int best = 0;
    double best2 = -1;
    std::uint64_t best_key = 0;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[std::size_t(k)], b = tri[std::size_t((k + 1) % 3)];
      const double l2 = length2(a, b);
      const std::uint64_t key = edge_key(a, b);
      if (!(l2 > limit2) || !(l2 > best2 || (l2 == best2 && key < best_key)) || !splittable(a, b)) continue;
      best = k, best2 = l2, best_key = key;
    }
    return std::pair{best, best2};
  };
  for (std::uint32_t t = 0; t < s.triangles.size(); ++t) link(t);
  std::deque<std::uint32_t> work;
  for (std::uint32_t t = 0; t < s.triangles.size(); ++t) work.push_back(t);

  while (!work.empty()) {
    const std::uint32_t t = work.front();
    work.pop_front();
    const auto [k, l2] = longest(t);
    if (l2 < 0) continue;
    if (s.triangles.size() >= max_triangles) return false;
    const std::uint32_t a = s.triangles[t][std::size_t(k)], b = s.triangles[t][std::size_t((k + 1) % 3)];
    const auto m = std::uint32_t(s.vertices.size());
    s.vertices.push_back((s.vertices[a] + s.vertices[b]) * 0.5);
    const std::vector<std::uint32_t> sharing = edge_triangles[edge_key(a, b)];
    for (const std::uint32_t x : sharing) {
      unlink(x);
      // Rotate x's corners (and their (u, v)) so that the split edge is its corners 0 -> 1.
      Tri tri = s.triangles[x];
      std::array<double, 6> uv = s.link.uv[x];
      while (edge_key(tri[0], tri[1]) != edge_key(a, b)) {
        tri = {tri[1], tri[2], tri[0]};
        uv = {uv[2], uv[3], uv[4], uv[5], uv[0], uv[1]};
      }
      const double um = 0.5 * (uv[0] + uv[2]), vm = 0.5 * (uv[1] + uv[3]);
      const auto y = std::uint32_t(s.triangles.size());
      s.triangles[x] = {tri[0], m, tri[2]};
      s.link.uv[x] = {uv[0], uv[1], um, vm, uv[4], uv[5]};
      s.triangles.push_back({m, tri[1], tri[2]});
      s.link.uv.push_back({um, vm, uv[2], uv[3], uv[4], uv[5]});
      s.link.face.push_back(s.link.face[x]);
      s.link.flags.push_back(s.link.flags[x]);
      link(x);
      link(y);
      work.push_back(x);
      work.push_back(y);
    }
    edge_triangles.erase(edge_key(a, b));
  }
  return true;
}

}  // namespace pierce
