#include "pierce/io/cad_surfaces.h"

#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <BRepBndLib.hxx>
#include <BRep_Tool.hxx>
#include <ElCLib.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Bnd_Box.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Sphere.hxx>
#include <IntCurvesFace_Intersector.hxx>
#include <IntCurveSurface_TransitionOnCurve.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <Standard_Failure.hxx>
#include <gp_Lin.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "cad_faces.h"
#include "cad_trim_grid.h"
#include "pierce/analysis/bvh_query.h"
#include "pierce/bvh_builder.h"
#include "pierce/slab.h"

namespace pierce {

namespace {

Vec3d vec(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }

constexpr int kMaxNewtonSteps = 30;

// (u, v) with a periodic direction's parameter moved into the face's own period window, from its
// lower bound: Newton may end any number of periods away (7.7e11 on a blend), and the trim
// classifier steps such a point back one period at a time (minutes).
void wrap_periodic(const CadFaces::Face& f, double& u, double& v) {
  if (f.surface->IsUPeriodic() && std::isfinite(u)) u = ElCLib::InPeriod(u, f.umin, f.umin + f.surface->UPeriod());
  if (f.surface->IsVPeriodic() && std::isfinite(v)) v = ElCLib::InPeriod(v, f.vmin, f.vmin + f.surface->VPeriod());
}

// Whether (u, v) lies in the face's parameter range, widened by `slack` of its size (Newton may
// end a hair outside a trimmed face near its boundary; periodic directions are not bounded).
bool in_range(const CadFaces::Face& f, double u, double v, double slack) {
  const double du = (f.umax - f.umin) * slack, dv = (f.vmax - f.vmin) * slack;
  const bool up = f.surface->IsUPeriodic(), vp = f.surface->IsVPeriodic();
  return (up || (u >= f.umin - du && u <= f.umax + du)) && (vp || (v >= f.vmin - dv && v <= f.vmax + dv));
}

// The diagonal of the shape's bounding box and its largest |coordinate| (1 and 0 for an empty
// shape): the scales of the tolerances here.
struct ShapeScale {
  double size = 1, max_abs = 0;
};
ShapeScale scale_of(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  ShapeScale s;
  if (box.IsVoid()) return s;
  s.size = std::max(std::sqrt(box.SquareExtent()), 1e-300);
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  s.max_abs = std::max({std::abs(x0), std::abs(y0), std::abs(z0), std::abs(x1), std::abs(y1), std::abs(z1)});
  return s;
}

struct Start {
  const CadFaces::Face* face;
  double u, v;
  double size;  // the triangle's largest corner distance on the surface: how far Newton may go
};

}  // namespace

// The whole-B-rep queries of exact_exit, per thread (as the classifiers below: an OpenCASCADE
// algorithm object is not to be used by two threads at once) and per geometry, built on first use.
//
// The line is intersected face by face, as IntCurvesFace_ShapeIntersector does (each face's
// IntCurvesFace_Intersector, in the shape's face order, the points merged and sorted by
// parameter), but a face whose box the line misses is not asked: its intersector finds no point
// on the face there. The shape intersector asks every face, and an analytic face's intersector
// intersects the whole untrimmed surface and builds its line adaptors on every call: most of
// the exact fallback's time on parts of many faces (pierce_bench_cad_refine, connector).
struct CadSurfaces::Intersectors {
  struct Face {
    Bnd_Box box;  // the face's, widened: every point its intersector finds lies in it
    Vec3d lo, hi;  // the box's corners
    std::unique_ptr<IntCurvesFace_Intersector> line;
    std::uint32_t link_face = kInvalidId;  // the face's index in the link (kInvalidId: not meshed)
    // A cylinder's or a sphere's: where the line comes within `radius` + `slack` of the axis
    // (through `centre` along unit `axis`) or of the centre; its points lie there.
    enum Kind : std::uint8_t { other, cylinder, sphere } kind = other;
    Vec3d centre, axis;
    double radius = 0, slack = 0;
  };
  struct OfGeom {
    std::vector<Face> faces;  // every face of the shape, in TopExp_Explorer order
    BRepClass3d_SolidClassifier inside;
    bool inside_loaded = false;  // `inside` is loaded on first use: the mesh answers most points
    double tolerance = 0;
    double slack = 0;  // far above the rounding of a point's coordinates
  };
  tbb::enumerable_thread_specific<std::map<std::uint32_t, std::unique_ptr<OfGeom>>> per_thread;
};

// BRepTopAdaptor_FClass2d::Perform is const but not safe to call from two threads at once
// (concurrent calls from TBB workers crash), so every thread builds its own classifier of a face
// on first use. In front of them, one TrimGrid per face, shared (read-only once built), answers
// the points away from the face's wires.
struct CadSurfaces::Classifiers {
  struct Slot {
    bool built = false;
    std::unique_ptr<BRepTopAdaptor_FClass2d> classifier;  // null if OpenCASCADE could not build it
  };
  using PerThread = std::vector<std::vector<Slot>>;  // [geom][face]
  tbb::enumerable_thread_specific<PerThread> per_thread;
  struct Grid {
    std::once_flag built;
    std::atomic<bool> ready{false};  // `grid` is built: no call_once, no classifier needed to read it
    TrimGrid grid;
  };
  std::vector<std::unique_ptr<Grid[]>> grids;  // [geom][face]

  explicit Classifiers(const std::vector<CadLink>& links) : grids(links.size()) {
    for (std::size_t g = 0; g < links.size(); ++g)
      if (!links[g].empty()) grids[g] = std::make_unique<Grid[]>(links[g].faces->faces.size());
  }

