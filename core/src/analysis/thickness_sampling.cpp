// Thickness, stage 1: the samples (per vertex, per face, or at given points) and the rows of
// the result. CAD samples start on the exact B-rep face, along its exact inward normal.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "pierce/analysis/bvh_query.h"
#include "pierce/analysis/mesh_topology.h"
#include "pierce/bvh_builder.h"
#include "pierce/huge_page_allocator.h"
#include "pierce/parallel_for_items.h"
#include "thickness_internal.h"

namespace pierce::analysis::detail {

void check_options(const Accel& accel, const ThicknessOptions& o) {
  if (!(o.max_distance > 0)) throw std::invalid_argument("thickness: max distance must be positive");
  if (!(o.min_thickness >= 0)) throw std::invalid_argument("thickness: min thickness must be >= 0");
  if (!(o.max_thickness >= 0)) throw std::invalid_argument("thickness: max thickness must be >= 0");
  if (o.min_thickness > 0 && o.max_thickness < o.min_thickness)
    throw std::invalid_argument("thickness: max thickness must not be below min thickness");
  if (o.method == ThicknessMethod::cone) {
    if (o.cone_rays < 1) throw std::invalid_argument("thickness: cone needs at least one ray");
    if (!(o.cone_angle_deg > 0 && o.cone_angle_deg < 180))
      throw std::invalid_argument("thickness: cone angle must be in (0, 180) degrees");
  }
  if (!(o.tie_tolerance_rel >= 0)) throw std::invalid_argument("thickness: tie tolerance must be >= 0");
  if (!is_exact(o.kernel)) throw std::invalid_argument("thickness: needs an exact kernel");
  const auto& geos = accel.scene().geometries();
  for (auto s : o.solids)
    if (s >= geos.size()) throw std::invalid_argument("thickness: no solid with id " + std::to_string(s));
  if (!o.sample_mask.empty()) {
    if (o.sample_mask.size() != geos.size())
      throw std::invalid_argument("thickness: the sample mask needs one entry per solid");
    for (std::size_t g = 0; g < geos.size(); ++g) {
      const std::size_t n = o.per == SampleAt::vertex ? geos[g].vertices.size() : geos[g].triangles.size();
      if (!o.sample_mask[g].empty() && o.sample_mask[g].size() != n)
        throw std::invalid_argument("thickness: the sample mask of solid " + std::to_string(g) +
                                    " does not match its element count");
    }
  }
  if (!o.tessellation_flags.empty()) {
    if (o.tessellation_flags.size() != geos.size())
      throw std::invalid_argument("thickness: the tessellation flags need one entry per solid");
    for (std::size_t g = 0; g < geos.size(); ++g)
      if (!o.tessellation_flags[g].empty() && o.tessellation_flags[g].size() != geos[g].triangles.size())
        throw std::invalid_argument("thickness: the tessellation flags of solid " + std::to_string(g) +
                                    " do not match its triangle count");
  }
  if (o.exact)
    for (std::uint32_t g = 0; g < geos.size(); ++g)
      if (o.exact->covers(g) && o.exact->folded(g).size() != geos[g].triangles.size())
        throw std::invalid_argument("thickness: the exact surfaces of solid " + std::to_string(g) +
                                    " do not match its triangles");
}

bool is_cad(const ThicknessOptions& opts, std::uint32_t g) {
  return (opts.exact && opts.exact->covers(g)) ||
         (g < opts.tessellation_flags.size() && !opts.tessellation_flags[g].empty());
}

std::span<const std::uint8_t> folded_flags(const ThicknessOptions& opts, std::uint32_t g) {
  if (opts.exact && opts.exact->covers(g)) return opts.exact->folded(g);
  if (g < opts.tessellation_flags.size()) return opts.tessellation_flags[g];
  return {};
}

namespace {

// CAD vertices on an edge: how far (a fraction of the distance to the triangle's centre) each
// face's sample is moved into the face.
constexpr double kEdgeInset = 1e-6;

bool closed_mesh(const Geometry& geo, const std::vector<std::uint32_t>& weld) {
  const EdgeStats e = edge_stats(geo, weld);
  return e.boundary == 0 && e.non_manifold == 0 && !geo.triangles.empty();
}

void push_row(ThicknessResult& res, std::uint32_t g, std::uint32_t element, Vec3d p, Vec3d n) {
  res.solid.push_back(g);
  res.element.push_back(element);
  res.point.push_back(p);
  res.normal.push_back(n);
  res.thickness.push_back(kNaN);
  res.thin.push_back(0);
  res.status.push_back(n == Vec3d{} ? ThicknessStatus::no_normal : ThicknessStatus::ok);
}

// Barycentrics (b1, b2) of corner k.
std::pair<double, double> corner_bary(int k) { return k == 1 ? std::pair{1.0, 0.0} : k == 2 ? std::pair{0.0, 1.0} : std::pair{0.0, 0.0}; }

// thickness_at on CAD input: the triangles within the nearest one's distance plus this fraction
// of its longest edge name the B-rep faces searched for the point's foot. A point on face B near
// its edge with face A may lie nearer to A's chords than to B's (B's chords are up to their
// sagitta away, a few hundredths of a chord at the default angular deflection).
constexpr double kCandidateReach = 0.25;

// Barycentrics (b1, b2) of point `p` (on the triangle's plane) on triangle `t`; its centre for a
// degenerate triangle.
std::pair<double, double> barycentrics(const Geometry& geo, std::uint32_t t, Vec3d p) {
  const Tri& tri = geo.triangles[t];
  const Vec3d a = geo.vertices[tri[0]], e1 = geo.vertices[tri[1]] - a, e2 = geo.vertices[tri[2]] - a;
  const Vec3d d = p - a;
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), det = d11 * d22 - d12 * d12;
  if (!(det > 0)) return {1.0 / 3.0, 1.0 / 3.0};
  return {(d22 * dot(d, e1) - d12 * dot(d, e2)) / det, (d11 * dot(d, e2) - d12 * dot(d, e1)) / det};
}

// Per thread, the candidate triangles of a point (reused from point to point).
struct Candidates {
  struct Near {
    double d;
    std::uint32_t prim;
    Vec3d point;  // the nearest point of the triangle
  };
  std::vector<Near> near;
  std::vector<FaceStart> starts;
};

// A CAD sample at mesh point `m` on triangle `prim`: projected onto the exact face when there
// are exact surfaces (a failed projection is a tessellation artefact), flagged when it starts on
// a folded triangle. `on_face`: the exact point already found (thickness_at); without it `m` is
// projected.
std::pair<Sample, CadSample> cad_sample(const ThicknessOptions& opts, std::uint32_t g, std::uint32_t out,
                                       std::uint32_t prim, double b1, double b2, Vec3d m, Vec3d mesh_inward,
                                       bool start_folded, bool closed,
                                       const std::optional<SurfacePoint>* on_face = nullptr) {
  Sample s{g, out};
  CadSample c{m, mesh_inward, m};
  c.closed = closed;
  if (opts.exact && opts.exact->covers(g)) {
    c.exact = true;
    c.face = opts.exact->face_of(g, prim);
    if (const auto p = on_face ? *on_face : opts.exact->project(g, prim, b1, b2, m)) {
      c.point = p->point;
      c.inward = p->normal * -1.0;
      if (p->normal == Vec3d{}) s.preset = ThicknessStatus::no_normal;  // a singular point
    } else {
      s.preset = ThicknessStatus::tessellation;
    }
  }
  if (start_folded) s.preset = ThicknessStatus::tessellation;
  return {s, c};
}

}  // namespace

