#include "pierce/origin_offsets.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstring>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "pierce/exact_predicates.h"
#include "pierce/proximity.h"

namespace pierce {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The float-rounded corners the float BVH holds, exactly, in double.
struct Corners {
  Vec3d v[3];
};

Corners corners_of(const Geometry& geo, std::uint32_t prim) {
  const Tri& t = geo.triangles[prim];
  Corners c;
  for (int i = 0; i < 3; ++i) c.v[i] = Vec3d(Vec3f(geo.vertices[t[i]]));
  return c;
}

// Side function s(x) = sigma * (n.x - w) with unit n: signed distance to the triangle's plane.
struct SidePlane {
  Vec3d n;
  double w = 0;
  double eval(const Vec3d& x) const { return dot(n, x) - w; }
};

// Unit normal of (v1-v0)x(v2-v0) in double; zero for a degenerate triangle.
Vec3d unit_normal(const Corners& c) {
  const Vec3d n = cross(c.v[1] - c.v[0], c.v[2] - c.v[0]);
  const double len = length(n);
  return len > 0 && std::isfinite(len) ? n * (1.0 / len) : Vec3d{};
}

double segment_dist2(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a, ap = p - a;
  const double l2 = dot(ab, ab);
  double t = l2 > 0 ? dot(ap, ab) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Vec3d d = ap - ab * t;
  return dot(d, d);
}

// Squared distance from p to triangle (a, b, c); robust for degenerate triangles (edges only).
double triangle_dist2(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double edges = std::min({segment_dist2(p, a, b), segment_dist2(p, b, c), segment_dist2(p, c, a)});
  const Vec3d n = cross(b - a, c - a);
  const double n2 = dot(n, n);
  if (!(n2 > 0)) return edges;
  const bool inside = dot(cross(b - a, p - a), n) >= 0 && dot(cross(c - b, p - b), n) >= 0 &&
                      dot(cross(a - c, p - c), n) >= 0;
  if (!inside) return edges;
  const double h = dot(n, p - a);
  return std::min(edges, h * h / n2);
}

// Squared distance from p to the part of triangle (a, b, c) where s >= -slab (s given per corner).
double clipped_dist2(const Vec3d& p, const Vec3d (&v)[3], const double (&s)[3], double slab) {
  Vec3d poly[4];
  int m = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const bool in_i = s[i] >= -slab, in_j = s[j] >= -slab;
    if (in_i) poly[m++] = v[i];
    if (in_i != in_j) {
      const double f = (s[i] + slab) / (s[i] - s[j]);
      poly[m++] = v[i] + (v[j] - v[i]) * std::clamp(f, 0.0, 1.0);
    }
  }
  if (m == 0) return kInf;
  if (m == 1) return dot(p - poly[0], p - poly[0]);
  if (m == 2) return segment_dist2(p, poly[0], poly[1]);
  double best = triangle_dist2(p, poly[0], poly[1], poly[2]);
  if (m == 4) best = std::min(best, triangle_dist2(p, poly[0], poly[2], poly[3]));
  return best;
}