  // This thread's classifier of `face`; null where the face is unclassifiable (refined points on
  // it are then not checked against its trim).
  const BRepTopAdaptor_FClass2d* of(const std::vector<CadLink>& links, std::uint32_t geom, std::uint32_t face) {
    PerThread& mine = per_thread.local();
    if (mine.empty()) {
      mine.resize(links.size());
      for (std::size_t g = 0; g < links.size(); ++g)
        if (!links[g].empty()) mine[g].resize(links[g].faces->faces.size());
    }
    Slot& slot = mine.at(geom).at(face);
    if (!slot.built) {
      slot.built = true;
      const CadFaces::Face& f = links[geom].faces->faces[face];
      try {
        const double span = std::max(f.umax - f.umin, f.vmax - f.vmin);
        slot.classifier = std::make_unique<BRepTopAdaptor_FClass2d>(f.face, 1e-9 * std::max(span, 1e-300));
      } catch (const Standard_Failure&) {
        slot.classifier.reset();
      }
    }
    return slot.classifier.get();
  }

  // Where (u, v) (in the face's period window) lies against the trim of `face`, as its classifier
  // says; TopAbs_IN where the face is unclassifiable.
  TopAbs_State state(const std::vector<CadLink>& links, std::uint32_t geom, std::uint32_t face, double u, double v) {
    Grid& g = grids[geom][face];
    if (!g.ready.load(std::memory_order_acquire)) {
      const BRepTopAdaptor_FClass2d* trim = of(links, geom, face);
      if (!trim) return TopAbs_IN;
      std::call_once(g.built, [&] {
        const CadFaces::Face& f = links[geom].faces->faces[face];
        g.grid = TrimGrid(f.face, f.umin, f.umax, f.vmin, f.vmax, *trim);
      });
      g.ready.store(true, std::memory_order_release);
    }
    const TopAbs_State known = g.grid.state(u, v);
    if (known != TopAbs_UNKNOWN) return known;
    const BRepTopAdaptor_FClass2d* trim = of(links, geom, face);
    if (!trim) return TopAbs_IN;
    return trim->Perform(gp_Pnt2d(u, v));
  }
};

namespace {

// Where a dipping patch lies: within `half_height` of its chord triangle's plane (unit normal
// `normal`, offset `height` = dot(corner, normal)) and inside the triangle's edges moved out by
// a slack (dot(p, edge_normal[k]) >= edge_offset[k], edge normals unit, in the plane, inwards).
struct PatchPrism {
  Vec3d normal;
  double height = 0, half_height = 0;
  Vec3d edge_normal[3];
  double edge_offset[3] = {0, 0, 0};
  std::uint32_t face = 0;
  BBoxd box;  // of the prism
};

}  // namespace

// Per geometry, the prisms holding the exact patches (a triangle's (u, v) triangle mapped onto its
// face) that dip below their triangle into the solid, in a BVH over their boxes built on first
// use; per thread, the exact line intersectors of the faces of such patches.
struct CadSurfaces::HiddenFaces {
  struct OfGeom {
    std::once_flag built;
    std::vector<PatchPrism> prisms;
    // The prisms' boxes, each stored as a triangle spanning it (the scene BVH's builder makes node
    // boxes the exact unions of their triangles' boxes); Triangle::prim indexes `prisms`.
    WideBvhd boxes;
    double tolerance = 0;  // for OpenCASCADE's intersector
    double margin = 0;     // crossings this near the segment's ends are not reported
  };
  explicit HiddenFaces(std::size_t geometries) : geoms(std::make_unique<OfGeom[]>(geometries)) {}
  static void build(const CadLink& l, OfGeom& h);
  std::unique_ptr<OfGeom[]> geoms;
  using Key = std::pair<std::uint32_t, std::uint32_t>;  // (geom, face)
  tbb::enumerable_thread_specific<std::map<Key, std::unique_ptr<IntCurvesFace_Intersector>>> intersectors;
  tbb::enumerable_thread_specific<NodeStack<double>> stacks;
};

namespace {

// The prism of triangle `uv`'s exact patch on face `f` when the patch dips into the solid below
// the triangle's plane by more than `noise`, else nullopt. The patch is sampled at its edge
// midpoints and centre (a smooth patch deviates most from its chord about there); twice the
// largest deviation from the chord seen, plus `noise`, bounds its height over the chord's plane
// and how far it reaches past the chord's edges. Where the normal is undefined (a pole) the point
// counts as dipping.
std::optional<PatchPrism> inward_patch_prism(const CadFaces::Face& f,
                                                                   const std::array<double, 6>& uv, double noise) {
  static constexpr double kBary[4][3] = {{0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {1 / 3.0, 1 / 3.0, 1 / 3.0}};
  const Geom_Surface& surf = *f.surface;
  gp_Pnt c[3];
  for (int k = 0; k < 3; ++k) c[k] = surf.Value(uv[std::size_t(2 * k)], uv[std::size_t(2 * k + 1)]);
  double dip = 0, deviation = 0;
  for (const auto& b : kBary) {
    const double u = b[0] * uv[0] + b[1] * uv[2] + b[2] * uv[4], v = b[0] * uv[1] + b[1] * uv[3] + b[2] * uv[5];
    gp_Pnt p;
    gp_Vec su, sv;
    surf.D1(u, v, p, su, sv);
    const gp_Vec off(c[0].XYZ() * b[0] + c[1].XYZ() * b[1] + c[2].XYZ() * b[2], p.XYZ());  // chord to surface
    const gp_Vec n = su.Crossed(sv) * f.sign;
    const double len = n.Magnitude();
    deviation = std::max(deviation, off.Magnitude());
    dip = std::max(dip, len > 0 ? -off.Dot(n) / len : off.Magnitude());
  }
  if (!(dip > noise)) return std::nullopt;
  const Vec3d a[3] = {vec(c[0].XYZ()), vec(c[1].XYZ()), vec(c[2].XYZ())};
  const Vec3d n = cross(a[1] - a[0], a[2] - a[0]);
  const double area2 = length(n);
  PatchPrism prism;
  const double reach = 2 * deviation + noise;
  if (area2 > 0) {
    prism.normal = n * (1.0 / area2);
    prism.height = dot(a[0], prism.normal);
    prism.half_height = reach;
    for (int k = 0; k < 3; ++k) {
      const Vec3d e = a[(k + 1) % 3] - a[k];
      const Vec3d m = cross(prism.normal, e) * (1.0 / length(e));  // inwards: the normal is the chord's own
      prism.edge_normal[k] = m;
      prism.edge_offset[k] = dot(a[k], m) - reach;
    }
  } else {
    // A chord of zero area (a patch at a pole): no plane to hold it, the box alone does.
    prism.half_height = std::numeric_limits<double>::infinity();
  }
  for (const Vec3d& p : a) prism.box.extend(p);
  const double w = 2 * reach;  // holds the prism: `reach` off the plane plus `reach` past the edges
  prism.box.lo = prism.box.lo - Vec3d{w, w, w};
  prism.box.hi = prism.box.hi + Vec3d{w, w, w};
  return prism;
}

// The part [ta, tb] of the segment that lies in the prism; ta > tb when none does.
void clip_to_prism(const PatchPrism& p, Vec3d org, Vec3d dir, double& ta, double& tb) {
  // Keeps dot(org + t dir, n) >= lo.
  auto keep = [&](Vec3d n, double lo) {
    const double a = dot(org, n) - lo, b = dot(dir, n);
    if (b > 0) ta = std::max(ta, -a / b);
    else if (b < 0) tb = std::min(tb, -a / b);
    else if (!(a >= 0)) tb = -std::numeric_limits<double>::infinity();
  };
  if (std::isfinite(p.half_height)) {
    keep(p.normal, p.height - p.half_height);
    keep(p.normal * -1.0, -(p.height + p.half_height));
    for (int k = 0; k < 3; ++k) keep(p.edge_normal[k], p.edge_offset[k]);
  }
}

}  // namespace

// Per triangle of every geometry, Start::size (negative until computed).
struct CadSurfaces::Sizes {
  std::vector<std::vector<std::atomic<double>>> geoms;
  explicit Sizes(const std::vector<CadLink>& links) : geoms(links.size()) {
    for (std::size_t g = 0; g < links.size(); ++g) {
      geoms[g] = std::vector<std::atomic<double>>(links[g].face.size());
      for (std::atomic<double>& a : geoms[g]) a.store(-1.0, std::memory_order_relaxed);
    }
  }
  std::atomic<double>& of(std::uint32_t geom, std::uint32_t prim) { return geoms.at(geom).at(prim); }
};

// Per geometry, mesh_bands(), measured on first use.
struct CadSurfaces::MeshBands {
  struct OfGeom {
    std::once_flag built;
    std::vector<double> band;      // per face
    analysis::MeshBands view;      // of `band` and the link's faces
    bool valid = false;            // measured, every band finite
  };
  explicit MeshBands(std::size_t geometries) : geoms(std::make_unique<OfGeom[]>(geometries)) {}
  // The bands per face; empty where the mesh folds or a band is not finite.
  static std::vector<double> measure(const CadLink& l);
  std::unique_ptr<OfGeom[]> geoms;
};

namespace {

// The largest distance between triangle `uv`'s chord and its exact patch on face `f`, sampled at
// the chord's edge midpoints and centre (a smooth patch deviates most from its chord about there).
double chord_deviation(const CadFaces::Face& f, const std::array<double, 6>& uv) {
  static constexpr double kBary[4][3] = {{0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {1 / 3.0, 1 / 3.0, 1 / 3.0}};
  const Geom_Surface& surf = *f.surface;
  gp_Pnt c[3];
  for (int k = 0; k < 3; ++k) c[k] = surf.Value(uv[std::size_t(2 * k)], uv[std::size_t(2 * k + 1)]);
  double deviation = 0;
  for (const auto& b : kBary) {
    const double u = b[0] * uv[0] + b[1] * uv[2] + b[2] * uv[4], v = b[0] * uv[1] + b[1] * uv[3] + b[2] * uv[5];
    const gp_XYZ chord = c[0].XYZ() * b[0] + c[1].XYZ() * b[1] + c[2].XYZ() * b[2];
    deviation = std::max(deviation, surf.Value(u, v).XYZ().Subtracted(chord).Modulus());
  }
  return deviation;
}

}  // namespace

std::vector<double> CadSurfaces::MeshBands::measure(const CadLink& l) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (l.check.folded > 0) return {};  // a fold turns the mesh inside out there
  const CadFaces& faces = *l.faces;
  std::vector<std::uint8_t> planar(faces.faces.size());
  for (std::size_t f = 0; f < planar.size(); ++f)
    planar[f] = GeomAdaptor_Surface(faces.faces[f].surface).GetType() == GeomAbs_Plane;
  // Each triangle's deviation, then the largest per face. Isolated, as HiddenFaces::build: this
  // runs inside the thickness loop's parallel_for.
  std::vector<double> deviation(l.face.size(), 0.0);
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, l.face.size(), 1024), [&](const auto& range) {
      for (std::size_t t = range.begin(); t != range.end(); ++t) {
        if (planar[l.face[t]]) continue;  // a plane's patch is its chord
        double d = kInf;  // where the surface cannot be evaluated the mesh may lie anywhere
        try {
          d = chord_deviation(faces.faces[l.face[t]], l.uv[t]);
        } catch (const Standard_Failure&) {
        }
        deviation[t] = d <= kInf ? d : kInf;  // NaN
      }
    });
  });
  std::vector<double> band(faces.faces.size(), 0.0);
  for (std::size_t t = 0; t < l.face.size(); ++t) band[l.face[t]] = std::max(band[l.face[t]], deviation[t]);
  const ShapeScale scale = scale_of(faces.shape);
  const double noise = 1e-9 * (scale.size + scale.max_abs);
  for (std::size_t f = 0; f < band.size(); ++f) {
    // The face's own tolerance and those of its edges and vertices: where the B-rep's faces meet
    // up to them, the gap lies within them of both faces' triangles.
    const TopoDS_Face& face = faces.faces[f].face;
    double tolerance = BRep_Tool::Tolerance(face);
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next())
      tolerance = std::max(tolerance, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
    for (TopExp_Explorer ex(face, TopAbs_VERTEX); ex.More(); ex.Next())
      tolerance = std::max(tolerance, BRep_Tool::Tolerance(TopoDS::Vertex(ex.Current())));
    band[f] = 2 * band[f] + 2 * tolerance + noise;
    if (!std::isfinite(band[f])) return {};
  }
  return band;
}

