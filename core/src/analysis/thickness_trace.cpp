// Thickness, stage 2: every sample measured with its method (ray, cone, sphere); CAD exits
// refined on the exact faces.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "pierce/analysis/bvh_query.h"
#include "pierce/bvh_builder.h"
#include "pierce/parallel_for_items.h"
#include "thickness_internal.h"

namespace pierce::analysis {

namespace {

// Where a ray left its solid, and the first of the solid's triangles it met.
struct ExitRecord {
  std::uint32_t prim = kInvalidId, first_prim = kInvalidId;
  float u = 0, v = 0;
};

// ray_exit_distance, optionally recording the exit crossing (CAD samples).
template <bool Record>
double exit_impl(HitIterator& it, std::uint32_t geom, Vec3d point, Vec3d dir, double max_distance, double tie,
                 double offset, ExitRecord* rec) {
  // Below the offset only the start triangle can be crossed, and its crossing is below `tie`.
  it.begin(Ray{point, dir, std::max(tie, offset), max_distance});
  int depth = 1;
  double group_t = -std::numeric_limits<double>::infinity();
  bool left_in_group = false, enter_pending = false;
  Hit h;
  while (it.next(h)) {
    if (h.geom != geom) continue;
    if constexpr (Record) {
      if (rec->first_prim == kInvalidId) rec->first_prim = h.prim;
    }
    if (h.t - group_t > tie) {
      if (enter_pending) ++depth;
      group_t = h.t;
      left_in_group = enter_pending = false;
    }
    if (h.enter) {
      enter_pending = true;
    } else if (!left_in_group) {
      left_in_group = true;
      if (--depth <= 0) {
        if constexpr (Record) rec->prim = h.prim, rec->u = h.u, rec->v = h.v;
        return h.t;
      }
    }
  }
  return detail::kNaN;
}

// Orthonormal basis (u, v) completing unit vector n.
void basis(Vec3d n, Vec3d& u, Vec3d& v) {
  const Vec3d a = std::abs(n.x) < 0.6 ? Vec3d{1, 0, 0} : (std::abs(n.y) < 0.6 ? Vec3d{0, 1, 0} : Vec3d{0, 0, 1});
  u = cross(n, a);
  u = u * (1.0 / length(u));
  v = cross(n, u);
}

struct ConeDir {
  Vec3d local;  // (x, y, z) with z along the cone's axis
  double angle;
};

// Directions spread evenly in solid angle over the cap (Fibonacci spiral), axis first.
std::vector<ConeDir> cone_directions(int k, double full_angle_deg) {
  std::vector<ConeDir> dirs{{{0, 0, 1}, 0.0}};
  const double half = full_angle_deg * std::numbers::pi / 360.0;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 1; i < k; ++i) {
    const double c = 1.0 - (1.0 - std::cos(half)) * (double(i) - 0.5) / double(k - 1);
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = golden * i;
    dirs.push_back({{s * std::cos(phi), s * std::sin(phi), c}, std::acos(std::clamp(c, -1.0, 1.0))});
  }
  return dirs;
}

// CAD exits where the ray makes less than about 15 degrees with the exit face (|cos| to its
// normal below this) are checked against the whole B-rep for an earlier crossing.
constexpr double kGrazingCos = 0.25;

struct Measured {
  double t = detail::kNaN;
  ThicknessStatus status = ThicknessStatus::ok;
  std::uint32_t exit_triangle = kInvalidId;  // mesh samples: the triangle the ray left through
};

// MeshSide on the scene's mesh, with a worker's traversal state: the triangles near the point are
// found on the float BVH and measured in double precision, each against its own face's band, the
// winding number is counted along the ray by the (exact) thickness kernel.
class SceneMeshSide final : public MeshSide {
 public:
  SceneMeshSide(const Accel& accel, HitIterator& it, NodeStack<float>& stack) : accel_(accel), it_(it), stack_(stack) {}