// Nearest distance from x to the BVH's triangles inside {s >= -slab}, skipping those `skip`
// accepts. On the one traversal (proximity.h): depth first, nearer child first, pruned by box
// distance and by the half-space.
template <typename Skip>
double nearest_in_halfspace(const WideBvhf& bvh, const Vec3d& x, const SidePlane& pl, double slab, double max_dist,
                            NodeStack<float>& stack, Skip&& skip) {
  struct Nearest : ProximityPolicy<float> {
    const Vec3d& x;
    const SidePlane& pl;
    double slab;
    Skip& skip;
    double best2;
    Nearest(const Vec3d& from, const SidePlane& plane, double s, Skip& sk, double b)
        : x(from), pl(plane), slab(s), skip(sk), best2(b) {}
    // Keys are float: rounding to nearest is monotone, so no box nearer than best2 is skipped
    // (proximity.h); a box at best2 is entered too. Once a triangle touches x (best2 = 0, as for a
    // hemisphere at a vertex the neighbours share) nothing can come nearer: no box is entered.
    float hi() const { return best2 > 0 ? float(best2) : -1.0f; }
    float cull_bound() const { return hi(); }
    void leaf(const TriBlock<float>& b) {
      double box2[kBlockLanes];
      lane_box_distances2(b, x, box2);
      for (std::uint32_t m = b.valid; m != 0; m &= m - 1) {
        const int l = __builtin_ctz(m);
        if (box2[l] > beyond_bound(best2)) continue;
        const Triangle<float> t = b.triangle(l);
        if (skip(t.geom, t.prim)) continue;
        const Vec3d v[3] = {Vec3d(t.v0), Vec3d(t.v1), Vec3d(t.v2)};
        const double s[3] = {pl.eval(v[0]), pl.eval(v[1]), pl.eval(v[2])};
        if (s[0] < -slab && s[1] < -slab && s[2] < -slab) continue;
        best2 = std::min(best2, clipped_dist2(x, v, s, slab));
      }
    }
  } p{x, pl, slab, skip, max_dist * max_dist};
  auto entered = [&](const WideNode<float>& n, float* key) {
    double d2[kWideArity], top[kWideArity];
    box_distances2(n, x, d2);
    // Max of s over each box: at its corner farthest along the plane's normal.
    for (int s = 0; s < kWideArity; ++s) {
      const auto far = [&](int a) { return pl.n[a] > 0 ? double(n.hi[a][s]) : double(n.lo[a][s]); };
      top[s] = pl.eval(Vec3d{far(0), far(1), far(2)});
    }
    std::uint32_t above = 0;
    for (int s = 0; s < kWideArity; ++s) {
      key[s] = float(d2[s]);
      above |= std::uint32_t(top[s] >= -slab) << s;
    }
    return above;
  };
  traverse_proximity(bvh, stack, entered, p);
  return std::sqrt(p.best2);
}

