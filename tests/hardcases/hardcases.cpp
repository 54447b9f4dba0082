#include "hardcases.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

namespace pierce::hard {

namespace {

using gen::Mesh;

std::uint64_t splitmix(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
int pick(std::uint64_t& s, int n) { return int(splitmix(s) % std::uint64_t(n)); }

bool is_float(double x) { return double(float(x)) == x; }
bool is_float(const Vec3d& v) { return is_float(v.x) && is_float(v.y) && is_float(v.z); }

BBoxd bounds_of(const std::vector<Mesh>& meshes) {
  BBoxd b;
  for (const Mesh& m : meshes)
    for (const Vec3d& v : m.vertices) b.extend(v);
  return b;
}

Case make_case(std::string family, std::string name, const std::vector<Mesh>& meshes, std::vector<Ray> rays,
               bool float_exact = true) {
  Case c;
  c.family = std::move(family);
  c.name = std::move(name);
  c.scene = gen::to_scene(meshes);
  c.rays = std::move(rays);
  c.float_exact = float_exact;
  return c;
}

// Octahedron with vertices center +- r e_i: faces in tilted planes, closed, outward CCW.
Mesh octahedron(Vec3d c, double r) {
  Mesh m;
  m.name = "octahedron";
  m.vertices = {c + Vec3d{r, 0, 0}, c + Vec3d{-r, 0, 0}, c + Vec3d{0, r, 0},
                c + Vec3d{0, -r, 0}, c + Vec3d{0, 0, r}, c + Vec3d{0, 0, -r}};
  // +x=0 -x=1 +y=2 -y=3 +z=4 -z=5
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

// Closed bipyramid: `per_side` vertices on each side of the square [-1,1]^2 at z = 0 (all on
// a dyadic grid), apexes (0,0,+-h): two fan vertices of valence 4 * per_side.
Mesh bipyramid(int per_side, double h) {
  Mesh m;
  m.name = "bipyramid";
  std::vector<Vec3d> ring;
  const double step = 2.0 / per_side;
  for (int i = 0; i < per_side; ++i) ring.push_back({-1 + i * step, -1, 0});
  for (int i = 0; i < per_side; ++i) ring.push_back({1, -1 + i * step, 0});
  for (int i = 0; i < per_side; ++i) ring.push_back({1 - i * step, 1, 0});
  for (int i = 0; i < per_side; ++i) ring.push_back({-1, 1 - i * step, 0});
  m.vertices = ring;
  const auto n = std::uint32_t(ring.size());
  m.vertices.push_back({0, 0, h});
  m.vertices.push_back({0, 0, -h});
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, n});      // ring is CCW seen from +z: upper fan faces outward
    m.triangles.push_back({j, i, n + 1});  // lower fan, reversed
  }
  return m;
}

// One quad (two triangles) at height z over [x0,x1] x [y0,y1], normal +z; diagonal choice by `alt`.
Mesh quad(double x0, double y0, double x1, double y1, double z, bool alt, std::string name = "quad") {
  Mesh m;
  m.name = std::move(name);
  m.vertices = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  if (alt)
    m.triangles = {{0, 1, 3}, {1, 2, 3}};
  else
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

Mesh rounded_to_float(Mesh m) {
  for (Vec3d& v : m.vertices) v = Vec3d(Vec3f(v));
  return m;
}

std::vector<Vec3d> grid_points(double x0, double x1, double y0, double y1, double z, double step) {
  std::vector<Vec3d> p;
  for (double x = x0; x <= x1; x += step)
    for (double y = y0; y <= y1; y += step) p.push_back({x, y, z});
  return p;
}

std::vector<Vec3d> concat(std::vector<Vec3d> a, const std::vector<Vec3d>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

Vec3d dyadic_direction(std::uint64_t& state, int axis, int sign) {
  Vec3d d;
  for (int k = 0; k < 3; ++k) d[k] = k == axis ? double(sign) : 0.25 * double(pick(state, 7) - 3);  // -3/4 .. 3/4
  return d;
}

Ray ray_through(const Vec3d& target, const Vec3d& dir, const BBoxd& bounds) {
  double reach = 1e-30;
  for (int k = 0; k < 3; ++k)
    reach = std::max({reach, std::abs(bounds.hi[k] - target[k]), std::abs(target[k] - bounds.lo[k])});
  const double s = std::exp2(std::ceil(std::log2(2.0 * reach)));  // power of two, > every extent from target
  Ray r;
  r.org = target - dir * s;
  r.dir = dir;
  return r;
}

std::vector<Vec3d> targets_of(const std::vector<Mesh>& meshes) {
  std::set<std::tuple<double, double, double>> seen;
  std::vector<Vec3d> out;
  auto add = [&](const Vec3d& p) {
    if (seen.insert({p.x, p.y, p.z}).second) out.push_back(p);
  };
  for (const Mesh& m : meshes)
    for (const Tri& t : m.triangles) {
      const Vec3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
      add(a), add(b), add(c);
      add((a + b) * 0.5), add((b + c) * 0.5), add((c + a) * 0.5);
      add((a + b + c) * (1.0 / 3.0));
    }
  return out;
}

std::vector<Ray> rays_through_targets(const std::vector<Vec3d>& targets, const BBoxd& bounds, int count,
                                      std::uint64_t seed, bool tilted, bool require_float) {
  std::vector<Ray> rays;
  if (targets.empty()) return rays;
  std::uint64_t s = seed;
  for (int tries = 0; int(rays.size()) < count && tries < 20 * count; ++tries) {
    const Vec3d& p = targets[std::size_t(pick(s, int(targets.size())))];
    const int axis = pick(s, 3), sign = pick(s, 2) ? 1 : -1;
    Vec3d d;
    if (tilted && pick(s, 2)) {
      d = dyadic_direction(s, axis, sign);
    } else {
      d[axis] = sign;
    }
    Ray r = ray_through(p, d, bounds);
    if (require_float) {
      if (!is_float(p)) continue;
      // An axis ray's path does not depend on its origin's coordinate along the axis: round it.
      if (!is_float(r.org) && d[axis] != 0 && d[(axis + 1) % 3] == 0 && d[(axis + 2) % 3] == 0)
        r.org = Vec3d(Vec3f(r.org));
      if (!is_float(r.org)) continue;
    }
    rays.push_back(r);
  }
  return rays;
}

// ---------------------------------------------------------------------------------------------

// The triangles of the unit box gen::box({0, 0, 0}, {1, 1, 1}) except its top face (z = 1), for
// the cases that replace the top by a mesh of their own.
std::vector<Tri> triangles_below_top(const Mesh& box) {
  std::vector<Tri> tris;
  for (const Tri& t : box.triangles) {
    bool top = true;
    for (auto i : t) top = top && box.vertices[i].z == 1.0;
    if (!top) tris.push_back(t);
  }
  return tris;
}

std::vector<Case> coplanar_duplicates(const Options& o) {
  std::vector<Case> out;
  const Mesh box = gen::box({0, 0, 0}, {1, 1, 1});
  const Mesh oct = octahedron({2, 0.5, 0.5}, 0.5);
  const std::vector<Mesh> single = {box, oct};
  const BBoxd b = bounds_of(single);
  const std::vector<Vec3d> targets = targets_of(single);
  for (const bool opposite : {false, true}) {
    const std::string fam = opposite ? "coplanar duplicates, opposite winding" : "coplanar duplicates, same winding";
    for (const int copies : {2, 3}) {
      // One geometry holding k copies, plus a second geometry repeating the first copy.
      std::vector<Mesh> meshes = {gen::duplicated(box, copies, opposite), gen::duplicated(oct, copies, opposite)};
      Mesh again = opposite ? gen::duplicated(box, 2, true) : box;
      meshes.push_back(again);
      out.push_back(make_case(fam, "copies=" + std::to_string(copies), meshes,
                              rays_through_targets(targets, b, o.rays_per_case, o.seed + 11 * copies + opposite)));
    }
  }
  return out;
}

std::vector<Case> coplanar_overlaps(const Options& o) {
  // Triangles on a 1/16 grid in planes perpendicular to an axis, each its own geometry,
  // overlapping partially (shared edges, vertices inside others, crossing edges).
  std::vector<Case> out;
  std::uint64_t s = o.seed * 7919 + 3;
  for (int variant = 0; variant < 2; ++variant) {
    std::vector<Mesh> meshes;
    std::vector<Vec3d> extra_targets;
    for (int i = 0; i < 16; ++i) {
      Mesh m;
      m.name = "tri" + std::to_string(i);
      const int axis = variant == 0 ? 2 : pick(s, 3);
      const double level = variant == 0 ? 0.5 : 0.25 * pick(s, 5);
      for (int k = 0; k < 3; ++k) {
        Vec3d p;
        p[axis] = level;
        p[(axis + 1) % 3] = pick(s, 17) / 16.0;
        p[(axis + 2) % 3] = pick(s, 17) / 16.0;
        m.vertices.push_back(p);
      }
      m.triangles = {{0, 1, 2}};
      meshes.push_back(m);
    }
    // A shared quad split both ways, and the same quad as one big triangle pair with a
    // vertex on the other's diagonal.
    meshes.push_back(quad(0, 0, 1, 1, 0.5, false, "quad_a"));
    meshes.push_back(quad(0, 0, 1, 1, 0.5, true, "quad_b"));
    meshes.push_back(quad(0.25, 0.25, 0.75, 0.75, 0.5, false, "quad_c"));
    for (int i = 0; i <= 16; ++i)
      for (int j = 0; j <= 16; ++j) extra_targets.push_back({i / 16.0, j / 16.0, 0.5});
    const BBoxd b = bounds_of(meshes);
    out.push_back(make_case("coplanar partial overlaps", variant == 0 ? "plane z=0.5" : "axis planes",
                            meshes,
                            rays_through_targets(concat(targets_of(meshes), extra_targets), b, o.rays_per_case,
                                                 o.seed + 101 + variant)));
  }
  return out;
}

std::vector<Case> touching_plates(const Options& o) {
  std::vector<Case> out;
  {
    const std::vector<Mesh> plates = gen::stacked_plates(8, 1.0, 0.125);
    const BBoxd b = bounds_of(plates);
    std::vector<Vec3d> t = targets_of(plates);
    for (int i = 0; i <= 8; ++i) t = concat(t, grid_points(0, 1, 0, 1, i * 0.125, 0.125));
    out.push_back(make_case("touching plates", "8 layers", plates, rays_through_targets(t, b, o.rays_per_case, o.seed + 201)));
  }
  {
    // Armour-like: plates of different footprints sharing parts of their faces.
    std::vector<Mesh> plates;
    const double fp[6][4] = {{0, 0, 1, 1}, {0.25, 0, 0.75, 1}, {0, 0.25, 1, 0.75},
                             {0, 0, 0.5, 0.5}, {0.5, 0.5, 1, 1}, {0, 0, 1, 1}};
    for (int i = 0; i < 6; ++i)
      plates.push_back(gen::box({fp[i][0], fp[i][1], i * 0.125}, {fp[i][2], fp[i][3], (i + 1) * 0.125},
                                "armour" + std::to_string(i)));
    const BBoxd b = bounds_of(plates);
    std::vector<Vec3d> t = targets_of(plates);
    for (int i = 0; i <= 6; ++i) t = concat(t, grid_points(0, 1, 0, 1, i * 0.125, 0.125));
    out.push_back(make_case("touching plates", "armour", plates, rays_through_targets(t, b, o.rays_per_case, o.seed + 202)));
  }
  return out;
}

std::vector<Case> t_junctions(const Options& o) {
  std::vector<Case> out;
  {
    // Touching solids whose shared faces are meshed differently: A's +x face meets B1's and
    // B2's -x faces, with B1/B2's shared edge running across A's face.
    const std::vector<Mesh> m = {gen::box({0, 0, 0}, {1, 1, 1}, "A"), gen::box({1, 0, 0}, {2, 1, 0.5}, "B1"),
                                 gen::box({1, 0, 0.5}, {2, 1, 1}, "B2"), gen::box({1, 0.5, 1}, {1.5, 1, 1.5}, "C")};
    std::vector<Vec3d> t = targets_of(m);
    t.push_back({1, 0.5, 0.5});
    t.push_back({1, 0.25, 0.5});
    t.push_back({1.25, 0.5, 1});
    out.push_back(make_case("T-junctions", "touching boxes", m, rays_through_targets(t, bounds_of(m), o.rays_per_case, o.seed + 301)));
  }
  {
    // One closed box whose top face is split into four quads while the sides are not: the
    // top's edge midpoints are T-junctions on the box's edges.
    Mesh box = gen::box({0, 0, 0}, {1, 1, 1});
    std::vector<Tri> tris = triangles_below_top(box);
    auto vid = [&](Vec3d p) {
      for (std::uint32_t i = 0; i < box.vertices.size(); ++i)
        if (box.vertices[i] == p) return i;
      box.vertices.push_back(p);
      return std::uint32_t(box.vertices.size() - 1);
    };
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double x0 = i * 0.5, y0 = j * 0.5;
        const std::uint32_t a = vid({x0, y0, 1}), b = vid({x0 + 0.5, y0, 1}), c = vid({x0 + 0.5, y0 + 0.5, 1}),
                            d = vid({x0, y0 + 0.5, 1});
        if ((i + j) % 2) {
          tris.push_back({a, b, c}), tris.push_back({a, c, d});
        } else {
          tris.push_back({a, b, d}), tris.push_back({b, c, d});
        }
      }
    box.triangles = tris;
    const std::vector<Mesh> m = {box};
    out.push_back(make_case("T-junctions", "split top face", m,
                            rays_through_targets(targets_of(m), bounds_of(m), o.rays_per_case, o.seed + 302)));
  }
  return out;
}

std::vector<Case> closed_edges_vertices(const Options& o) {
  std::vector<Case> out;
  const std::vector<std::pair<std::string, std::vector<Mesh>>> scenes = {
      {"cube grid 3^3", gen::cube_grid(3)},
      {"voxel block 4", {gen::voxel_block(4)}},
      {"fan valence 64", {bipyramid(16, 1.0)}},
      {"octahedra", {octahedron({0, 0, 0}, 1), octahedron({1, 0, 0}, 1), octahedron({0.5, 0.5, 0.5}, 0.5)}},
  };
  int k = 0;
  for (const auto& [name, meshes] : scenes) {
    std::vector<Vec3d> t = targets_of(meshes);
    if (name.rfind("fan", 0) == 0)  // the apexes, many times: every ray through a fan vertex
      for (int i = 0; i < 16; ++i) t.push_back({0, 0, (i % 2) ? 1.0 : -1.0});
    out.push_back(make_case("closed meshes: edges and vertices", name, meshes,
                            rays_through_targets(t, bounds_of(meshes), 2 * o.rays_per_case, o.seed + 401 + k++)));
  }
  return out;
}

std::vector<Case> grazing(const Options& o) {
  // Rays lying in the plane of faces: along a face, along an edge line, along a diagonal.
  std::vector<Case> out;
  const std::vector<Mesh> m = {gen::box({0, 0, 0}, {1, 1, 1}), octahedron({2.5, 0.5, 0.5}, 0.5)};
  const BBoxd b = bounds_of(m);
  std::uint64_t s = o.seed * 31 + 5;
  std::vector<Ray> rays;
  const double marks[] = {0, 0.25, 0.5, 1};
  for (int i = 0; i < o.rays_per_case; ++i) {
    const int axis = pick(s, 3);       // the face plane is x_axis = level
    const double level = pick(s, 2);   // 0 or 1
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Vec3d p;
    p[axis] = level;
    p[u] = marks[pick(s, 4)];
    p[v] = marks[pick(s, 4)];
    Vec3d d;  // in the plane: no component along `axis`
    const int major = pick(s, 2) ? u : v, minor = major == u ? v : u;
    d[major] = pick(s, 2) ? 1 : -1;
    d[minor] = 0.25 * (pick(s, 9) - 4);
    rays.push_back(ray_through(p, d, b));
  }
  // Octahedron faces: planes +-x +-y +-z = r around its center; in-plane dyadic directions.
  const Vec3d c{2.5, 0.5, 0.5};
  const Vec3d in_plane[] = {{1, -1, 0}, {1, 0, -1}, {0, 1, -1}, {1, -0.5, -0.5}, {-0.5, 1, -0.5}};
  for (int i = 0; i < o.rays_per_case / 2; ++i) {
    Vec3d sg{pick(s, 2) ? 1.0 : -1.0, pick(s, 2) ? 1.0 : -1.0, pick(s, 2) ? 1.0 : -1.0};
    Vec3d d = in_plane[pick(s, 5)];
    d = {d.x * sg.x, d.y * sg.y, d.z * sg.z};  // in the plane sg . (x - c) = 0.5
    const Vec3d pts[] = {{0.25, 0.25, 0}, {0.5, 0, 0}, {0.125, 0.125, 0.25}, {0, 0, 0.5}};
    Vec3d q = pts[pick(s, 4)];
    q = Vec3d{q.x * sg.x, q.y * sg.y, q.z * sg.z} + c;
    rays.push_back(ray_through(q, d, b));
  }
  out.push_back(make_case("grazing: ray in a face's plane", "box + octahedron", m, rays));
  return out;
}

std::vector<Case> near_coplanar(const Options& o) {
  // Plates whose faces are one ulp apart. Origins stay close to the faces (within a factor of
  // two of their coordinate) so the kernels' differences are exact and the two faces get
  // distinct t.
  std::vector<Case> out;
  for (const bool use_double : {false, true}) {
    for (const double h : {0.5, 96.0}) {
      const double up = use_double ? std::nextafter(h, 2 * h) : double(std::nextafter(float(h), float(2 * h)));
      const double dn = use_double ? std::nextafter(h, 0.0) : double(std::nextafter(float(h), 0.f));
      const std::vector<Mesh> m = {gen::box({0, 0, h / 2}, {1, 1, h}, "below"),
                                   gen::box({0, 0, up}, {1, 1, 1.5 * h}, "above"),
                                   quad(0.25, 0.25, 0.75, 0.75, dn, true, "under"),
                                   quad(0, 0.5, 1, 1, h, false, "on")};
      std::uint64_t s = o.seed * 131 + std::uint64_t(h) + (use_double ? 17 : 0);
      std::vector<Ray> rays;
      std::vector<Vec3d> t = concat(targets_of({quad(0, 0, 1, 1, h, false)}), grid_points(0, 1, 0, 1, h, 0.125));
      std::erase_if(t, [](const Vec3d& p) { return !is_float(p); });
      for (int i = 0; i < o.rays_per_case; ++i) {
        Vec3d p = t[std::size_t(pick(s, int(t.size())))];
        const int sign = pick(s, 2) ? 1 : -1;
        Vec3d d{0, 0, double(sign)};
        if (pick(s, 2)) {
          // Tilted rays only through points off every edge: the shear mixes the one-ulp offset
          // into x and y, which float cannot hold exactly next to an edge.
          d = dyadic_direction(s, 2, sign);
          p = {(1 + 2 * pick(s, 8)) / 16.0, (1 + 2 * pick(s, 8)) / 16.0, h};
        }
        Ray r;
        r.org = p - d * std::min(h / 4, 0.25);  // close: the kernels' differences stay exact
        r.dir = d;
        rays.push_back(r);
      }
      char name[64];
      std::snprintf(name, sizeof name, "%s, h=%g", use_double ? "1 double ulp" : "1 float ulp", h);
      out.push_back(make_case(use_double ? "nearly coplanar, 1 ulp (double input)" : "nearly coplanar, 1 ulp",
                              name, m, rays, !use_double));
    }
  }
  return out;
}

std::vector<Case> slivers(const Options& o) {
  std::vector<Case> out;
  const double ulp = std::ldexp(1.0, -24);  // one float ulp at 0.5..1
  Mesh box = gen::box({0, 0, 0}, {1, 1, 1});
  // Replace the top face by a fan around f = (0.5, ulp, 1), next to e = (0.5, 0, 1) on the
  // edge: (a, e, f) and (e, b, f) are slivers of width one ulp.
  std::vector<Tri> tris = triangles_below_top(box);
  const std::uint32_t a = 4, b = 5, c = 7, d = 6;  // gen::box's top corners (0,0) (1,0) (1,1) (0,1)
  box.vertices.push_back({0.5, 0, 1});
  box.vertices.push_back({0.5, ulp, 1});
  const std::uint32_t e = 8, f = 9;
  for (const Tri& t : std::vector<Tri>{{a, e, f}, {e, b, f}, {b, c, f}, {c, d, f}, {d, a, f}}) tris.push_back(t);
  // Zero-area triangles: collinear corners on an edge, a repeated corner, a single point.
  for (const Tri& t : std::vector<Tri>{{a, e, b}, {a, a, c}, {e, e, e}, {b, e, a}}) tris.push_back(t);
  box.triangles = tris;
  // Needles: a fan around (0.5, 0.5, 0) on the bottom... with one neighbour 1 ulp away.
  Mesh needles;
  needles.name = "needles";
  needles.vertices = {{2, 0, 0}, {3, 0, 0}, {3, ulp, 0}, {2, 1, 0}, {3, 1, 0}, {2.5, 0.5, 0}, {2.5, 0.5 + ulp, 0}};
  needles.triangles = {{0, 1, 5}, {1, 2, 5}, {2, 4, 6}, {2, 6, 5}, {4, 3, 6}, {3, 0, 5}, {3, 5, 6},
                       {5, 6, 5}, {0, 5, 4}};
  // Zero-area triangle in a tilted plane (3D collinear).
  Mesh line;
  line.name = "collinear";
  line.vertices = {{0, 2, 0}, {0.25, 2.25, 0.25}, {0.75, 2.75, 0.75}};
  line.triangles = {{0, 1, 2}};
  const std::vector<Mesh> m = {box, needles, line};
  std::vector<Vec3d> t = targets_of(m);
  for (const Vec3d& p : {Vec3d{0.5, 0, 1}, Vec3d{0.5, ulp, 1}, Vec3d{0.25, 0, 1}, Vec3d{0.5, ulp / 2, 1},
                         Vec3d{2.5, 0.5, 0}, Vec3d{3, ulp / 2, 0}, Vec3d{0.5, 2.5, 0.5}})
    for (int i = 0; i < 6; ++i) t.push_back(p);
  // Origins one unit from the target: far origins would round the one-ulp offsets away in the
  // kernels' differences.
  std::erase_if(t, [](const Vec3d& p) { return !is_float(p); });
  std::uint64_t s = o.seed * 577 + 501;
  std::vector<Ray> rays;
  for (int i = 0; i < 2 * o.rays_per_case; ++i) {
    const Vec3d p = t[std::size_t(pick(s, int(t.size())))];
    const int axis = pick(s, 3), sign = pick(s, 2) ? 1 : -1;
    // Axis-aligned only: a tilted ray mixes the one-ulp offsets with unit coordinates in the
    // kernels' shear, which float cannot hold exactly (outside the exact class).
    Vec3d d;
    d[axis] = sign;
    Ray r;
    r.org = p - d;
    r.dir = d;
    rays.push_back(r);
  }
  out.push_back(make_case("slivers and zero-area triangles", "box fan + needles", m, rays));
  return out;
}

std::vector<Case> scaled_translated(const Options& o) {
  std::vector<Case> out;
  std::vector<Mesh> base = gen::cube_grid(2);
  for (const Mesh& p : gen::stacked_plates(3, 2.0, 0.5)) base.push_back(gen::translated(p, {0, 0, 3}));
  struct Variant {
    double scale;
    Vec3d offset;
    bool round_to_float;  // store the input as float (what a float file holds)
    bool tilted;          // dyadic tilted rays (exact only for power-of-two scales)
  };
  const Variant variants[] = {
      {1e-6, {0, 0, 0}, true, false},        {1e-3, {0, 0, 0}, true, false},
      {1e3, {0, 0, 0}, true, false},         {1e6, {0, 0, 0}, true, false},
      {std::ldexp(1.0, -20), {0, 0, 0}, true, true}, {std::ldexp(1.0, 20), {0, 0, 0}, true, true},
      {1, {1e3, -1e3, 1e3}, true, true},     {1, {1e6, -1e6, 1e6}, true, true},
      {1e3, {1e6, 1e6, -1e6}, true, false},
      // Not representable in float: features of 1e-3 and 1e-6 at an offset of 1e6.
      {1e-3, {1e6, -1e6, 1e6}, false, false}, {1e-6, {1e6, 1e6, 1e6}, false, false},
  };
  int k = 0;
  for (const Variant& v : variants) {
    std::vector<Mesh> m;
    for (const Mesh& b : base) {
      Mesh x = gen::translated(gen::scaled(b, v.scale), v.offset);
      m.push_back(v.round_to_float ? rounded_to_float(x) : x);
    }
    char name[96];
    std::snprintf(name, sizeof name, "scale %g, offset %g", v.scale, v.offset.x);
    const bool fe = v.round_to_float;
    // Decimal scales: rays through vertices only; an edge midpoint's offsets to the other
    // corners are not exact in float.
    std::vector<Vec3d> targets;
    if (v.tilted) {
      targets = targets_of(m);
    } else {
      for (const Mesh& x : m) targets.insert(targets.end(), x.vertices.begin(), x.vertices.end());
    }
    std::vector<Ray> rays =
        rays_through_targets(targets, bounds_of(m), o.rays_per_case, o.seed + 601 + k++, v.tilted, fe);
    out.push_back(make_case(fe ? "scaled 1e-6..1e6, offsets to 1e6" : "1e-6/1e-3 features at offset 1e6 (double input)",
                            name, m, rays, fe));
  }
  return out;
}

std::vector<Case> deep_stack(const Options& o) {
  std::vector<Case> out;
  Mesh m;
  m.name = "layers";
  const int n = o.deep_layers;
  const double dz = std::ldexp(1.0, -10);
  for (int i = 0; i < n; ++i) {
    const Mesh q = quad(0, 0, 1, 1, i * dz, i % 2 == 1);
    const auto base = std::uint32_t(m.vertices.size());
    for (const Vec3d& v : q.vertices) m.vertices.push_back(v);
    for (Tri t : q.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  std::uint64_t s = o.seed * 977 + 9;
  std::vector<Ray> rays;
  const Vec3d targets[] = {{0.5, 0.5, 0}, {0.25, 0.25, 0}, {0, 0, 0}, {1, 1, 0}, {0.5, 0, 0}, {0.375, 0.625, 0}};
  for (int i = 0; i < o.deep_rays; ++i) {
    const Vec3d p = targets[std::size_t(pick(s, 6))];
    const int sign = i % 2 ? 1 : -1;
    Vec3d d{0, 0, double(sign)};
    if (i % 4 >= 2) d = {(pick(s, 5) - 2) / 64.0, (pick(s, 5) - 2) / 64.0, double(sign)};
    // Through p at the stack's middle height, from outside the stack.
    const double mid = std::floor(n / 2.0) * dz;
    Ray r;
    r.org = Vec3d{p.x, p.y, mid} - d * (mid + 1.0);
    r.dir = d;
    rays.push_back(r);
  }
  out.push_back(make_case("depth complexity " + std::to_string(n), std::to_string(n) + " quads", {m}, rays));
  return out;
}

std::vector<Case> segment_ends(const Options& o) {
  // Rays that start exactly on a face (thickness rays, tmin = 0) and end exactly on one
  // (tmax = the face's t), plus ends one ulp short of a face.
  std::vector<Case> out;
  const std::vector<Mesh> m = gen::stacked_plates(4, 1.0, 0.25);
  std::uint64_t s = o.seed * 4421 + 1;
  std::vector<Ray> rays;
  for (int i = 0; i < 2 * o.rays_per_case; ++i) {
    const int start = pick(s, 5), sign = start == 0 ? 1 : (start == 4 ? -1 : (pick(s, 2) ? 1 : -1));
    const Vec3d p{pick(s, 9) / 8.0, pick(s, 9) / 8.0, start * 0.25};
    Vec3d d = pick(s, 2) ? Vec3d{0, 0, double(sign)} : dyadic_direction(s, 2, sign);
    Ray r;
    r.org = p;
    r.dir = d;
    r.tmin = 0;
    const int mode = pick(s, 4);
    const int reach = sign > 0 ? 4 - start : start;  // faces ahead
    const int j = reach > 0 ? 1 + pick(s, reach) : 0;
    const double tj = j * 0.25;  // exact: |d_z| = 1
    if (mode == 0) r.tmax = tj;                                          // ends on a face
    if (mode == 1) r.tmax = double(std::nextafter(float(tj), 0.f));       // ends one ulp short
    if (mode == 2) r.tmin = r.tmax = tj;                                  // a point segment on a face
    if (mode == 3) r.tmin = tj;                                           // starts at a later face
    rays.push_back(r);
  }
  out.push_back(make_case("segments starting/ending on a surface", "4 plates", m, rays));
  return out;
}

std::vector<Case> double_rounding(const Options& o) {
  // For the double kernels: triangles whose edge passes within one rounding of the ray, so that
  // the double products in the edge function round to a false zero or the wrong sign. The ray is
  // the z axis; triangle i lies at z = i. Input in double (not representable in float).
  std::vector<Case> out;
  std::uint64_t s = o.seed * 2654435761u + 77;
  auto unit = [&] { return double(splitmix(s) >> 11) * 0x1p-53; };  // [0, 1) with 53 random bits
  std::vector<Mesh> meshes;
  for (int i = 0; int(meshes.size()) < 4 * o.rays_per_case && i < 100000; ++i) {
    // Edge b-c through (almost) the origin: c is -lambda * b rounded to double.
    const Vec3d b{0.5 + unit(), -(0.5 + unit()), 0};
    const double lambda = 0.5 + unit();
    const Vec3d c{-lambda * b.x, -lambda * b.y, 0};
    const double p = c.x * b.y, q = c.y * b.x;
    // Keep edges where the rounded edge function is zero or tiny (the exact one is not
    // computed here: the oracle decides).
    if (std::abs(p - q) > 0x1p-50 * (std::abs(p) + std::abs(q))) continue;
    // The third corner on either side of the edge, far from it.
    const Vec3d nrm{-(c.y - b.y), c.x - b.x, 0};
    const double side = (meshes.size() % 2) ? 1.0 : -1.0;
    Mesh m;
    m.name = "edge" + std::to_string(meshes.size());
    const double z = double(meshes.size());
    m.vertices = {Vec3d{b.x, b.y, z}, Vec3d{c.x, c.y, z}, (b + c) * 0.5 + nrm * side + Vec3d{0, 0, z}};
    // Every third one a sliver through the ray: corner on the axis, the other two almost
    // collinear with it (its area may round to zero in double, but it is not zero).
    if (meshes.size() % 3 == 2) m.vertices[2] = Vec3d{0, 0, z};
    m.triangles = {{0, 1, 2}};
    meshes.push_back(m);
  }
  std::vector<Ray> rays;
  for (const double x : {0.0, -0.0}) {  // the same axis ray, both ways, and from either end
    rays.push_back({{x, 0, -1}, {0, 0, 1}, 0, std::numeric_limits<double>::infinity()});
    rays.push_back({{x, 0, double(meshes.size())}, {0, 0, -1}, 0, std::numeric_limits<double>::infinity()});
  }
  out.push_back(make_case("edges within one double rounding (double input)", std::to_string(meshes.size()) + " triangles",
                          meshes, rays, false));
  return out;
}

std::vector<Case> invalid_rays(const Options&) {
  std::vector<Case> out;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<Ray> rays = {
      {{0.5, 0.5, -1}, {0, 0, 0}, 0, inf},       {{nan, 0.5, -1}, {0, 0, 1}, 0, inf},
      {{0.5, 0.5, -1}, {0, nan, 1}, 0, inf},     {{0.5, 0.5, -inf}, {0, 0, 1}, 0, inf},
      {{0.5, 0.5, -1}, {0, 0, inf}, 0, inf},     {{0.5, 0.5, -1}, {0, 0, 1}, nan, inf},
      {{0.5, 0.5, -1}, {0, 0, 1}, 0, nan},       {{0.5, 0.5, -1}, {0, 0, 1}, 3, 2},
      {{0.5, 0.5, -1}, {0, 0, 1}, inf, inf},     {{0.5, 0.5, -1}, {0, 0, 1}, -inf, -inf},
      {{0.5, 0.5, -1}, {0, 0, 1e-45}, 0, inf},   {{0.5, 0.5, -1}, {0, 0, 1e300}, 0, inf},
      {{0.5, 0.5, 1e300}, {0, 0, 1}, 0, inf},   {{0.5, 0.5, -1}, {0, 0, 1}, -inf, inf},
  };
  out.push_back(make_case("invalid rays, empty scene", "box", {gen::box({0, 0, 0}, {1, 1, 1})}, rays));
  out.push_back(make_case("invalid rays, empty scene", "empty scene", {}, rays));
  return out;
}

Case random_dyadic(std::uint64_t seed, int objects, int ray_count) {
  std::uint64_t s = seed * 0x9E3779B97F4A7C15ull + 1;
  auto grid = [&](int n) { return pick(s, n + 1) / 16.0; };  // 0 .. n/16
  std::vector<Mesh> meshes;
  for (int i = 0; i < objects; ++i) {
    const int kind = pick(s, 6);
    if (kind <= 1) {  // closed box, possibly touching or overlapping others
      Vec3d lo{grid(48), grid(48), grid(48)}, hi = lo;
      for (int k = 0; k < 3; ++k) hi[k] += (1 + pick(s, 16)) / 16.0;
      meshes.push_back(gen::box(lo, hi, "box" + std::to_string(i)));
      if (kind == 1 && pick(s, 2)) meshes.push_back(gen::duplicated(meshes.back(), 2, pick(s, 2)));
    } else if (kind == 2) {  // a stack of touching plates
      const double x0 = grid(32), y0 = grid(32), z0 = grid(32), t = (1 + pick(s, 4)) / 16.0;
      for (const Mesh& p : gen::stacked_plates(2 + pick(s, 3), 0.5, t))
        meshes.push_back(gen::translated(p, {x0, y0, z0}));
    } else if (kind == 3) {  // a closed octahedron (tilted faces)
      meshes.push_back(octahedron({grid(48) + 0.5, grid(48) + 0.5, grid(48) + 0.5}, (1 + pick(s, 8)) / 16.0));
    } else {  // loose triangles, often in an axis plane, sometimes degenerate
      Mesh m;
      m.name = "tris" + std::to_string(i);
      const int axis = pick(s, 3);
      const double level = grid(64);
      for (int t = 0; t < 6; ++t) {
        for (int k = 0; k < 3; ++k) {
          Vec3d p{grid(64), grid(64), grid(64)};
          if (kind == 4) p[axis] = level;
          m.vertices.push_back(p);
        }
        if (pick(s, 8) == 0) m.vertices.back() = m.vertices[m.vertices.size() - 2];  // zero area
        const auto b = std::uint32_t(m.vertices.size() - 3);
        m.triangles.push_back({b, b + 1, b + 2});
      }
      meshes.push_back(m);
    }
  }
  const BBoxd b = bounds_of(meshes);
  std::vector<Vec3d> targets = targets_of(meshes);
  std::erase_if(targets, [](const Vec3d& p) { return !is_float(p); });
  for (int i = 0; i < 64; ++i) targets.push_back({grid(64), grid(64), grid(64)});
  std::vector<Ray> rays = rays_through_targets(targets, b, ray_count, seed * 31 + 7, true, true);
  // Some segments start or end exactly on a face crossing (an axis-plane triangle's level).
  for (Ray& r : rays) {
    const int mode = pick(s, 4);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(r.dir[k]) > std::abs(r.dir[axis])) axis = k;
    const double level = grid(64);  // t where the ray crosses the plane x_axis = level: exact
    const double t = (level - r.org[axis]) / r.dir[axis];
    if (t < 0 || !is_float(t)) continue;
    if (mode == 1) r.tmax = t;
    if (mode == 2) r.tmin = t;
  }
  Case c = make_case("random dyadic", "seed " + std::to_string(seed), meshes, rays);
  return c;
}

std::vector<Case> corpus(const Options& o) {
  std::vector<Case> all;
  auto add = [&](std::vector<Case> v) {
    for (Case& c : v) all.push_back(std::move(c));
  };
  for (auto family : {coplanar_duplicates, coplanar_overlaps, touching_plates, t_junctions, closed_edges_vertices,
                      grazing, near_coplanar, slivers, scaled_translated, double_rounding, segment_ends, invalid_rays,
                      deep_stack})
    add(family(o));
  return all;
}

}  // namespace pierce::hard