const analysis::MeshBands* CadSurfaces::mesh_bands(std::uint32_t geom) const {
  if (!covers(geom)) return nullptr;
  MeshBands::OfGeom& b = bands_->geoms[geom];
  std::call_once(b.built, [&] {
    try {
      b.band = MeshBands::measure(links_[geom]);
    } catch (const Standard_Failure&) {
      b.band.clear();
    }
    if (b.band.empty()) return;
    b.view = analysis::MeshBands{links_[geom].face, b.band, *std::max_element(b.band.begin(), b.band.end())};
    b.valid = true;
  });
  return b.valid ? &b.view : nullptr;
}

CadSurfaces::~CadSurfaces() = default;

std::optional<double> CadSurfaces::exact_exit(std::uint32_t geom, Vec3d org, Vec3d dir, double tmin,
                                              const analysis::MeshSide* mesh) const {
  const CadLink& l = links_.at(geom);
  if (l.empty() || l.faces->shape.IsNull()) return std::nullopt;
  const analysis::MeshBands* bands = mesh ? mesh_bands(geom) : nullptr;
  try {
    auto& x = intersectors_->per_thread.local()[geom];
    if (!x) {
      x = std::make_unique<Intersectors::OfGeom>();
      const ShapeScale scale = scale_of(l.faces->shape);
      const double size = scale.size;
      x->tolerance = 1e-9 * size;
      x->slack = 1e-9 * (size + scale.max_abs);
      std::size_t meshed = 0;  // the link's faces: the shape's, in the same order, less the unmeshed
      for (TopExp_Explorer ex(l.faces->shape, TopAbs_FACE); ex.More(); ex.Next()) {
        const TopoDS_Face& face = TopoDS::Face(ex.Current());
        Intersectors::Face f;
        if (meshed < l.faces->faces.size() && l.faces->faces[meshed].face.IsEqual(face))
          f.link_face = std::uint32_t(meshed++);
        BRepBndLib::Add(face, f.box);  // widened by the face's, edges' and vertices' tolerances
        double tol = BRep_Tool::Tolerance(face);
        for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next())
          tol = std::max(tol, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
        f.box.Enlarge(10 * tol + 1e-6 * size);  // points ON an edge lie within its tolerance
        f.box.Get(f.lo.x, f.lo.y, f.lo.z, f.hi.x, f.hi.y, f.hi.z);
        const GeomAdaptor_Surface surface(BRep_Tool::Surface(face));  // placed as the face
        f.slack = 10 * tol + 1e-6 * size;  // as the box's: far above the intersector's tolerance
        if (surface.GetType() == GeomAbs_Cylinder) {
          const gp_Cylinder c = surface.Cylinder();
          f.kind = Intersectors::Face::cylinder;
          f.centre = vec(c.Location().XYZ()), f.axis = vec(c.Axis().Direction().XYZ()), f.radius = c.Radius();
        } else if (surface.GetType() == GeomAbs_Sphere) {
          const gp_Sphere c = surface.Sphere();
          f.kind = Intersectors::Face::sphere;
          f.centre = vec(c.Location().XYZ()), f.radius = c.Radius();
        }
        f.line = std::make_unique<IntCurvesFace_Intersector>(face, x->tolerance);
        x->faces.push_back(std::move(f));
      }
    }
    const gp_Lin line(gp_Pnt(org.x, org.y, org.z), gp_Dir(dir.x, dir.y, dir.z));
    // A box the half-line beyond tmin misses holds no crossing there: the line misses it, or
    // leaves it before tmin (clipped to the box widened by a slack far above rounding: a cheaper
    // test than Bnd_Box::IsOut, which the faces it keeps still go through).
    // The part [a, b] of the line beyond tmin inside the box (lo, hi); false where the line runs
    // parallel to a side outside it.
    auto span_in_box = [&](Vec3d lo, Vec3d hi, double& a, double& b) {
      a = tmin, b = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < 3; ++k) {
        if (dir[k] == 0) {
          if (org[k] < lo[k] || org[k] > hi[k]) return false;
          continue;
        }
        const double t0 = (lo[k] - org[k]) / dir[k], t1 = (hi[k] - org[k]) / dir[k];
        a = std::max(a, std::min(t0, t1)), b = std::min(b, std::max(t0, t1));
      }
      return true;
    };
    auto behind = [&](const Intersectors::Face& f) {
      const Vec3d slack{x->slack, x->slack, x->slack};
      double a, b;
      return !span_in_box(f.lo - slack, f.hi + slack, a, b) || a > b;
    };
    // A cylinder or sphere holds no crossing beyond tmin either where the line comes within its
    // slack of the surface (|distance to the axis or centre - radius| <= slack) only outside the
    // face's box or before tmin. The slack is far above the intersector's tolerance and the
    // rounding here, so every point it finds lies in these parts of the line.
    auto clear_of = [&](const Intersectors::Face& f) {
      if (f.kind == Intersectors::Face::other) return false;
      Vec3d o = org - f.centre, d = dir;
      if (f.kind == Intersectors::Face::cylinder) {
        o = o - f.axis * dot(o, f.axis), d = d - f.axis * dot(d, f.axis);
      }
      // The distance to the axis or centre is sqrt(|near|^2 + (t - mid)^2 dd).
      const double dd = dot(d, d);
      if (!(dd > 1e-12)) return false;  // about along the axis: not decided here
      const double mid = -dot(o, d) / dd;
      const Vec3d near = o + d * mid;
      const double n2 = dot(near, near), outer = f.radius + f.slack, inner = f.radius - f.slack;
      const double h_out = (outer * outer - n2) / dd;
      if (!(h_out >= 0)) return std::isfinite(h_out);  // the line passes farther than radius + slack
      const double w_out = std::sqrt(h_out);
      const double w_in = inner > 0 && inner * inner > n2 ? std::sqrt((inner * inner - n2) / dd) : 0.0;
      double a, b;  // the box's part of the line beyond tmin
      if (!span_in_box(f.lo, f.hi, a, b)) return true;
      const bool first = std::max(a, mid - w_out) <= std::min(b, mid - w_in);
      const bool second = std::max(a, mid + w_in) <= std::min(b, mid + w_out);
      return !first && !second;
    };
    // Where the line crosses a face (touching one, tangent to it, is no crossing), nearest first,
    // with the mesh's band of the face (infinite where the mesh does not answer).
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, double>> crossings;
    for (Intersectors::Face& f : x->faces) {
      if (behind(f) || f.box.IsOut(line) || clear_of(f)) continue;
      f.line->Perform(line, tmin, kInf);
      if (!f.line->IsDone()) return std::nullopt;
      const double band = bands && f.link_face != kInvalidId ? bands->band[f.link_face] : kInf;
      for (Standard_Integer i = 1; i <= f.line->NbPnt(); ++i)
        if (f.line->Transition(i) != IntCurveSurface_Tangent && f.line->WParameter(i) > tmin)
          crossings.emplace_back(f.line->WParameter(i), band);
    }
    std::sort(crossings.begin(), crossings.end());
    // The ray leaves at the first crossing beyond which it is outside the solid, settled by
    // classifying the line between it and the next crossing: OpenCASCADE's transitions cannot be
    // trusted where the line runs in a face (a vertex sample on a rim, down the face below it: it
    // reports a crossing, "out" through the face's interior, every 1e-4 along it). Beyond the last
    // crossing the line is outside. A point farther from every triangle than the band of the
    // triangle's face lies on the same side of the mesh and of the B-rep (the mesh deforms into
    // the B-rep within the bands without passing it): there the mesh's winding number answers,
    // and OpenCASCADE's classifier (a line intersection of the whole solid per point) is asked
    // only in the bands. A midpoint within the smaller of the two crossings' faces' bands of the
    // first crossing is not asked of the mesh: a triangle there would lie within its band.
    for (std::size_t i = 0; i < crossings.size(); ++i) {
      const double ti = crossings[i].first;
      if (i + 1 == crossings.size()) return ti;
      const double mid = 0.5 * (ti + crossings[i + 1].first);
      if (mid - ti <= x->tolerance) continue;  // the same crossing, reported twice
      const double near_band = std::min(crossings[i].second, crossings[i + 1].second);
      const analysis::MeshSide::Side side = std::isfinite(near_band) && mid - ti > near_band
                                                ? mesh->side(geom, org + dir * mid, dir, *bands)
                                                : analysis::MeshSide::unknown;
      if (side == analysis::MeshSide::outside) return ti;
      if (side == analysis::MeshSide::inside) continue;
      if (!x->inside_loaded) x->inside.Load(l.faces->shape), x->inside_loaded = true;
      x->inside.Perform(line.Location().Translated(gp_Vec(line.Direction()) * mid), x->tolerance);
      if (x->inside.State() == TopAbs_OUT) return ti;
    }
    return std::nullopt;
  } catch (const Standard_Failure&) {
    return std::nullopt;
  }
}

