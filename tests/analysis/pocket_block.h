#pragma once
// A block with rectangular pockets milled from its top, leaving floors of known thickness: the
// thin-wall regions' test model (exact thickness, area and position of every floor).
#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "pierce/generators.h"

namespace pierce::test {

struct Pocket {
  double x0, x1, y0, y1;  // footprint
  double floor;           // thickness left under it (the pocket runs from z = floor to the top)
};

// Appends quad p0 p1 p2 p3 (a planar rectangle, corners in order) as two triangles p0 p1 p2 and
// p0 p2 p3, wound so that their normal points along `outward`.
inline void add_quad(gen::Mesh& m, std::array<std::uint32_t, 4> q, Vec3d outward) {
  const Vec3d n = cross(m.vertices[q[1]] - m.vertices[q[0]], m.vertices[q[2]] - m.vertices[q[0]]);
  if (dot(n, outward) < 0) std::swap(q[1], q[3]);
  m.triangles.push_back({q[0], q[1], q[2]});
  m.triangles.push_back({q[0], q[2], q[3]});
}

// Block [0, size] with the pockets, meshed on a grid through every box coordinate, each interval
// split into steps of at most `step`: one closed, consistently wound mesh whose top and bottom
// quads share their diagonals' direction.
inline gen::Mesh pocket_block(Vec3d size, const std::vector<Pocket>& pockets, double step) {
  std::array<std::vector<double>, 3> lines;
  for (int a = 0; a < 3; ++a) lines[std::size_t(a)] = {0.0, a == 0 ? size.x : a == 1 ? size.y : size.z};
  for (const Pocket& p : pockets) {
    lines[0].insert(lines[0].end(), {p.x0, p.x1});
    lines[1].insert(lines[1].end(), {p.y0, p.y1});
    lines[2].push_back(p.floor);
  }
  for (auto& l : lines) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
    std::vector<double> fine{l.front()};
    for (std::size_t i = 1; i < l.size(); ++i) {
      const int parts = std::max(1, int(std::ceil((l[i] - l[i - 1]) / step)));
      for (int k = 1; k < parts; ++k) fine.push_back(l[i - 1] + (l[i] - l[i - 1]) * k / parts);
      fine.push_back(l[i]);
    }
    l = fine;
  }
  const auto nx = lines[0].size() - 1, ny = lines[1].size() - 1, nz = lines[2].size() - 1;
  auto solid = [&](long i, long j, long k) {
    if (i < 0 || j < 0 || k < 0 || i >= long(nx) || j >= long(ny) || k >= long(nz)) return false;
    const double x = 0.5 * (lines[0][std::size_t(i)] + lines[0][std::size_t(i) + 1]);
    const double y = 0.5 * (lines[1][std::size_t(j)] + lines[1][std::size_t(j) + 1]);
    const double z = 0.5 * (lines[2][std::size_t(k)] + lines[2][std::size_t(k) + 1]);
    for (const Pocket& p : pockets)
      if (x > p.x0 && x < p.x1 && y > p.y0 && y < p.y1 && z > p.floor) return false;
    return true;
  };
  gen::Mesh m;
  m.name = "pocket_block";
  std::map<std::array<std::size_t, 3>, std::uint32_t> index;
  auto vertex = [&](std::array<std::size_t, 3> g) {
    auto [it, added] = index.emplace(g, std::uint32_t(m.vertices.size()));
    if (added) m.vertices.push_back({lines[0][g[0]], lines[1][g[1]], lines[2][g[2]]});
    return it->second;
  };
  for (long i = 0; i < long(nx); ++i)
    for (long j = 0; j < long(ny); ++j)
      for (long k = 0; k < long(nz); ++k) {
        if (!solid(i, j, k)) continue;
        const std::array<long, 3> c{i, j, k};
        for (int a = 0; a < 3; ++a)
          for (int side = 0; side < 2; ++side) {
            std::array<long, 3> nb = c;
            nb[std::size_t(a)] += side ? 1 : -1;
            if (solid(nb[0], nb[1], nb[2])) continue;
            // The face's corners: axis a fixed, the other two (b, c) in cyclic order.
            const int b = (a + 1) % 3, d = (a + 2) % 3;
            std::array<std::uint32_t, 4> q{};
            const int corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int k2 = 0; k2 < 4; ++k2) {
              std::array<std::size_t, 3> g{std::size_t(c[0]), std::size_t(c[1]), std::size_t(c[2])};
              g[std::size_t(a)] += std::size_t(side);
              g[std::size_t(b)] += std::size_t(corners[k2][0]);
              g[std::size_t(d)] += std::size_t(corners[k2][1]);
              q[std::size_t(k2)] = vertex(g);
            }
            Vec3d out{};
            (a == 0 ? out.x : a == 1 ? out.y : out.z) = side ? 1.0 : -1.0;
            add_quad(m, q, out);
          }
      }
  return m;
}

// The same block with one pocket, meshed as coarsely as a CAD exporter might: the bottom and the
// floor are two triangles each, the top a ring of four quads around the pocket's rim.
inline gen::Mesh coarse_pocket_block(Vec3d size, const Pocket& p) {
  gen::Mesh m;
  m.name = "coarse_pocket_block";
  auto v = [&](double x, double y, double z) {
    m.vertices.push_back({x, y, z});
    return std::uint32_t(m.vertices.size() - 1);
  };
  const double X = size.x, Y = size.y, Z = size.z;
  const std::uint32_t b0 = v(0, 0, 0), b1 = v(X, 0, 0), b2 = v(X, Y, 0), b3 = v(0, Y, 0);
  const std::uint32_t t0 = v(0, 0, Z), t1 = v(X, 0, Z), t2 = v(X, Y, Z), t3 = v(0, Y, Z);
  const std::uint32_t r0 = v(p.x0, p.y0, Z), r1 = v(p.x1, p.y0, Z), r2 = v(p.x1, p.y1, Z), r3 = v(p.x0, p.y1, Z);
  const std::uint32_t f0 = v(p.x0, p.y0, p.floor), f1 = v(p.x1, p.y0, p.floor), f2 = v(p.x1, p.y1, p.floor),
                      f3 = v(p.x0, p.y1, p.floor);
  add_quad(m, {b0, b1, b2, b3}, {0, 0, -1});
  add_quad(m, {b0, b1, t1, t0}, {0, -1, 0});
  add_quad(m, {b1, b2, t2, t1}, {1, 0, 0});
  add_quad(m, {b2, b3, t3, t2}, {0, 1, 0});
  add_quad(m, {b3, b0, t0, t3}, {-1, 0, 0});
  add_quad(m, {t0, t1, r1, r0}, {0, 0, 1});
  add_quad(m, {t1, t2, r2, r1}, {0, 0, 1});
  add_quad(m, {t2, t3, r3, r2}, {0, 0, 1});
  add_quad(m, {t3, t0, r0, r3}, {0, 0, 1});
  add_quad(m, {r0, r1, f1, f0}, {0, 1, 0});  // pocket walls face into the pocket
  add_quad(m, {r1, r2, f2, f1}, {-1, 0, 0});
  add_quad(m, {r2, r3, f3, f2}, {0, -1, 0});
  add_quad(m, {r3, r0, f0, f3}, {1, 0, 0});
  add_quad(m, {f0, f1, f2, f3}, {0, 0, 1});
  return m;
}

}  // namespace pierce::test
