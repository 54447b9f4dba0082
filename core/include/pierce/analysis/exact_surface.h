#pragma once
// The exact surfaces behind a tessellated model, as thickness analyses ask them: for CAD input
// (STEP, IGES, BREP) every triangle lies on one B-rep face and knows the (u, v) of its corners
// there. The core knows this interface only; the OpenCASCADE implementation is in pierce_cad
// (pierce/io/cad_surfaces.h), so pierce_core stays free of OpenCASCADE.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pierce/vec3.h"

namespace pierce::analysis {

struct SurfacePoint {
  Vec3d point;   // on the exact surface
  Vec3d normal;  // unit, outward of the solid
};

struct SurfaceCrossing {
  double t;      // along the line
  Vec3d normal;  // unit outward normal of the face there (zero where undefined)
  // On the face's boundary (a B-rep edge): whether the line leaves the solid there depends on
  // the neighbouring faces too.
  bool on_boundary = false;
};

// Where a search for the nearest face point starts: triangle `prim` at barycentrics (b1, b2) of
// its corners 1 and 2.
struct FaceStart {
  std::uint32_t prim = 0;
  double b1 = 0, b2 = 0;
};

struct NearestFacePoint {
  SurfacePoint at;
  std::size_t start = 0;  // the index in the starts of the face it lies on
};

// How far the closed mesh of a solid may lie from its B-rep, face by face: every point of
// triangle `prim`, and every point it passes on the way to its exact patch, lies within
// band[face[prim]] of the triangle. So a point farther than that from every triangle lies on the
// same side of the mesh and of the B-rep.
struct MeshBands {
  std::span<const std::uint32_t> face;  // per triangle of the geometry: its B-rep face
  std::span<const double> band;         // per face, finite
  double largest = 0;                   // of `band`
};

// Where a point lies against the closed mesh of a solid, as the caller of exact_exit can tell from
// its own exact traversal: a cheaper answer than the exact solid's classifier, used by exact_exit
// only where the two provably agree (the point farther from every triangle than that triangle's
// face's band). One object per thread.
class MeshSide {
 public:
  enum Side : int { unknown = -1, outside = 0, inside = 1 };
  virtual ~MeshSide() = default;
  // Whether `p` lies inside the mesh of geometry `geom`: its winding number along `dir` (unit),
  // counted by an exact kernel. unknown when a triangle of the geometry lies within its own face's
  // band of `p`, or the winding number is neither 0 nor 1.
  virtual Side side(std::uint32_t geom, Vec3d p, Vec3d dir, const MeshBands& bands) const = 0;
};

// Every call is const and may run on many threads at once.
class ExactSurfaces {
 public:
  virtual ~ExactSurfaces() = default;

  // Whether geometry `geom` is a tessellated exact model known here (false for meshes).
  virtual bool covers(std::uint32_t geom) const = 0;
  // The exact face triangle `prim` lies on (an index within its geometry).
  virtual std::uint32_t face_of(std::uint32_t geom, std::uint32_t prim) const = 0;
  // Per triangle, nonzero where the tessellation folds there (see cad_io.h, TriangleFlag).
  virtual std::span<const std::uint8_t> folded(std::uint32_t geom) const = 0;
  // The point of the face of triangle `prim` nearest to `p`, by Newton steps on the surface from
  // the triangle's (u, v) at barycentrics (b1, b2) of its corners 1 and 2, with the face's unit
  // outward normal there (zero where it is undefined: a singular point such as a cone's apex).
  // nullopt when no foot point is found.
  virtual std::optional<SurfacePoint> project(std::uint32_t geom, std::uint32_t prim, double b1, double b2,
                                              Vec3d p) const = 0;
  // The point of the B-rep nearest to `p` on the faces of the triangles in `starts` (each face
  // searched once, by Newton steps from its first start's (u, v); a foot outside its face's trim
  // does not count), with the face's unit outward normal there. A `p` that lies on that face
  // within the B-rep's tolerance is returned unchanged (its normal from the face). nullopt when
  // no face gives a foot point.
  virtual std::optional<NearestFacePoint> nearest_on_faces(std::uint32_t geom, std::span<const FaceStart> starts,
                                                           Vec3d p) const = 0;
  // The t > 0 where the line org + t dir crosses the face of triangle `prim`, by Newton steps on
  // (u, v, t) from the triangle's (u, v) at barycentrics (b1, b2), the crossing nearest to that
  // start; nullopt when there is none near it.
  virtual std::optional<SurfaceCrossing> intersect(std::uint32_t geom, std::uint32_t prim, double b1, double b2,
                                                   Vec3d org, Vec3d dir) const = 0;
  // The fallback when the mesh gives no answer (no exit found, the refinement failed, a glancing
  // exit): the smallest t > tmin where the line org + t dir (dir unit) leaves the exact solid of
  // geometry `geom` for its outside, from an exact intersection with every face; nullopt when
  // there is none. Touching a face (tangent to it, or running in it) is not leaving: a ray from a
  // rim down the face below it stays on the boundary, then inside, and leaves where the material
  // ends. Much slower than intersect(): for the rare samples that need it. With `mesh` (the
  // geometry's mesh is closed), a point between two crossings is classified by the mesh wherever
  // it lies farther from every triangle than the triangle's face may deviate from it (MeshBands);
  // the exact solid's classifier decides the others.
  virtual std::optional<double> exact_exit(std::uint32_t geom, Vec3d org, Vec3d dir, double tmin,
                                           const MeshSide* mesh = nullptr) const = 0;
  // The smallest t in (0, t_end) where the line org + t dir (dir unit) crosses a face of
  // geometry `geom` where the face bulges into the solid beyond its triangles (a hole's wall, a
  // concave blend): such a crossing can lie within the facets' sagitta, so the mesh shows none (a
  // line through a hole's rim a hair inside its circle passes between the chords and the arc).
  // nullopt when there is none. Faces that bulge out of the solid, and planes, hide no crossing.
  // Crossings within 1e-7 of the solid's size of either end are not reported, and near its ends
  // the line is not checked against the face it starts on (org on start_face, left about along
  // its normal) and the face it ends on (org + t_end dir on end_face, met at a non-glancing angle):
  // within a facet's sagitta of there it cannot cross them again. kInvalidId: no such face.
  virtual std::optional<double> hidden_crossing(std::uint32_t geom, Vec3d org, Vec3d dir, double t_end,
                                                std::uint32_t start_face, std::uint32_t end_face) const = 0;
};

}  // namespace pierce::analysis