std::uint64_t splitmix(std::uint64_t& s) {
  std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Hemisphere centres of one triangle for a set (the polygon set's first one is the centroid).
int centres(HemisphereSet kind, const Corners& c, std::uint32_t geom, std::uint32_t prim, std::uint64_t seed,
            Vec3d* out) {
  const Vec3d g = (c.v[0] + c.v[1] + c.v[2]) * (1.0 / 3.0);
  switch (kind) {
    case HemisphereSet::center:
    case HemisphereSet::polygon: out[0] = g; return 1;
    case HemisphereSet::vertex:
      for (int i = 0; i < 3; ++i) out[i] = c.v[i];
      return 3;
    case HemisphereSet::median:
    case HemisphereSet::median_center:
      for (int i = 0; i < 3; ++i) out[i] = (c.v[i] + g) * 0.5;
      if (kind == HemisphereSet::median) return 3;
      out[3] = g;
      return 4;
    case HemisphereSet::random: {
      std::uint64_t s = seed ^ (std::uint64_t(geom) << 32 | prim);
      for (int k = 0; k < 4; ++k) {
        double u = double(splitmix(s) >> 11) * 0x1p-53, v = double(splitmix(s) >> 11) * 0x1p-53;
        if (u + v > 1) u = 1 - u, v = 1 - v;
        out[k] = c.v[0] + (c.v[1] - c.v[0]) * u + (c.v[2] - c.v[0]) * v;
      }
      return 4;
    }
  }
  return 0;
}

// For coplanar, non-degenerate triangles a and b sharing the edge `key`: whether their third
// corners lie strictly on opposite sides of it (exact, in the projection along the normal's
// largest axis, which keeps orientations of points in the plane).
bool opposite_sides(const std::array<float, 6>& key, const Corners& a, const Corners& b) {
  const Vec3d e0{key[0], key[1], key[2]}, e1{key[3], key[4], key[5]};
  const Vec3d n = cross(a.v[1] - a.v[0], a.v[2] - a.v[0]);
  const int drop = std::abs(n.x) > std::abs(n.y) ? (std::abs(n.x) > std::abs(n.z) ? 0 : 2)
                                                 : (std::abs(n.y) > std::abs(n.z) ? 1 : 2);
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  auto side = [&](const Corners& c) {
    int s = 0;
    for (const Vec3d& p : c.v) {
      const int o = orient2d({e0[i], e0[j]}, {e1[i], e1[j]}, {p[i], p[j]});
      if (o != 0) s = o;
    }
    return s;
  };
  const int sa = side(a), sb = side(b);
  return sa != 0 && sb != 0 && sa != sb;
}

// Edge-connected, exactly coplanar patches of non-degenerate triangles, per geometry.
std::vector<std::uint32_t> coplanar_patches(const Scene& scene, const std::vector<std::size_t>& first) {
  const std::size_t total = first.back();
  std::vector<std::uint32_t> parent(total);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<std::uint32_t> patch(total);
  std::vector<std::uint8_t> dissolved(total, 0);
  auto find = [&](std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  struct KeyHash {
    std::size_t operator()(const std::array<float, 6>& k) const {
      std::size_t h = 1469598103934665603ull;
      for (float f : k) {
        std::uint32_t b;
        std::memcpy(&b, &f, 4);
        h = (h ^ b) * 1099511628211ull;
      }
      return h;
    }
  };
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    std::unordered_map<std::array<float, 6>, std::vector<std::uint32_t>, KeyHash> edges;
    for (std::uint32_t t = 0; t < geo.triangles.size(); ++t) {
      if (geo.degenerate[t]) continue;
      const Corners c = corners_of(geo, t);
      for (int i = 0; i < 3; ++i) {
        Vec3f a(c.v[i]), b(c.v[(i + 1) % 3]);
        if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
        edges[{a.x, a.y, a.z, b.x, b.y, b.z}].push_back(t);
      }
    }
    for (auto& [key, tris] : edges) {
      for (std::size_t i = 0; i < tris.size(); ++i)
        for (std::size_t j = i + 1; j < tris.size(); ++j) {
          const Corners a = corners_of(geo, tris[i]), b = corners_of(geo, tris[j]);
          bool coplanar = true;
          for (int k = 0; k < 3 && coplanar; ++k)
            coplanar = orient3d(a.v[0], a.v[1], a.v[2], b.v[k]) == 0;
          // Only neighbours on the two sides of the shared edge: a duplicated or folded-over face
          // stays its own patch and so still limits the patch's radius (to 0).
          if (coplanar && opposite_sides(key, a, b))
            parent[find(std::uint32_t(first[g] + tris[i]))] = find(std::uint32_t(first[g] + tris[j]));
        }
    }
    // A patch reached through a chain that folds back onto itself (a duplicated face is on the
    // same side of some edge as a patch member) is dissolved into single triangles.
    for (auto& [key, tris] : edges)
      for (std::size_t i = 0; i < tris.size(); ++i)
        for (std::size_t j = i + 1; j < tris.size(); ++j) {
          const std::uint32_t ri = find(std::uint32_t(first[g] + tris[i]));
          if (ri != find(std::uint32_t(first[g] + tris[j]))) continue;
          if (tris.size() > 2 || !opposite_sides(key, corners_of(geo, tris[i]), corners_of(geo, tris[j])))
            dissolved[ri] = 1;
        }
  }
  for (std::uint32_t i = 0; i < total; ++i) {
    const std::uint32_t r = find(i);
    patch[i] = dissolved[r] ? i : r;
  }
  return patch;
}

}  // namespace

std::string_view hemisphere_set_name(HemisphereSet s) {
  switch (s) {
    case HemisphereSet::center: return "center";
    case HemisphereSet::vertex: return "vertex";
    case HemisphereSet::median: return "median";
    case HemisphereSet::median_center: return "median+center";
    case HemisphereSet::polygon: return "polygon";
    case HemisphereSet::random: return "random";
  }
  return "?";
}

std::optional<HemisphereSet> parse_hemisphere_set(std::string_view name) {
  for (HemisphereSet s : kAllHemisphereSets)
    if (hemisphere_set_name(s) == name) return s;
  return std::nullopt;
}

int hemispheres_per_side(HemisphereSet s) {
  switch (s) {
    case HemisphereSet::center: return 1;
    case HemisphereSet::polygon: return 2;
    case HemisphereSet::vertex:
    case HemisphereSet::median: return 3;
    case HemisphereSet::median_center:
    case HemisphereSet::random: return 4;
  }
  return 1;
}

std::span<const Hemisphere> OriginOffsets::hemispheres(std::uint32_t geom, std::uint32_t prim, int side) const {
  if (geom + 1 >= first_.size() || prim >= first_[geom + 1] - first_[geom] || spheres_.empty()) return {};
  return {spheres_.data() + slot(first_[geom] + prim, side, 0), std::size_t(per_side_)};
}

std::uint32_t OriginOffsets::surface_id(std::uint32_t geom, std::uint32_t prim) const {
  if (geom + 1 >= first_.size() || prim >= first_[geom + 1] - first_[geom]) return kInvalidId;
  const std::size_t i = first_[geom] + prim;
  return patch_.empty() ? std::uint32_t(i) : patch_[i];
}

OriginOffsets build_origin_offsets(const Scene& scene, const WideBvhf& bvh, HemisphereSet kind,
                                   const OriginOffsetOptions& opts) {
  OriginOffsets oo;
  oo.scene_ = &scene;
  oo.kind_ = kind;
  oo.per_side_ = hemispheres_per_side(kind);
  oo.first_.push_back(0);
  BBoxd fbox;  // bounds of the float-rounded vertices
  for (const Geometry& geo : scene.geometries()) {
    oo.first_.push_back(oo.first_.back() + geo.triangles.size());
    for (const Vec3d& v : geo.vertices) fbox.extend(Vec3d(Vec3f(v)));
  }
  const std::size_t total = oo.first_.back();
  oo.max_abs_ = fbox.max_abs_coord();
  oo.extent_ = fbox.empty() ? 0.0 : length(fbox.extent());
  oo.slab_ = std::ldexp(oo.max_abs_ + oo.extent_, -18);
  const double build_shrink = std::ldexp(oo.max_abs_ + oo.extent_, -40);
  // Beyond this every point of the scene is inside the ball: no need to look farther.
  const double max_radius = 4 * oo.extent_ + build_shrink;
  oo.spheres_.assign(total * oo.stride(), Hemisphere{});
  if (kind == HemisphereSet::polygon) oo.patch_ = coplanar_patches(scene, oo.first_);

  std::vector<std::pair<std::uint32_t, std::uint32_t>> ids(total);  // global index -> (geom, prim)
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
    for (std::uint32_t p = 0; p < scene.geometry(g).triangles.size(); ++p) ids[oo.first_[g] + p] = {g, p};

  auto to_radius = [&](double d) {
    const double r = std::max(0.0, std::min(d, max_radius) - build_shrink);
    float f = float(r);
    if (double(f) > r) f = std::nextafter(f, 0.0f);
    return f;
  };

  tbb::enumerable_thread_specific<NodeStack<float>> stacks;
  auto build_range = [&](std::size_t b, std::size_t e) {
    NodeStack<float>& stack = stacks.local();
    for (std::size_t i = b; i < e; ++i) {
      const auto [g, p] = ids[i];
      const Geometry& geo = scene.geometry(g);
      if (geo.degenerate[p]) continue;
      const Corners c = corners_of(geo, p);
      const Vec3f nf(unit_normal(c));
      if (nf == Vec3f{}) continue;
      // The plane as stored (float): build and query both use exactly these values.
      const float wf = float(dot(Vec3d(nf), c.v[0]));
      oo.spheres_[i * oo.stride()] = {nf, wf};
      const Vec3d n(nf);
      Vec3d pts[4];
      const int k = centres(kind, c, g, p, opts.seed, pts);
      const std::uint32_t patch = oo.patch_.empty() ? 0 : oo.patch_[i];
      auto skip = [&](std::uint32_t qg, std::uint32_t qp) {
        if (oo.patch_.empty()) return qg == g && qp == p;
        return oo.patch_[oo.first_[qg] + qp] == patch;
      };
      for (int side = 0; side < 2; ++side) {
        const double sigma = side == 0 ? 1.0 : -1.0;
        const SidePlane pl{n * sigma, sigma * double(wf)};
        Hemisphere* out = oo.spheres_.data() + oo.slot(i, side, 0);
        for (int j = 0; j < k; ++j) {
          // The radius is measured from the stored (float) centre.
          const Vec3f cf(pts[j]);
          const double d = nearest_in_halfspace(bvh, Vec3d(cf), pl, oo.slab_, max_radius, stack, skip);
          out[j] = {cf, to_radius(d)};
        }
      }
    }
  };
  if (opts.parallel) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, total, 256),
                      [&](const auto& r) { build_range(r.begin(), r.end()); });
  } else {
    build_range(0, total);
  }

  if (kind == HemisphereSet::polygon) {
    // Second hemisphere of every triangle: the patch's largest centroid hemisphere (Zoet 3.1),
    // valid for the whole patch because every radius was found with the patch left out.
    std::unordered_map<std::uint32_t, std::array<Hemisphere, 2>> largest;
    for (std::size_t i = 0; i < total; ++i)
      for (int side = 0; side < 2; ++side) {
        const Hemisphere& h = oo.spheres_[oo.slot(i, side, 0)];
        Hemisphere& best = largest[oo.patch_[i]][std::size_t(side)];
        if (h.radius > best.radius) best = h;
      }
    for (std::size_t i = 0; i < total; ++i)
      for (int side = 0; side < 2; ++side)
        oo.spheres_[oo.slot(i, side, 1)] = largest[oo.patch_[i]][std::size_t(side)];
  }
  return oo;
}