SampleSet build_samples(const Scene& scene, const ThicknessOptions& opts, ThicknessResult& res) {
  SampleSet set;
  set.solids = opts.solids;
  if (set.solids.empty())
    for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) set.solids.push_back(g);
  res.per = opts.per;
  std::size_t elements = 0;
  bool any_exact = false;
  for (std::uint32_t g : set.solids) {
    elements += opts.per == SampleAt::vertex ? scene.geometry(g).vertices.size() : scene.geometry(g).triangles.size();
    any_exact = any_exact || (opts.exact && opts.exact->covers(g));
  }
  // In huge pages (huge_page_allocator.h): the rows are filled once, at once.
  reserve_huge(res.solid, elements), reserve_huge(res.element, elements), reserve_huge(res.point, elements);
  reserve_huge(res.normal, elements), reserve_huge(res.thickness, elements), reserve_huge(res.thin, elements);
  reserve_huge(res.status, elements), reserve_huge(set.samples, elements);
  for (std::uint32_t g : set.solids) {
    const Geometry& geo = scene.geometry(g);
    std::vector<std::uint32_t> weld = weld_by_position(geo.vertices);
    const std::size_t base = res.size();
    const bool cad = is_cad(opts, g);
    const std::span<const std::uint8_t> folded = folded_flags(opts, g);
    const bool closed = cad && closed_mesh(geo, weld);
    const bool masked = !opts.sample_mask.empty();
    const std::vector<std::uint8_t>* mask = masked ? &opts.sample_mask[g] : nullptr;
    auto selected = [&](std::uint32_t e) { return !masked || (!mask->empty() && (*mask)[e] != 0); };
    if (opts.per == SampleAt::vertex) {
      auto normals = vertex_normals(geo, weld);
      // With a mask, a group of coincident vertices is measured (at its first vertex) when any
      // of its vertices is selected.
      std::vector<std::uint8_t> group_wanted;
      std::vector<std::uint32_t> out_of;  // result index of each pushed vertex
      if (masked) {
        group_wanted.assign(geo.vertices.size(), 0);
        for (std::uint32_t v = 0; v < geo.vertices.size(); ++v)
          if (selected(v)) group_wanted[weld[v]] = 1;
        out_of.assign(geo.vertices.size(), kInvalidId);
      }
      // Triangles around each welded vertex, for the sphere method's exclusions and CAD samples.
      std::vector<std::vector<std::uint32_t>> around;
      if (opts.method == ThicknessMethod::sphere || cad) {
        around.resize(geo.vertices.size());
        for (std::uint32_t t = 0; t < geo.triangles.size(); ++t)
          for (auto v : geo.triangles[t]) {
            auto& list = around[weld[v]];
            if (list.empty() || list.back() != t) list.push_back(t);
          }
      }
      auto wanted = [&](std::uint32_t v) { return !masked || selected(v) || (weld[v] == v && group_wanted[v]); };
      // The rows first: they hold the normals, which are then freed before the samples are made
      // (one vertex-sized array less at the peak; a vertex's normal is its row's).
      for (std::uint32_t v = 0; v < geo.vertices.size(); ++v) {
        if (!wanted(v)) continue;
        push_row(res, g, v, geo.vertices[v], normals[v]);
        if (masked) out_of[v] = std::uint32_t(res.size() - 1);
      }
      std::vector<Vec3d>().swap(normals);
      for (std::uint32_t v = 0; v < geo.vertices.size(); ++v) {
        if (!wanted(v)) continue;
        const std::uint32_t out = masked ? out_of[v] : std::uint32_t(base + v);
        const Vec3d normal = res.normal[out];
        if (weld[v] != v && (normal != Vec3d{} || cad)) {
          set.copies.emplace_back(out, masked ? out_of[weld[v]] : std::uint32_t(base + weld[v]));
          continue;
        }
        if (cad) {
          // One sample per exact face through the vertex, from the vertex's (u, v) on it.
          std::map<std::uint32_t, std::pair<std::uint32_t, int>> per_face;  // face -> (triangle, corner)
          std::map<std::uint32_t, bool> face_folded;
          for (std::uint32_t t : around[v]) {
            const std::uint32_t f = opts.exact && opts.exact->covers(g) ? opts.exact->face_of(g, t) : 0;
            if (geo.degenerate[t]) continue;
            int corner = 0;
            for (int k = 0; k < 3; ++k)
              if (weld[geo.triangles[t][std::size_t(k)]] == v) corner = k;
            per_face.emplace(f, std::pair{t, corner});
            face_folded[f] = face_folded[f] || (!folded.empty() && folded[t] != 0);
          }
          if (per_face.empty()) {
            res.status[out] = ThicknessStatus::no_normal;
            continue;
          }
          res.status[out] = ThicknessStatus::ok;
          auto add = [&](std::pair<Sample, CadSample> smp) {
            smp.first.exclude_begin = std::uint32_t(set.exclude.size());
            if (opts.method == ThicknessMethod::sphere)
              set.exclude.insert(set.exclude.end(), around[v].begin(), around[v].end());
            smp.first.exclude_end = std::uint32_t(set.exclude.size());
            set.add_cad(smp.first, smp.second);
          };
          const bool exact = opts.exact && opts.exact->covers(g);
          bool any_folded = false;
          for (const auto& [f, fo] : face_folded) any_folded = any_folded || fo;
          if (!exact) {  // flags only: the mesh normal, once
            auto smp = cad_sample(opts, g, out, per_face.begin()->second.first, 0, 0, geo.vertices[v],
                                  normal * -1.0, any_folded, closed);
            if (normal == Vec3d{}) smp.first.preset = ThicknessStatus::no_normal;
            add(smp);
            continue;
          }
          // Each face's exact normal at the vertex. A face's sample is taken where its inward
          // normal enters the material past every other face through the vertex (a convex edge
          // of 90 degrees or more, a concave or tangent one); at an acute edge it would leave at
          // once through the neighbour (a knife edge, no wall to measure), so it is not taken.
          struct AtFace {
            std::uint32_t face, tri;
            int corner;
            std::optional<SurfacePoint> at;
          };
          std::vector<AtFace> faces;
          for (const auto& [f, tc] : per_face) {
            const auto [b1, b2] = corner_bary(tc.second);
            faces.push_back({f, tc.first, tc.second, opts.exact->project(g, tc.first, b1, b2, geo.vertices[v])});
          }
          std::size_t taken = 0, projected = 0;
          Vec3d mean{};
          for (const AtFace& af : faces) {
            if (!af.at) continue;
            ++projected;
            if (af.at->normal == Vec3d{}) continue;  // singular point of this face (a cone's apex)
            mean = mean + af.at->normal;
            // Leaving through `other`: the edge is convex there (other's triangle bends away
            // below this face's tangent plane) and the ray heads out of other's side.
            bool enters = true;
            for (const AtFace& other : faces) {
              if (&other == &af || !other.at || !(dot(af.at->normal, other.at->normal) < -1e-9)) continue;
              const Tri& ot = geo.triangles[other.tri];
              const Vec3d oc = (geo.vertices[ot[0]] + geo.vertices[ot[1]] + geo.vertices[ot[2]]) * (1.0 / 3.0);
              if (dot(oc - geo.vertices[v], af.at->normal) < 0) enters = false;
            }
            if (!enters) continue;
            auto [b1, b2] = corner_bary(af.corner);
            Vec3d m = geo.vertices[v];
            if (faces.size() > 1) {
              // On an edge: the sample of face f is its limit from inside the face, a hair
              // (kEdgeInset of the triangle) off the vertex toward the triangle's centre, so its
              // ray does not run along the neighbouring face.
              const Tri& tri = geo.triangles[af.tri];
              const Vec3d c = (geo.vertices[tri[0]] + geo.vertices[tri[1]] + geo.vertices[tri[2]]) * (1.0 / 3.0);
              b1 += kEdgeInset * (1.0 / 3.0 - b1), b2 += kEdgeInset * (1.0 / 3.0 - b2);
              m = m + (c - m) * kEdgeInset;
            }
            add(cad_sample(opts, g, out, af.tri, b1, b2, m, normal * -1.0, face_folded[af.face], closed));
            ++taken;
          }
          if (taken > 0) continue;
          if (projected == 0) {  // no face could place the vertex: an artefact of the mesh
            Sample smp{g, out};
            smp.preset = ThicknessStatus::tessellation;
            add({smp, CadSample{geo.vertices[v], normal * -1.0, geo.vertices[v], true, closed}});
            continue;
          }
          // Every face's ray would leave at once (an acute edge or corner): one sample from the
          // vertex along the mean of the faces' exact normals, as a mesh vertex is sampled.
          const double ml = length(mean);
          Sample smp{g, out};
          CadSample at{geo.vertices[v], normal * -1.0, geo.vertices[v], true, closed};
          for (const AtFace& af : faces)
            if (af.at) at.point = af.at->point;  // the vertex on the B-rep
          if (ml > 0) at.inward = mean * (-1.0 / ml);
          smp.preset = any_folded ? ThicknessStatus::tessellation
                                  : (ml > 0 ? ThicknessStatus::ok : ThicknessStatus::no_normal);
          add({smp, at});
          continue;
        }
        if (normal == Vec3d{}) continue;
        Sample s{g, out, std::uint32_t(set.exclude.size())};
        if (!around.empty()) set.exclude.insert(set.exclude.end(), around[v].begin(), around[v].end());
        s.exclude_end = std::uint32_t(set.exclude.size());
        set.samples.push_back(s);
      }
    } else {
      // A triangle repeating an earlier one's corners (a duplicated face, whatever its winding)
      // is measured like the first one, as vertex normals count it.
      const auto first = first_occurrence(geo, weld);
      for (std::uint32_t t = 0; t < geo.triangles.size(); ++t) {
        if (!selected(t)) continue;
        const Tri& tri = geo.triangles[t];
        const Vec3d c = (geo.vertices[tri[0]] + geo.vertices[tri[1]] + geo.vertices[tri[2]]) * (1.0 / 3.0);
        const Vec3d n = geo.degenerate[t] ? Vec3d{} : face_normal(geo, first[t]);
        push_row(res, g, t, c, n);
        if (n == Vec3d{}) continue;
        const std::uint32_t ex = std::uint32_t(set.exclude.size());
        set.exclude.push_back(t);
        if (cad) {
          auto [s, at] = cad_sample(opts, g, std::uint32_t(res.size() - 1), t, 1.0 / 3.0, 1.0 / 3.0, c, n * -1.0,
                                    !folded.empty() && folded[t] != 0, closed);
          s.exclude_begin = ex, s.exclude_end = ex + 1;
          set.add_cad(s, at);
          continue;
        }
        set.samples.push_back({g, std::uint32_t(res.size() - 1), ex, ex + 1, t});
      }
    }
    set.ranges.emplace_back(base, res.size());
    set.welds.push_back(std::move(weld));
  }
  if (any_exact) res.brep_faces.assign(res.size(), 0);
  res.exit_triangle.assign(res.size(), kInvalidId);
  return set;
}