  Side side(std::uint32_t geom, Vec3d p, Vec3d dir, const MeshBands& bands) const override {
    // The kernel may trace the float copy of the mesh (float_rounding_margin from the double one).
    const double margin = float_rounding_margin(accel_.wide());
    const double reach = bands.largest + margin;  // of every triangle's band: the box holds them all
    BBoxd box;
    box.lo = p - Vec3d{reach, reach, reach};
    box.hi = p + Vec3d{reach, reach, reach};
    bool near = false;
    for_each_overlapping(accel_.scene(), accel_.wide(), box, stack_, [&](const Triangle<double>& t) {
      if (near || t.geom != geom) return;
      const double r = bands.band[bands.face[t.prim]] + margin;
      // A triangle whose box lies farther than r from p on some axis is farther than r.
      for (std::size_t k = 0; k < 3; ++k)
        if (std::min({t.v0[k], t.v1[k], t.v2[k]}) > p[k] + r || std::max({t.v0[k], t.v1[k], t.v2[k]}) < p[k] - r)
          return;
      const Vec3d q = closest_point_on_triangle(p, t.v0, t.v1, t.v2);
      near = !(dot(q - p, q - p) > r * r);
    });
    if (near) return unknown;
    it_.begin(Ray{p, dir, 0, std::numeric_limits<double>::infinity()});
    int winding = 0;  // leaves minus enters beyond p: 1 inside, 0 outside a closed mesh
    Hit h;
    while (it_.next(h))
      if (h.geom == geom) winding += h.enter ? -1 : 1;
    return winding == 1 ? inside : winding == 0 ? outside : unknown;
  }

 private:
  const Accel& accel_;
  HitIterator& it_;
  NodeStack<float>& stack_;
};

}  // namespace

// The ray starts on the solid's surface heading inward, so it is inside (depth 1) from the
// start. Crossings within `tie` of the origin are the start triangle, its neighbours through
// the same vertex and coplanar duplicates, all at t = 0 up to rounding: skipped via tmin.
// Beyond that, only this geometry's crossings count (a touching neighbour's coincident face
// is another geometry). Crossings of this geometry within `tie` of each other form one group
// (coplanar duplicates, whose t may differ by rounding): a group's leaves are applied once and
// before its enters, so a duplicated far face exits once and a zero-thickness fold (leave and
// enter together) still exits where the material ends.
double ray_exit_distance(HitIterator& it, std::uint32_t geom, Vec3d point, Vec3d dir, double max_distance,
                         double tie, double offset) {
  return exit_impl<false>(it, geom, point, dir, max_distance, tie, offset, nullptr);
}