CadSurfaces::CadSurfaces(std::vector<CadLink> links)
    : links_(std::move(links)),
      intersectors_(std::make_unique<Intersectors>()),
      classifiers_(std::make_unique<Classifiers>(links_)),
      hidden_(std::make_unique<HiddenFaces>(links_.size())),
      bands_(std::make_unique<MeshBands>(links_.size())),
      sizes_(std::make_unique<Sizes>(links_)) {
  folded_.resize(links_.size());
  for (std::size_t g = 0; g < links_.size(); ++g) {
    const CadLink& l = links_[g];
    if (l.empty()) continue;
    if (l.face.size() != l.uv.size() || l.face.size() != l.flags.size())
      throw std::invalid_argument("CadSurfaces: inconsistent link of geometry " + std::to_string(g));
    folded_[g].resize(l.flags.size());
    for (std::size_t t = 0; t < l.flags.size(); ++t) folded_[g][t] = (l.flags[t] & kTriangleFolded) != 0;
  }
}

bool CadSurfaces::any() const {
  return std::any_of(links_.begin(), links_.end(), [](const CadLink& l) { return !l.empty(); });
}

bool CadSurfaces::covers(std::uint32_t geom) const { return geom < links_.size() && !links_[geom].empty(); }

std::uint32_t CadSurfaces::face_of(std::uint32_t geom, std::uint32_t prim) const { return links_.at(geom).face.at(prim); }