double safe_offset(const OriginOffsets& oo, std::uint32_t geom, std::uint32_t prim, const Vec3d& o,
                   const Vec3d& d) {
  // Everything the query reads sits in one block per triangle: its plane, then its hemispheres.
  const Hemisphere* plane = oo.plane(geom, prim);
  if (!plane) return 0;
  const Vec3d n(plane->center);  // unit normal (zero for a degenerate triangle)
  const double nd = dot(n, d);
  if (!(nd != 0) || !all_finite(o) || !all_finite(d)) return 0;  // in the plane, or not a ray
  const int side = nd > 0 ? 0 : 1;
  const double mo = max_abs(o), a = dot(d, d);
  const double e16 = oo.extent() * 0x1p-16, s_abs = oo.max_abs() + mo;
  double s_o = std::numeric_limits<double>::quiet_NaN();  // signed distance of o above the plane, on demand
  double best = 0;
  const Hemisphere* first = plane + 1 + side * oo.per_side();
  for (const Hemisphere* h = first; h != first + oo.per_side(); ++h) {
    const double r = h->radius;
    if (!(r > 0)) continue;
    const double mu = e16 + (s_abs + r) * 0x1p-21;
    const double reff = r - 2 * mu;
    if (!(reff > 0)) continue;
    const Vec3d oc = o - Vec3d(h->center);
    const double cc = dot(oc, oc) - reff * reff;
    if (!(cc < 0)) continue;  // origin not inside the shrunk ball
    // The kernel's ray must stay in the widened half-space the radius was measured in.
    if (std::isnan(s_o)) s_o = (nd > 0 ? 1.0 : -1.0) * (dot(n, o) - double(plane->radius));
    if (!(s_o >= -oo.slab() + (s_abs + r) * 0x1p-21)) continue;
    const double b = dot(d, oc);
    const double root = std::sqrt(b * b - a * cc);
    // Positive root of a t^2 + 2 b t + cc, in the form without cancellation.
    const double t = b > 0 ? -cc / (b + root) : (root - b) / a;
    if (std::isfinite(t)) best = std::max(best, t * (1 - 0x1p-30));
  }
  return best;
}

}  // namespace pierce
