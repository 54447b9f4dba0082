#include "pierce/generators.h"

#include <cmath>
#include <map>
#include <random>
#include <sstream>

namespace pierce::gen {

Mesh box(Vec3d lo, Vec3d hi, std::string name) {
  Mesh m;
  m.name = std::move(name);
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Outward CCW faces: -x, +x, -y, +y, -z, +z.
  m.triangles = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
  return m;
}

std::vector<Mesh> stacked_plates(int layers, double size, double thickness) {
  std::vector<Mesh> out;
  for (int i = 0; i < layers; ++i)
    out.push_back(box({0, 0, i * thickness}, {size, size, (i + 1) * thickness}, "plate" + std::to_string(i)));
  return out;
}

std::vector<Mesh> cube_grid(int n) {
  std::vector<Mesh> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        Mesh b = box({double(i), double(j), double(k)}, {i + 1.0, j + 1.0, k + 1.0},
                     "cube_" + std::to_string(i) + "_" + std::to_string(j) + "_" + std::to_string(k));
        if ((i + j + k) % 2 == 1) {
          // Other diagonal on every face: the two triangles of a quad a,b,c,d (a-b-c, a-c-d)
          // become (a-b-d, b-c-d).
          std::vector<Tri> t;
          for (std::size_t f = 0; f < b.triangles.size(); f += 2) {
            const Tri t0 = b.triangles[f], t1 = b.triangles[f + 1];
            const std::uint32_t a = t0[0], bb = t0[1], c = t0[2], d = t1[2];
            t.push_back({a, bb, d});
            t.push_back({bb, c, d});
          }
          b.triangles = t;
        }
        out.push_back(std::move(b));
      }
  return out;
}

Mesh voxel_block(int n) {
  Mesh m;
  m.name = "voxel_block";
  std::map<std::tuple<int, int, int>, std::uint32_t> ids;
  auto vid = [&](int x, int y, int z) {
    auto [it, fresh] = ids.try_emplace({x, y, z}, std::uint32_t(m.vertices.size()));
    if (fresh) m.vertices.push_back({double(x), double(y), double(z)});
    return it->second;
  };
  // For each axis and each boundary side, emit unit quads with outward winding.
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          auto corner = [&](int da, int db) {
            int p[3];
            p[axis] = side * n, p[u] = a + da, p[v] = b + db;
            return vid(p[0], p[1], p[2]);
          };
          std::uint32_t q[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
          // (u, v, axis) is right-handed: CCW in (u, v) faces +axis.
          if (side == 0) std::swap(q[1], q[3]);
          if ((a + b) % 2 == 0) {
            m.triangles.push_back({q[0], q[1], q[2]});
            m.triangles.push_back({q[0], q[2], q[3]});
          } else {
            m.triangles.push_back({q[0], q[1], q[3]});
            m.triangles.push_back({q[1], q[2], q[3]});
          }
        }
  }
  return m;
}

Mesh random_soup(std::size_t count, double size, std::uint64_t seed) {
  Mesh m;
  m.name = "soup";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0), D(-0.5, 0.5);
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3d c{U(rng), U(rng), U(rng)};
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + Vec3d{D(rng), D(rng), D(rng)} * size);
    const auto b = std::uint32_t(3 * i);
    m.triangles.push_back({b, b + 1, b + 2});
  }
  return m;
}

Mesh blob(int subdivisions, std::uint64_t seed, double bumpiness) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3d> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                          {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  std::vector<Tri> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& x : v) x = x * (1.0 / length(x));
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, fresh] = mid.try_emplace({key.first, key.second}, std::uint32_t(v.size()));
      if (fresh) {
        Vec3d m = (v[a] + v[b]) * 0.5;
        v.push_back(m * (1.0 / length(m)));
      }
      return it->second;
    };
    std::vector<Tri> nf;
    for (const Tri& t : f) {
      const std::uint32_t a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
      nf.push_back({t[0], a, c});
      nf.push_back({t[1], b, a});
      nf.push_back({t[2], c, b});
      nf.push_back({a, b, c});
    }
    f = std::move(nf);
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ph(0.0, 6.283185307179586);
  const double p1 = ph(rng), p2 = ph(rng), p3 = ph(rng);
  for (auto& x : v) {
    const double r = 1.0 + bumpiness * (0.5 * std::sin(3 * x.x + p1) * std::sin(2 * x.y + p2) +
                                        0.5 * std::sin(4 * x.z + p3) * std::cos(3 * x.x));
    x = x * r;
  }
  return {"blob", v, f};
}

Mesh duplicated(const Mesh& m, int copies, bool alternate_winding) {
  Mesh out{m.name, m.vertices, {}};
  for (int c = 0; c < copies; ++c)
    for (Tri t : m.triangles) {
      if (alternate_winding && c % 2 == 1) std::swap(t[1], t[2]);
      out.triangles.push_back(t);
    }
  return out;
}

Mesh translated(Mesh m, Vec3d offset) {
  for (auto& v : m.vertices) v = v + offset;
  return m;
}

Mesh scaled(Mesh m, double factor) {
  for (auto& v : m.vertices) v = v * factor;
  return m;
}

Scene to_scene(const std::vector<Mesh>& meshes) {
  Scene s;
  for (const Mesh& m : meshes) s.add_mesh(m.vertices, m.triangles, m.name, "generated");
  return s;
}

std::string to_obj(const std::vector<Mesh>& meshes) {
  std::ostringstream o;
  o.precision(17);
  std::size_t base = 1;
  for (const Mesh& m : meshes) {
    o << "o " << (m.name.empty() ? "mesh" : m.name) << "\n";
    for (const Vec3d& v : m.vertices) o << "v " << v.x << " " << v.y << " " << v.z << "\n";
    for (const Tri& t : m.triangles) o << "f " << t[0] + base << " " << t[1] + base << " " << t[2] + base << "\n";
    base += m.vertices.size();
  }
  return o.str();
}

Mesh flipped(Mesh m) {
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

Mesh merged(Mesh a, const Mesh& b) {
  const auto base = std::uint32_t(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (Tri t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return a;
}

Mesh icosphere(int subdivisions, double radius, Vec3d centre) {
  Mesh m = blob(subdivisions, 7, 0.0);
  m.name = "sphere";
  return translated(scaled(m, radius), centre);
}

Mesh hollow_sphere(int outer_subdivisions, int inner_subdivisions, double inner) {
  Mesh m = merged(icosphere(outer_subdivisions), flipped(icosphere(inner_subdivisions, inner)));
  m.name = "hollow_sphere";
  return m;
}

}  // namespace pierce::gen