std::span<const std::uint8_t> CadSurfaces::folded(std::uint32_t geom) const {
  if (geom >= folded_.size()) return {};
  return folded_[geom];
}

namespace {

// `size` caches Start::size of the triangle (negative until computed; the same value from any
// thread).
Start start_of(const CadLink& l, std::uint32_t prim, double b1, double b2, std::atomic<double>& size) {
  const CadFaces::Face& f = l.faces->faces.at(l.face.at(prim));
  const auto& uv = l.uv[prim];
  const double b0 = 1.0 - b1 - b2;
  Start s{&f, b0 * uv[0] + b1 * uv[2] + b2 * uv[4], b0 * uv[1] + b1 * uv[3] + b2 * uv[5], 0};
  s.size = size.load(std::memory_order_relaxed);
  if (!(s.size >= 0)) {
    gp_Pnt c[3];
    for (int k = 0; k < 3; ++k) c[k] = f.surface->Value(uv[std::size_t(2 * k)], uv[std::size_t(2 * k + 1)]);
    s.size = std::max({c[0].Distance(c[1]), c[1].Distance(c[2]), c[2].Distance(c[0])});
    size.store(s.size, std::memory_order_relaxed);
  }
  return s;
}

}  // namespace

// Foot point: Newton on the gradient of |S(u, v) - p|^2 / 2 (second derivatives included;
// Gauss-Newton where the Hessian is not positive definite).
std::optional<analysis::SurfacePoint> CadSurfaces::project(std::uint32_t geom, std::uint32_t prim, double b1,
                                                           double b2, Vec3d p) const {
  double u = 0, v = 0;
  return foot(geom, prim, b1, b2, p, u, v);
}

