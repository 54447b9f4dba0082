#include "scenes.h"

#include <random>

namespace pierce::test {

namespace {

// Half-open footprint test: the tie rule puts an axis ray through a boundary at (a, b) on the
// side of larger coordinates, for +axis and -axis rays alike (docs/EXACTNESS.md).
bool half_open(double a, double lo, double hi) { return lo <= a && a < hi; }

BBoxd bounds_of(const std::vector<gen::Mesh>& meshes) {
  BBoxd b;
  for (const auto& m : meshes)
    for (const Vec3d& v : m.vertices) b.extend(v);
  return b;
}

struct Builder {
  const Xform& x;
  Case c;
  std::mt19937_64 rng;

  Builder(const Xform& xf, std::vector<gen::Mesh> base, std::uint64_t seed) : x(xf), rng(seed) {
    for (auto& m : base) c.meshes.push_back(transformed(std::move(m), x.scale, x.offset));
  }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  // A ray given in the untransformed frame.
  void add(const Ray& base_ray, Expect e) { c.probes.push_back({transformed(base_ray, x.scale, x.offset), e}); }
  // Rays generated in the transformed frame.
  void add_random(std::size_t n, Expect e) {
    for (const Ray& r : random_rays(bounds_of(c.meshes), n, rng())) c.probes.push_back({r, e});
  }
  void add_vertex_rays(std::size_t n, Expect e) {
    for (const Ray& r : vertex_rays(c.meshes, bounds_of(c.meshes), n, rng())) c.probes.push_back({r, e});
  }
};

// Plates along z: rays through interiors, face diagonals, footprint boundaries and the touching
// planes, and oblique rays.
void plate_probes(Builder& b, int layers, int interior, bool extras) {
  const double top = layers * 0.1;
  const Expect through{2 * layers, true, true};
  for (int i = 0; i < interior; ++i) {
    const double sign = i % 2 ? -1.0 : 1.0;
    b.add({{b.uniform(0.01, 0.99), b.uniform(0.01, 0.99), sign > 0 ? -1.0 : top + 1.0}, axis_unit(2, sign)}, through);
  }
  for (int k = 1; k < 8; ++k)  // face diagonals x = y of both z faces
    b.add({{k / 8.0, k / 8.0, k % 2 ? -1.0 : top + 1.0}, axis_unit(2, k % 2 ? 1.0 : -1.0)}, through);
  if (!extras) return;
  for (double px : {0.0, 0.5, 1.0})
    for (double py : {0.0, 0.5, 1.0})
      for (double sign : {1.0, -1.0}) {
        const bool in = half_open(px, 0, 1) && half_open(py, 0, 1);
        b.add({{px, py, sign > 0 ? -1.0 : top + 1.0}, axis_unit(2, sign)}, {in ? 2 * layers : 0, true, true});
      }
  // Along x in the plane where two plates touch: only the upper plate's sides are crossed.
  for (int k = 0; k <= layers; ++k)
    for (double sign : {1.0, -1.0}) {
      const Ray r{{sign > 0 ? -1.0 : 2.0, b.uniform(0.01, 0.99), k * 0.1}, axis_unit(0, sign)};
      b.add(r, {k < layers ? 2 : 0, true, true});
    }
  // Oblique rays through the edges where plates meet their neighbours' sides.
  for (int k = 0; k <= layers; ++k) b.add({{-1.0, b.uniform(0.01, 0.99), k * 0.1 - 1.0}, {1, 0, 1}}, {-1, true, false});
  b.add_random(60, {-1, true, true});
}

std::vector<gen::Mesh> duplicated_boxes(bool alternate) {
  gen::Mesh a = gen::duplicated(gen::box({0, 0, 0}, {1, 1, 1}, "dupA"), 7, alternate);
  gen::Mesh b = gen::duplicated(gen::box({1, 0, 0}, {2, 1, 1}, "dupB"), 4, alternate);
  return {a, b};
}

}  // namespace

std::string family_name(Family f) {
  switch (f) {
    case Family::soup: return "soup";
    case Family::blob: return "blob";
    case Family::plates: return "plates";
    case Family::plates_reversed: return "plates_reversed";
    case Family::plates_thickness: return "plates_thickness";
    case Family::duplicated_same: return "duplicated_same";
    case Family::duplicated_alternate: return "duplicated_alternate";
    case Family::overlapping: return "overlapping";
    case Family::cube_grid: return "cube_grid";
    case Family::voxel_block: return "voxel_block";
    case Family::deep_plates: return "deep_plates";
  }
  return "?";
}

Case build_case(Family f, const Xform& x) {
  switch (f) {
    case Family::soup: {
      gen::Mesh s2 = gen::random_soup(800, 0.05, 2);
      s2.name = "soup2";
      Builder b(x, {gen::random_soup(800, 0.2, 1), s2}, 101);
      b.add_random(120, {});
      for (int i = 0; i < 40; ++i) {  // origins inside the soup
        const Vec3d dir{b.uniform(-1, 1), b.uniform(-1, 1), b.uniform(-1, 1)};
        b.add({{b.uniform(0, 1), b.uniform(0, 1), b.uniform(0, 1)}, dir}, {});
      }
      for (int i = 0; i < 60; ++i) {  // one or two zero direction components
        Vec3d dir{b.uniform(-1, 1), b.uniform(-1, 1), b.uniform(-1, 1)};
        dir[std::size_t(i % 3)] = 0.0;
        if (i >= 30) dir[std::size_t((i + 1) % 3)] = 0.0;
        const Vec3d org{b.uniform(0, 1), b.uniform(0, 1), b.uniform(0, 1)};
        b.add({org - dir * 2.0, dir}, {});
      }
      b.add_vertex_rays(40, {});
      return std::move(b.c);
    }
    case Family::blob: {
      gen::Mesh small = gen::translated(gen::scaled(gen::blob(2, 9), 0.5), {1.2, 0.3, 0});
      small.name = "blob2";
      Builder b(x, {gen::blob(3, 7), small}, 202);
      b.add_random(120, {-1, true, true});
      b.add_vertex_rays(100, {-1, true, false});
      // Axis rays exactly through (float) vertices, from outside.
      const BBoxd box = bounds_of(b.c.meshes);
      const double far = 2 * length(box.extent());
      for (int i = 0; i < 40; ++i) {
        const auto& m = b.c.meshes[std::size_t(i % 2)];
        const Vec3d v = as_float(m.vertices[b.rng() % m.vertices.size()]);
        const int axis = i % 3;
        const double sign = (i / 3) % 2 ? 1.0 : -1.0;
        Vec3d org = v;
        org[std::size_t(axis)] -= sign * far;
        b.c.probes.push_back({{org, axis_unit(axis, sign * x.scale)}, {-1, true, false}});
      }
      return std::move(b.c);
    }
    case Family::plates:
    case Family::plates_reversed: {
      auto plates = gen::stacked_plates(12);
      if (f == Family::plates_reversed) std::reverse(plates.begin(), plates.end());
      Builder b(x, plates, 303);
      plate_probes(b, 12, 40, true);
      return std::move(b.c);
    }
    case Family::plates_thickness: {
      // Rays starting exactly on a plate face (the surface they start on is hit at t = 0).
      const int n = 12;
      Builder b(x, gen::stacked_plates(n), 404);
      for (int k = 0; k <= n; ++k)
        for (double sign : {1.0, -1.0})
          for (int rep = 0; rep < 4; ++rep) {
            // Every boundary plane from the start on, the start plane included.
            auto boundary_hits = [n](int j) { return j == 0 || j == n ? 1 : 2; };
            int count = 0;
            for (int j = 0; j <= n; ++j)
              if (sign > 0 ? j >= k : j <= k) count += boundary_hits(j);
            const Vec3d dir = rep < 2 ? axis_unit(2, sign) : Vec3d{b.uniform(-0.3, 0.3), b.uniform(-0.3, 0.3), sign};
            const Vec3d org{b.uniform(0.4, 0.6), b.uniform(0.4, 0.6), k * 0.1};
            b.add({org, dir}, {count, false, false});
          }
      return std::move(b.c);
    }
    case Family::duplicated_same:
    case Family::duplicated_alternate: {
      Builder b(x, duplicated_boxes(f == Family::duplicated_alternate), 505);
      // Closed: each copy is a closed surface (inward for flipped copies): as many enters as leaves.
      for (int i = 0; i < 30; ++i) {
        const double sign = i % 2 ? 1.0 : -1.0;
        const bool in_a = i % 4 < 2;
        const double px = in_a ? b.uniform(0.01, 0.99) : b.uniform(1.01, 1.99);
        b.add({{px, b.uniform(0.01, 0.99), sign > 0 ? -1.0 : 2.0}, axis_unit(2, sign)}, {in_a ? 14 : 8, true, false});
        b.add({{sign > 0 ? -1.0 : 3.0, b.uniform(0.01, 0.99), b.uniform(0.01, 0.99)}, axis_unit(0, sign)},
              {22, true, false});
      }
      for (double px : {0.0, 0.25, 0.5, 1.0, 1.5, 2.0})
        for (double py : {0.0, 0.5, 1.0})
          for (double sign : {1.0, -1.0}) {
            int count = 0;
            if (half_open(py, 0, 1)) count = half_open(px, 0, 1) ? 14 : (half_open(px, 1, 2) ? 8 : 0);
            b.add({{px, py, sign > 0 ? -1.0 : 2.0}, axis_unit(2, sign)}, {count, true, false});
          }
      b.add_random(60, {-1, true, false});
      return std::move(b.c);
    }
    case Family::overlapping: {
      // Open unit-ish squares in the plane z = 0.5, corners on a 1/16 grid, random diagonal and
      // facing: partially overlapping coplanar triangles whose corners lie on each other's edges.
      std::mt19937_64 rng(606);
      struct Square {
        double x0, y0, x1, y1;
      };
      std::vector<Square> squares;
      std::vector<gen::Mesh> meshes;
      for (int s = 0; s < 10; ++s) {
        const double x0 = double(rng() % 9) / 16, y0 = double(rng() % 9) / 16;
        const double x1 = x0 + double(4 + rng() % 4) / 16, y1 = y0 + double(4 + rng() % 4) / 16;
        squares.push_back({x0, y0, x1, y1});
        gen::Mesh m;
        m.name = "square" + std::to_string(s);
        m.vertices = {{x0, y0, 0.5}, {x1, y0, 0.5}, {x1, y1, 0.5}, {x0, y1, 0.5}};
        m.triangles = rng() % 2 ? std::vector<Tri>{{0, 1, 2}, {0, 2, 3}} : std::vector<Tri>{{0, 1, 3}, {1, 2, 3}};
        if (rng() % 2)
          for (Tri& t : m.triangles) std::swap(t[1], t[2]);
        meshes.push_back(std::move(m));
      }
      Builder b(x, meshes, 607);
      auto covering = [&](double px, double py) {
        int n = 0;
        for (const Square& q : squares) n += half_open(px, q.x0, q.x1) && half_open(py, q.y0, q.y1);
        return n;
      };
      // Generic points: at least 1/80 from any grid line, far above float rounding at 1e5.
      for (int i = 0; i < 80; ++i) {
        const double px = (double(b.rng() % 16) + b.uniform(0.2, 0.8)) / 16;
        const double py = (double(b.rng() % 16) + b.uniform(0.2, 0.8)) / 16;
        const double sign = i % 2 ? 1.0 : -1.0;
        b.add({{px, py, 0.5 - sign}, axis_unit(2, sign)}, {covering(px, py), false, false});
      }
      // Axis rays through grid points: corners and edges of squares, half-open rule.
      for (int gx = 0; gx <= 16; gx += 1)
        for (int gy = 0; gy <= 16; gy += 2) {
          const double px = gx / 16.0, py = gy / 16.0, sign = (gx + gy / 2) % 2 ? 1.0 : -1.0;
          b.add({{px, py, 0.5 - sign}, axis_unit(2, sign)}, {covering(px, py), false, false});
        }
      // Oblique rays: the plane point decides, when generic.
      for (int i = 0; i < 60; ++i) {
        const double px = (double(b.rng() % 16) + b.uniform(0.2, 0.8)) / 16;
        const double py = (double(b.rng() % 16) + b.uniform(0.2, 0.8)) / 16;
        const Vec3d dir{b.uniform(-0.7, 0.7), b.uniform(-0.7, 0.7), i % 2 ? 1.0 : -1.0};
        b.add({Vec3d{px, py, 0.5} - dir * 1.5, dir}, {covering(px, py), false, false});
      }
      // Oblique rays through grid points (which side is decided by the ray's shear).
      for (int i = 0; i < 60; ++i) {
        const Vec3d p{double(b.rng() % 17) / 16, double(b.rng() % 17) / 16, 0.5};
        const Vec3d dir{double(int(b.rng() % 9) - 4) / 8, double(int(b.rng() % 9) - 4) / 8, i % 2 ? 1.0 : -1.0};
        b.add({p - dir * 2.0, dir}, {});
      }
      return std::move(b.c);
    }
    case Family::cube_grid:
    case Family::voxel_block: {
      const int n = f == Family::cube_grid ? 3 : 4;
      const int per = f == Family::cube_grid ? 2 * n : 2;  // crossings of a column of cubes / the block
      Builder b(x, f == Family::cube_grid ? gen::cube_grid(n) : std::vector<gen::Mesh>{gen::voxel_block(n)}, 707);
      // Axis rays through every integer and half-integer point: edges, vertices, face centres.
      for (int axis = 0; axis < 3; ++axis)
        for (double sign : {1.0, -1.0})
          for (int i = 0; i <= 2 * n; ++i)
            for (int j = 0; j <= 2 * n; ++j) {
              const double p = i / 2.0, q = j / 2.0;
              const bool in = half_open(p, 0, n) && half_open(q, 0, n);
              b.add({on_plane(axis, sign > 0 ? -1.0 : n + 1.0, p, q), axis_unit(axis, sign)}, {in ? per : 0, true, true});
            }
      // Diagonal rays through integer points (through edges and vertices shared by up to 8 cubes).
      const Vec3d dirs[] = {{1, 1, 0},  {1, -1, 0}, {0, 1, 1},  {1, 0, -1}, {1, 1, 1},  {1, -1, 1},
                            {-1, 1, 1}, {1, 2, 0},  {2, 1, 1},  {1, 1, 2},  {-1, -1, -1}, {0, -2, 1}};
      for (int i = 0; i < 120; ++i) {
        const Vec3d p{double(b.rng() % (n + 1)), double(b.rng() % (n + 1)), double(b.rng() % (n + 1))};
        const Vec3d d = dirs[std::size_t(i) % std::size(dirs)];
        b.add({p - d * double(3 * n), d}, {-1, true, false});
      }
      // Rays starting on grid points inside (thickness rays): surfaces at t = 0.
      for (int i = 0; i < 60; ++i) {
        const Vec3d p{double(b.rng() % (n + 1)), double(b.rng() % (2 * n + 1)) / 2, double(b.rng() % (n + 1))};
        const Vec3d d = i % 3 == 0 ? axis_unit(int(i / 3) % 3, (i / 9) % 2 ? 1.0 : -1.0) : dirs[std::size_t(i) % std::size(dirs)];
        b.add({p, d}, {});
      }
      b.add_random(60, {-1, true, true});
      return std::move(b.c);
    }
    case Family::deep_plates: {
      const int layers = 600;  // 1200 surfaces along z
      Builder b(x, gen::stacked_plates(layers), 808);
      plate_probes(b, layers, 8, false);
      // Steep oblique rays through all plates.
      for (int i = 0; i < 4; ++i) {
        const Vec3d dir{b.uniform(-0.01, 0.01), b.uniform(-0.01, 0.01), i % 2 ? 1.0 : -1.0};
        const Vec3d mid{0.5, 0.5, layers * 0.05};
        b.add({mid - dir * (layers * 0.05 + 1), dir}, {2 * layers, true, true});
      }
      for (int k : {1, 300, 599})
        b.add({{-1.0, b.uniform(0.01, 0.99), k * 0.1}, axis_unit(0, 1.0)}, {2, true, true});
      return std::move(b.c);
    }
  }
  return {};
}

}  // namespace pierce::test