SampleSet build_point_samples(const Scene& scene, const ThicknessOptions& opts, const std::vector<std::uint32_t>& solids,
                              const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                              ThicknessResult& res) {
  if (solids.size() != points.size() || (!normals.empty() && normals.size() != points.size()))
    throw std::invalid_argument("thickness_at: one solid (and normal, if any) per point");
  for (std::size_t i = 0; i < solids.size(); ++i)
    if (solids[i] >= scene.geometries().size())
      throw std::invalid_argument("thickness_at: point " + std::to_string(i) + ": no solid with id " +
                                  std::to_string(solids[i]));
  SampleSet set;
  res.per = SampleAt::face;
  // One closest-point BVH per solid asked for.
  std::vector<WideBvhd> bvh;
  std::vector<std::uint32_t> bvh_of(scene.geometries().size(), kInvalidId);
  std::vector<std::vector<std::uint32_t>> welds(scene.geometries().size());
  std::vector<std::uint8_t> closed(scene.geometries().size(), 0);
  for (std::uint32_t g : solids) {
    if (bvh_of[g] != kInvalidId) continue;
    set.solids.push_back(g);
    Scene one;
    one.add_mesh(scene.geometry(g).vertices, scene.geometry(g).triangles);
    bvh_of[g] = std::uint32_t(bvh.size());
    bvh.push_back(build_wide_bvh<double>(one));
    welds[g] = weld_by_position(scene.geometry(g).vertices);
    closed[g] = is_cad(opts, g) && closed_mesh(scene.geometry(g), welds[g]);
  }
  std::sort(set.solids.begin(), set.solids.end());
  const std::size_t n = points.size();
  res.solid = solids;
  res.element.assign(n, kInvalidId);
  res.point = points;
  res.normal.assign(n, Vec3d{});
  res.thickness.assign(n, kNaN);
  res.thin.assign(n, 0);
  res.status.assign(n, ThicknessStatus::no_normal);
  bool any_exact = false;
  for (std::uint32_t g : set.solids) any_exact = any_exact || (opts.exact && opts.exact->covers(g));
  if (any_exact) res.brep_faces.assign(n, 0);
  res.exit_triangle.assign(n, kInvalidId);
  std::vector<Sample> samples(n);
  std::vector<CadSample> cads(n);  // of the CAD points
  std::vector<std::uint8_t> has_sample(n, 0);
  tbb::enumerable_thread_specific<NodeStack<double>> stacks;
  tbb::enumerable_thread_specific<Candidates> candidates;
  parallel_for_items(n, 64, stacks, {}, [&](NodeStack<double>& stack, std::size_t i) {
    const std::uint32_t g = solids[i];
    const Geometry& geo = scene.geometry(g);
    const ClosestPoint cp =
        closest_point(bvh[bvh_of[g]], points[i], std::numeric_limits<double>::infinity(), {}, stack);
    if (!cp.found()) return;
    std::uint32_t t = cp.prim;
    Vec3d on_mesh = cp.point;
    // CAD: the point goes onto the nearest B-rep face directly (a point on the B-rep stays where
    // it is); the triangles near it only name the faces to search, each from its nearest one.
    std::optional<SurfacePoint> on_face;
    if (opts.exact && opts.exact->covers(g)) {
      const double d = std::sqrt(cp.dist2);
      const Tri& nt = geo.triangles[t];
      const double longest = std::max({length(geo.vertices[nt[1]] - geo.vertices[nt[0]]),
                                       length(geo.vertices[nt[2]] - geo.vertices[nt[1]]),
                                       length(geo.vertices[nt[0]] - geo.vertices[nt[2]])});
      const double reach = d + kCandidateReach * longest;
      Candidates& cand = candidates.local();
      cand.near.clear();
      const BBoxd box{points[i] - Vec3d{reach, reach, reach}, points[i] + Vec3d{reach, reach, reach}};
      for_each_overlapping(bvh[bvh_of[g]], box, stack, [&](const Triangle<double>& tri) {
        const Vec3d q = closest_point_on_triangle(points[i], tri.v0, tri.v1, tri.v2);
        const double dq = length(q - points[i]);
        if (dq <= reach) cand.near.push_back({dq, tri.prim, q});
      });
      // Nearest first, the nearest triangle of all leading (ties: lowest id, as closest_point).
      std::sort(cand.near.begin(), cand.near.end(), [&](const auto& a, const auto& b) {
        if ((a.prim == t) != (b.prim == t)) return a.prim == t;
        return a.d < b.d || (a.d == b.d && a.prim < b.prim);
      });
      cand.starts.clear();
      for (const auto& c : cand.near) {
        const auto [b1, b2] = barycentrics(geo, c.prim, c.point);
        cand.starts.push_back({c.prim, b1, b2});
      }
      if (const auto near = opts.exact->nearest_on_faces(g, cand.starts, points[i])) {
        t = cand.near[near->start].prim;
        on_mesh = cand.near[near->start].point;
        on_face = near->at;
      }
    }
    res.element[i] = t;
    res.point[i] = on_mesh;
    Vec3d given = normals.empty() ? Vec3d{} : normals[i];
    const double gl = length(given);
    given = gl > 0 && std::isfinite(gl) ? given * (1.0 / gl) : Vec3d{};
    const Vec3d fn = geo.degenerate[t] ? Vec3d{} : face_normal(geo, t);
    const Vec3d mesh_n = given != Vec3d{} ? given : fn;
    if (mesh_n == Vec3d{} && !(opts.exact && opts.exact->covers(g))) return;
    res.status[i] = ThicknessStatus::ok;
    res.normal[i] = mesh_n;
    const auto [b1, b2] = barycentrics(geo, t, on_mesh);
    Sample s{g, std::uint32_t(i)};
    if (is_cad(opts, g)) {
      const std::span<const std::uint8_t> folded = folded_flags(opts, g);
      auto [cs, at] = cad_sample(opts, g, std::uint32_t(i), t, b1, b2, on_mesh, mesh_n * -1.0,
                                 !folded.empty() && folded[t] != 0, closed[g] != 0, on_face ? &on_face : nullptr);
      if (given != Vec3d{}) at.inward = given * -1.0;
      if (cs.preset == ThicknessStatus::ok && at.inward == Vec3d{}) cs.preset = ThicknessStatus::no_normal;
      s = cs;
      cads[i] = at;
    }
    samples[i] = s;
    has_sample[i] = 1;
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_sample[i]) continue;
    Sample s = samples[i];
    s.exclude_begin = std::uint32_t(set.exclude.size());
    set.exclude.push_back(res.element[i]);
    s.exclude_end = s.exclude_begin + 1;
    if (is_cad(opts, s.geom)) {
      set.add_cad(s, cads[i]);
    } else {
      set.samples.push_back(s);
    }
  }
  return set;
}

}  // namespace pierce::analysis::detail