std::optional<analysis::NearestFacePoint> CadSurfaces::nearest_on_faces(std::uint32_t geom,
                                                                        std::span<const analysis::FaceStart> starts,
                                                                        Vec3d p) const {
  const CadLink& l = links_.at(geom);
  std::optional<analysis::NearestFacePoint> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const std::uint32_t face = l.face.at(starts[k].prim);
    bool seen = false;
    for (std::size_t j = 0; j < k && !seen; ++j) seen = l.face[starts[j].prim] == face;
    if (seen) continue;
    double u = 0, v = 0;
    const std::optional<analysis::SurfacePoint> q = foot(geom, starts[k].prim, starts[k].b1, starts[k].b2, p, u, v);
    if (!q) continue;
    wrap_periodic(l.faces->faces[face], u, v);
    if (classifiers_->state(links_, geom, face, u, v) == TopAbs_OUT) continue;
    const double d = length(q->point - p);
    if (d < best_d) best_d = d, best = analysis::NearestFacePoint{*q, k};
  }
  if (best && best_d <= BRep_Tool::Tolerance(l.faces->faces[l.face[starts[best->start].prim]].face))
    best->at.point = p;  // on the face already: it keeps its coordinates
  return best;
}

std::optional<analysis::SurfacePoint> CadSurfaces::foot(std::uint32_t geom, std::uint32_t prim, double b1, double b2,
                                                        Vec3d p, double& u_out, double& v_out) const {
  const Start s = start_of(links_.at(geom), prim, b1, b2, sizes_->of(geom, prim));
  const Geom_Surface& surf = *s.face->surface;
  double u = s.u, v = s.v;
  const gp_Pnt p0 = surf.Value(u, v);
  const double scale = std::max({1.0, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  const double tol = 1e-12 * scale;  // the step after it is far below (quadratic convergence)
  bool converged = false;
  gp_Pnt q;
  gp_Vec su, sv, suu, svv, suv;
  for (int i = 0; i < kMaxNewtonSteps; ++i) {
    surf.D2(u, v, q, su, sv, suu, svv, suv);
    const gp_Vec r(gp_Pnt(p.x, p.y, p.z), q);  // S - p
    const double gu = su.Dot(r), gv = sv.Dot(r);
    double a = su.Dot(su) + suu.Dot(r), b = su.Dot(sv) + suv.Dot(r), d = sv.Dot(sv) + svv.Dot(r);
    double det = a * d - b * b;
    if (!(a > 0 && det > 0)) {
      a = su.Dot(su), b = su.Dot(sv), d = sv.Dot(sv);
      det = a * d - b * b;
      if (!(det > 0)) return std::nullopt;
    }
    const double du = -(d * gu - b * gv) / det, dv = -(a * gv - b * gu) / det;
    u += du, v += dv;
    const double step = (su * du + sv * dv).Magnitude();
    if (step <= tol) {
      converged = true;
      break;
    }
  }
  const gp_Pnt target(p.x, p.y, p.z);
  auto plausible = [&](double uu, double vv) {
    if (!in_range(*s.face, uu, vv, 1e-3)) return false;
    const gp_Pnt at = surf.Value(uu, vv);
    return at.Distance(p0) <= 2 * s.size + at.Distance(target);
  };
  if (!converged || !plausible(u, v)) {
    // Newton failed (near a pole or a strongly curved patch): OpenCASCADE's projection on the
    // face's parameter range, the nearest solution.
    converged = false;
    try {
      GeomAPI_ProjectPointOnSurf proj(target, s.face->surface, s.face->umin, s.face->umax, s.face->vmin, s.face->vmax);
      if (proj.NbPoints() > 0) {
        proj.LowerDistanceParameters(u, v);
        converged = plausible(u, v);
      }
    } catch (const Standard_Failure&) {
      converged = false;
    }
    if (!converged) return std::nullopt;
  }
  u_out = u, v_out = v;
  surf.D1(u, v, q, su, sv);
  const gp_Vec n = su.Crossed(sv) * s.face->sign;
  const double len = n.Magnitude();
  if (!(len > 1e-12 * su.Magnitude() * sv.Magnitude()) || !(len > 0))
    return analysis::SurfacePoint{vec(q.XYZ()), Vec3d{}};  // a singular point: no normal
  return analysis::SurfacePoint{vec(q.XYZ()), vec(n.XYZ()) * (1.0 / len)};
}

// S(u, v) = org + t dir: Newton on (u, v, t) with the Jacobian [Su Sv -dir].
std::optional<analysis::SurfaceCrossing> CadSurfaces::intersect(std::uint32_t geom, std::uint32_t prim, double b1,
                                                                double b2, Vec3d org, Vec3d dir) const {
  const Start s = start_of(links_.at(geom), prim, b1, b2, sizes_->of(geom, prim));
  const Geom_Surface& surf = *s.face->surface;
  double u = s.u, v = s.v;
  const gp_Vec d(dir.x, dir.y, dir.z);
  const gp_Pnt o(org.x, org.y, org.z);
  gp_Pnt q = surf.Value(u, v);
  const gp_Pnt p0 = q;
  double t = gp_Vec(o, q).Dot(d) / d.SquareMagnitude();
  const double scale = std::max({1.0, std::abs(org.x), std::abs(org.y), std::abs(org.z)});
  const double tol = 1e-12 * scale;  // the step after it is far below (quadratic convergence)
  gp_Vec su, sv;
  bool converged = false;
  for (int i = 0; i < kMaxNewtonSteps; ++i) {
    surf.D1(u, v, q, su, sv);
    const gp_Vec f = gp_Vec(o, q) - d * t;  // S - org - t dir
    // Solve [su sv -d] x = -f by Cramer's rule.
    const gp_Vec m = d * -1.0;
    const double det = su.Dot(sv.Crossed(m));
    if (!(std::abs(det) > 0)) return std::nullopt;
    const gp_Vec rhs = f * -1.0;
    const double du = rhs.Dot(sv.Crossed(m)) / det;
    const double dv = su.Dot(rhs.Crossed(m)) / det;
    const double dt = su.Dot(sv.Crossed(rhs)) / det;
    u += du, v += dv, t += dt;
    const double step = (su * du + sv * dv).Magnitude() + std::abs(dt) * d.Magnitude();
    if (step <= tol) {
      converged = true;
      break;
    }
  }
  const double t0 = gp_Vec(o, p0).Dot(d) / d.SquareMagnitude();
  // The face's outward unit normal at (uu, vv), zero where undefined.
  auto normal_at = [&](double uu, double vv) {
    gp_Pnt pp;
    gp_Vec du, dv;
    surf.D1(uu, vv, pp, du, dv);
    const gp_Vec n = du.Crossed(dv) * s.face->sign;
    const double len = n.Magnitude();
    return len > 1e-12 * du.Magnitude() * dv.Magnitude() && len > 0 ? vec(n.XYZ()) * (1.0 / len) : Vec3d{};
  };
  // Inside the face's trim: a crossing of the untrimmed surface beyond the face's boundary is
  // not where the ray leaves (it left through a neighbour first).
  auto trim_state = [&](double uu, double vv) {
    wrap_periodic(*s.face, uu, vv);
    return classifiers_->state(links_, geom, links_[geom].face.at(prim), uu, vv);
  };
  if (converged && t > 0 && in_range(*s.face, u, v, 1e-3) &&
      surf.Value(u, v).Distance(p0) <= 2 * s.size + 1e-9 * scale) {
    const TopAbs_State state = trim_state(u, v);
    if (state == TopAbs_OUT) return std::nullopt;  // the caller asks the whole B-rep
    return analysis::SurfaceCrossing{t, normal_at(u, v), state == TopAbs_ON};
  }
  // Newton failed (near a pole, a grazing ray): OpenCASCADE's exact intersection of the line with
  // the face, the crossing nearest to the start. Rare, so the intersector is built here.
  try {
    IntCurvesFace_Intersector x(s.face->face, 1e-9 * scale);
    const double len = d.Magnitude();
    x.Perform(gp_Lin(o, gp_Dir(d)), 0, std::numeric_limits<double>::infinity());
    if (!x.IsDone()) return std::nullopt;
    std::optional<analysis::SurfaceCrossing> best;
    for (Standard_Integer i = 1; i <= x.NbPnt(); ++i) {
      const double w = x.WParameter(i) / len;
      if (!(w > 0) || x.Pnt(i).Distance(p0) > 2 * s.size + 1e-9 * scale) continue;
      if (!best || std::abs(w - t0) < std::abs(best->t - t0)) best = analysis::SurfaceCrossing{w, normal_at(x.UParameter(i), x.VParameter(i)), x.State(i) == TopAbs_ON};
    }
    return best;
  } catch (const Standard_Failure&) {
    return std::nullopt;
  }
}

void CadSurfaces::HiddenFaces::build(const CadLink& l, OfGeom& h) {
  const ShapeScale scale = scale_of(l.faces->shape);
  h.tolerance = 1e-9 * scale.size;
  h.margin = 1e-7 * scale.size;
  const double noise = 1e-9 * (scale.size + scale.max_abs);
  std::vector<std::uint8_t> planar(l.faces->faces.size());
  for (std::size_t f = 0; f < planar.size(); ++f)
    planar[f] = GeomAdaptor_Surface(l.faces->faces[f].surface).GetType() == GeomAbs_Plane;
  std::vector<std::optional<PatchPrism>> prisms(l.face.size());
  // Isolated: this runs inside the thickness loop's parallel_for, and a thread waiting here for
  // its helpers must not take another sample of that loop, which would wait on this once_flag.
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, prisms.size(), 1024), [&](const auto& range) {
      for (std::size_t t = range.begin(); t != range.end(); ++t) {
        if (planar[l.face[t]]) continue;
        try {
          prisms[t] = inward_patch_prism(l.faces->faces[l.face[t]], l.uv[t], noise);
        } catch (const Standard_Failure&) {
          prisms[t].reset();  // the surface cannot be evaluated there: nothing to intersect either
        }
        if (prisms[t]) prisms[t]->face = l.face[t];
      }
    });
  });
  std::vector<Vec3d> corners;
  std::vector<Tri> spans;
  for (const std::optional<PatchPrism>& p : prisms) {
    if (!p) continue;
    const auto first = std::uint32_t(corners.size());
    corners.push_back(p->box.lo);
    corners.push_back(p->box.hi);
    corners.push_back({p->box.lo.x, p->box.hi.y, p->box.lo.z});  // with lo and hi: the box's own box, never flat
    spans.push_back({first, first + 1, first + 2});
    h.prisms.push_back(*p);
  }
  if (spans.empty()) return;
  Scene scene;
  scene.add_mesh(std::move(corners), std::move(spans));
  h.boxes = build_wide_bvh<double>(scene);
}