namespace detail {

double ray_exit(HitIterator& it, std::uint32_t geom, Vec3d point, Vec3d dir, double max_distance, double tie,
                double offset, std::uint32_t& exit_triangle) {
  ExitRecord rec;
  const double t = exit_impl<true>(it, geom, point, dir, max_distance, tie, offset, &rec);
  exit_triangle = std::isnan(t) ? kInvalidId : rec.prim;
  return t;
}

bool trace_samples(const Accel& accel, const ThicknessOptions& opts, const SampleSet& set, ThicknessResult& res,
                   const Progress& progress) {
  const Scene& scene = accel.scene();
  // Sphere method: one closest-point BVH per sampled solid (queries stay inside the solid).
  std::vector<WideBvhd> solid_bvh;
  std::vector<std::uint32_t> bvh_of(scene.geometries().size(), kInvalidId);
  if (opts.method == ThicknessMethod::sphere) {
    for (std::uint32_t g : set.solids) {
      if (bvh_of[g] != kInvalidId) continue;
      Scene one;
      one.add_mesh(scene.geometry(g).vertices, scene.geometry(g).triangles);
      bvh_of[g] = std::uint32_t(solid_bvh.size());
      solid_bvh.push_back(build_wide_bvh<double>(one));
    }
  }

  const double tie = tie_distance(scene, opts.tie_tolerance_rel);
  std::optional<OriginOffsets> offsets;
  if (uses_origin_offsets(opts)) offsets = build_origin_offsets(scene, accel.wide(), opts.offset_set);
  // Where a sample starts and along which inward direction (a mesh sample: its result row).
  struct Start {
    Vec3d point, inward;
    const CadSample* cad;  // null for a mesh sample
  };
  auto start_of = [&](const Sample& s) -> Start {
    if (s.is_cad()) {
      const CadSample& c = set.cad[s.cad];
      return {c.point, c.inward, &c};
    }
    return {res.point[s.out_index], res.normal[s.out_index] * -1.0, nullptr};
  };
  auto offset_of = [&](const Sample& s, Vec3d point, Vec3d dir) {
    return offsets && s.prim != kInvalidId ? safe_offset(*offsets, s.geom, s.prim, point, dir) : 0.0;
  };
  const std::vector<ConeDir> cone =
      opts.method == ThicknessMethod::cone ? cone_directions(opts.cone_rays, opts.cone_angle_deg)
                                           : std::vector<ConeDir>{};
  const double min_cone_angle = cone.size() > 1 ? cone[1].angle : 1.0;
  KernelOptions kopts;
  kopts.order.tie = TieOrder::leave_before_enter;

  struct Worker {
    HitIterator it;
    NodeStack<double> stack;
    std::vector<std::pair<double, double>> lens;
    NodeStack<float> fstack;
  };
  tbb::enumerable_thread_specific<Worker> workers(
      [&] { return Worker{HitIterator(accel, opts.kernel, kopts), {}, {}, {}}; });

  // One ray of a sample: meshes as ray_exit_distance; CAD samples traced on the mesh from the
  // mesh point, then the exit refined on the exact face of the triangle crossed.
  auto one_ray = [&](Worker& w, const Sample& s, const Start& at, Vec3d dir) -> Measured {
    if (!at.cad) {
      Measured m;
      m.t = ray_exit(w.it, s.geom, at.point, dir, opts.max_distance, tie, offset_of(s, at.point, dir), m.exit_triangle);
      return m;
    }
    const CadSample& c = *at.cad;
    ExitRecord rec;
    const double tm = exit_impl<true>(w.it, s.geom, c.mesh_point, dir, opts.max_distance, tie, 0, &rec);
    const std::span<const std::uint8_t> folded = folded_flags(opts, s.geom);
    const bool met_fold = !folded.empty() && rec.first_prim != kInvalidId && folded[rec.first_prim] != 0;
    // Where the mesh gives no answer, the exact B-rep is asked directly (slow, rare); the mesh
    // of a closed solid classifies the points on the way that lie clear of it.
    const SceneMeshSide mesh_side(accel, w.it, w.fstack);
    const MeshSide* mesh = c.closed ? &mesh_side : nullptr;
    auto exact_fallback = [&]() -> Measured {
      const std::optional<double> t = opts.exact->exact_exit(s.geom, c.point, dir, tie, mesh);
      if (!t) return {kNaN, ThicknessStatus::tessellation};
      if (*t > opts.max_distance) return {kNaN, ThicknessStatus::no_exit};
      return {*t};
    };
    if (std::isnan(tm)) {
      // In a closed solid every ray finds an exit: one that does not slipped through the mesh.
      const bool artefact = c.closed && std::isinf(opts.max_distance);
      if (!artefact) return {kNaN, ThicknessStatus::no_exit};
      if (c.exact && !met_fold) return exact_fallback();
      return {kNaN, ThicknessStatus::tessellation};
    }
    if (met_fold || (!folded.empty() && folded[rec.prim] != 0)) return {kNaN, ThicknessStatus::tessellation};
    if (!c.exact) return {tm};
    const std::optional<SurfaceCrossing> x = opts.exact->intersect(s.geom, rec.prim, rec.u, rec.v, c.point, dir);
    if (!x) return exact_fallback();
    double t = x->t;
    // A ray that meets the face at a glancing angle is where the mesh and the B-rep may disagree:
    // it may leave the exact solid before the mesh says (a graze the chords hide), or only touch
    // the face (a vertex sample on a rim, running down the face below it, grazes that face's
    // chords at once) and leave much later. So may one that meets the face on its boundary (an
    // edge, where it may run on into a neighbouring face's plane). The whole B-rep decides, as it
    // does where the ray crosses a face before that the mesh cannot show (a hole's wall, passed a
    // hair inside its circle, between the chords and the arc).
    if (x->on_boundary || !(std::abs(dot(x->normal, dir)) >= kGrazingCos) ||
        opts.exact->hidden_crossing(s.geom, c.point, dir, x->t, c.face, opts.exact->face_of(s.geom, rec.prim))) {
      const std::optional<double> first = opts.exact->exact_exit(s.geom, c.point, dir, tie, mesh);
      if (first) t = *first;
    }
    if (t > opts.max_distance) return {kNaN, ThicknessStatus::no_exit};
    return {t};
  };

  auto measure = [&](Worker& w, const Sample& s) -> Measured {
    if (s.preset != ThicknessStatus::ok) return {kNaN, s.preset};
    const Start at = start_of(s);
    const Measured ray = one_ray(w, s, at, at.inward);
    switch (opts.method) {
      case ThicknessMethod::ray: return ray;
      case ThicknessMethod::cone: {
        if (ray.status == ThicknessStatus::tessellation) return ray;
        Vec3d u, v;
        basis(at.inward, u, v);
        w.lens.clear();
        std::size_t escaped = 0, counted = 0;
        for (std::size_t i = 0; i < cone.size(); ++i) {
          const Vec3d d = u * cone[i].local.x + v * cone[i].local.y + at.inward * cone[i].local.z;
          const Measured m = i == 0 ? ray : one_ray(w, s, at, d);
          if (m.status == ThicknessStatus::tessellation) continue;  // CAD: an artefact, left out
          ++counted;
          if (std::isnan(m.t)) ++escaped;
          else w.lens.emplace_back(m.t, cone[i].angle);
        }
        // Most rays escaping means there is no enclosed material here to measure.
        if (w.lens.empty() || 2 * escaped > counted) return {kNaN, ThicknessStatus::no_exit};
        return {cone_aggregate(w.lens, opts.cone_aggregate, min_cone_angle)};
      }
      case ThicknessMethod::sphere: {
        if (std::isnan(ray.t)) return ray;
        const WideBvhd& bvh = solid_bvh[bvh_of[s.geom]];
        const std::span<const std::uint32_t> exclude(set.exclude.data() + s.exclude_begin,
                                                     s.exclude_end - s.exclude_begin);
        // Shrinking ball (Ma et al. 2012): the ball touching the point with its centre on the
        // inward normal shrinks to pass through the nearest surface point inside it, until
        // none is left. It starts at half the ray thickness, which bounds it. CAD samples: the
        // ball lives on the mesh, so it touches the mesh sample (along the exact normal); the
        // refined ray from the B-rep point, plus the distance between the two, bounds it.
        const Vec3d from = at.cad ? at.cad->mesh_point : at.point;
        double r = 0.5 * (at.cad ? ray.t + length(at.cad->mesh_point - at.point) : ray.t);
        for (int iter = 0; iter < opts.sphere_max_iterations && r > tie; ++iter) {
          const Vec3d c = from + at.inward * r;
          const ClosestPoint cp = closest_point(bvh, c, r * r, exclude, w.stack);
          if (!cp.found() || cp.dist2 >= r * r * (1.0 - 1e-12)) break;
          const Vec3d d = cp.point - from;
          const double denom = 2.0 * dot(at.inward, d);
          if (!(denom > 0)) break;
          const double rn = dot(d, d) / denom;
          if (!(rn < r)) break;
          r = rn;
        }
        return {2.0 * r};
      }
    }
    return {kNaN, ThicknessStatus::no_exit};
  };

  // Mesh samples write their own result slot (one each); CAD samples are gathered, as a slot may
  // have several (a vertex on an edge has one per face).
  std::vector<Measured> measured(set.cad.size());
  const bool completed = parallel_for_items(set.samples.size(), 64, workers, progress, [&](Worker& w, std::size_t i) {
    const Sample& s = set.samples[i];
    const Measured m = measure(w, s);
    if (s.is_cad()) {
      measured[s.cad] = m;
    } else {
      res.thickness[s.out_index] = m.t;
      res.status[s.out_index] = std::isnan(m.t) ? ThicknessStatus::no_exit : ThicknessStatus::ok;
      if (opts.method == ThicknessMethod::ray) res.exit_triangle[s.out_index] = m.exit_triangle;
    }
  });
  if (!completed) return false;

  // CAD slots keep their smallest valid sample, with its point and normal; without a valid one,
  // `tessellation` wins over no_exit and no_normal.
  std::vector<std::uint8_t> seen(set.cad.empty() ? 0 : res.size(), 0);
  for (const Sample& s : set.samples) {
    if (!s.is_cad()) continue;
    const CadSample& c = set.cad[s.cad];
    const Measured& m = measured[s.cad];
    const std::uint32_t k = s.out_index;
    const ThicknessStatus st = std::isnan(m.t) && m.status == ThicknessStatus::ok ? ThicknessStatus::no_exit : m.status;
    if (!res.brep_faces.empty() && c.exact) res.brep_faces[k] = std::uint8_t(std::min(255, res.brep_faces[k] + 1));
    auto rank = [](ThicknessStatus x) {
      return x == ThicknessStatus::ok ? 0 : x == ThicknessStatus::tessellation ? 1 : x == ThicknessStatus::no_exit ? 2 : 3;
    };
    const bool better = !seen[k] || rank(st) < rank(res.status[k]) ||
                        (st == ThicknessStatus::ok && res.status[k] == ThicknessStatus::ok && m.t < res.thickness[k]);
    seen[k] = 1;
    if (!better) continue;
    res.thickness[k] = st == ThicknessStatus::ok ? m.t : kNaN;
    res.status[k] = st;
    if (c.exact && s.preset != ThicknessStatus::tessellation) {
      res.point[k] = c.point;
      res.normal[k] = c.inward * -1.0;
    }
  }
  return true;
}

}  // namespace detail

}  // namespace pierce::analysis