std::optional<double> CadSurfaces::hidden_crossing(std::uint32_t geom, Vec3d org, Vec3d dir, double t_end,
                                                   std::uint32_t start_face, std::uint32_t end_face) const {
  if (!covers(geom)) return std::nullopt;
  HiddenFaces::OfGeom& h = hidden_->geoms[geom];
  std::call_once(h.built, [&] { HiddenFaces::build(links_[geom], h); });
  const double tmin = h.margin, tmax = t_end - h.margin;
  if (h.boxes.empty() || !(tmax > tmin)) return std::nullopt;
  const TraversalRay<double> ray = TraversalRay<double>::make(Ray{org, dir, tmin, tmax}, h.boxes.scene_max_abs);
  if (!ray.valid()) return std::nullopt;
  const Vec3d end = org + dir * t_end;
  auto holds = [&](const BBoxd& b, Vec3d p) {
    return p.x >= b.lo.x - h.margin && p.x <= b.hi.x + h.margin && p.y >= b.lo.y - h.margin &&
           p.y <= b.hi.y + h.margin && p.z >= b.lo.z - h.margin && p.z <= b.hi.z + h.margin;
  };
  // The faces whose dipping patches' prisms the segment passes through, each once.
  std::uint32_t met[8];
  std::size_t n_met = 0;
  bool overflow = false;
  auto crosses_box = [&](const BBoxd& b) { return box_overlaps(ray, slab(ray, b.lo, b.hi), tmin, tmax); };
  analysis::for_each_entered(h.boxes, hidden_->stacks.local(), crosses_box, [&](const Triangle<double>& tri) {
    const PatchPrism& p = h.prisms[tri.prim];
    double ta = tmin, tb = tmax;
    clip_to_prism(p, org, dir, ta, tb);
    if (!(ta <= tb)) return;
    const std::uint32_t face = p.face;
    if ((face == start_face && holds(p.box, org)) || (face == end_face && holds(p.box, end))) return;
    if (std::find(met, met + n_met, face) != met + n_met) return;
    if (n_met == std::size(met)) overflow = true;
    else met[n_met++] = face;
  });
  if (overflow) return tmin;  // more faces than kept: there may be one, and the whole B-rep decides
  const gp_Lin line(gp_Pnt(org.x, org.y, org.z), gp_Dir(dir.x, dir.y, dir.z));
  std::optional<double> first;
  auto& mine = hidden_->intersectors.local();
  for (std::size_t k = 0; k < n_met; ++k) {
    try {
      auto& x = mine[{geom, met[k]}];
      if (!x) x = std::make_unique<IntCurvesFace_Intersector>(links_[geom].faces->faces[met[k]].face, h.tolerance);
      x->Perform(line, tmin, tmax);
      if (!x->IsDone()) continue;
      for (Standard_Integer i = 1; i <= x->NbPnt(); ++i) {
        const double w = x->WParameter(i);
        if (w > tmin && w < tmax && !(first && *first <= w)) first = w;
      }
    } catch (const Standard_Failure&) {
      return tmin;  // undecided: the caller asks the whole B-rep
    }
  }
  return first;
}

std::shared_ptr<const CadSurfaces> cad_surfaces(const std::vector<LoadedFile>& files, std::size_t geometries) {
  std::vector<CadLink> links(geometries);
  bool any = false;
  for (const LoadedFile& f : files)
    for (std::size_t k = 0; k < f.cad.size() && f.first_geometry + k < geometries; ++k) {
      links[f.first_geometry + k] = f.cad[k];
      any = any || !f.cad[k].empty();
    }
  if (!any) return nullptr;
  return std::make_shared<CadSurfaces>(std::move(links));
}

}  // namespace pierce
