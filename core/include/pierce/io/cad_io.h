#pragma once
// CAD files through OpenCASCADE (library target pierce_cad, so pierce_core stays free of OCCT):
// STEP (.step .stp), IGES (.iges .igs) and BREP (.brep .brp). Every solid becomes one triangle
// mesh, tessellated with BRepMesh_IncrementalMesh and wound outward (faces with TopAbs_REVERSED
// orientation are flipped; a solid whose mesh encloses negative volume is turned right side out).
// STEP and IGES go through XDE (XCAF) so part and assembly names are kept: a solid is named by
// its assembly path, e.g. "bracket_assy/bolt", with "#2", "#3"... for repeated names.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pierce/scene.h"

namespace pierce {

struct TessellationOptions {
  // Maximum distance between the surface and its triangles, in model units (mm for STEP and
  // IGES, which OpenCASCADE converts to mm). 0: 0.1% of the model's bounding-box diagonal.
  double linear_deflection = 0;
  double angular_deflection_deg = 15;  // maximum angle between adjacent triangles' normals
  // A solid whose tessellation folds (see TessellationCheck) is meshed again, finer, up to this
  // many times; 0: folds are only flagged.
  int fold_remesh_rounds = 3;
  // Triangle edges longer than this (model units) are split at their midpoints after the check,
  // so that large flat faces, which the mesher covers with a few big triangles, get samples
  // enough for a thickness map (conforming: a closed mesh stays closed; see cad_split.h). 0: no
  // splitting.
  double max_edge_length = 0;
};

// Per-triangle findings of the check against the B-rep (bits of CadLink::flags).
enum TriangleFlag : std::uint8_t {
  kTriangleFolded = 1,  // its normal points away from the B-rep face's normal (a fold)
  kTriangleSliver = 2,  // near-zero area: height below 1e-6 of its longest edge
};

// What the loader found comparing a solid's triangles with their B-rep faces. A triangle is
// folded when its normal makes more than 90 degrees with the face's normal at the triangle's
// centre (the UV mean of its nodes): the mesh turns back on itself there.
struct TessellationCheck {
  std::size_t faces = 0;            // B-rep faces of the solid
  std::size_t folded = 0;           // folded triangles in the final mesh (flagged)
  std::size_t slivers = 0;          // sliver triangles in the final mesh
  std::size_t folded_found = 0;     // folded triangles in the first tessellation
  std::size_t faces_folded = 0;     // faces with folds in the first tessellation
  std::size_t faces_remeshed = 0;   // faces tessellated again (all faces of the solid, per round)
  int remesh_rounds = 0;            // how often the solid was meshed again
  double final_deflection = 0;      // linear deflection of the final mesh
};

// The solid's B-rep faces (OpenCASCADE, opaque here; see cad_surfaces.h).
struct CadFaces;

// The link of each triangle to the B-rep: its face and the (u, v) of its corners there.
struct CadLink {
  std::vector<std::uint32_t> face;          // per triangle: index of its face in `faces`
  std::vector<std::array<double, 6>> uv;    // per triangle: u0, v0, u1, v1, u2, v2 of its corners
  std::vector<std::uint8_t> flags;          // per triangle: TriangleFlag bits
  TessellationCheck check;
  std::shared_ptr<const CadFaces> faces;    // kept alive by every copy

  bool empty() const { return faces == nullptr; }
};

struct CadSolid {
  std::string name;
  std::vector<Vec3d> vertices;  // welded: one per distinct position
  std::vector<Tri> triangles;
  CadLink link;  // one entry per triangle
};

// Where a CAD file's load spent its time (wall seconds): reading (parsing and converting to
// B-rep shapes, with the reader's checks), meshing (BRepMesh_IncrementalMesh, the fold
// remeshing included) and checking (the triangles against their faces, welding, orientation,
// storing the curves of edges on planar faces).
struct CadLoadTimes {
  double read = 0, mesh = 0, check = 0;
};

struct CadModel {
  std::vector<CadSolid> solids;
  CadLoadTimes times;
  std::string units;                  // "mm" (STEP, IGES) or "model units" (BREP)
  double linear_deflection = 0;       // the one used
  std::vector<std::string> warnings;  // skipped entities, faces without triangulation, shells
                                      // loaded as open surfaces...
};

// True for the extensions above (case-insensitive).
bool is_cad_file(const std::string& path);

// Throws InputError naming the file for a missing or unreadable file, an unsupported extension,
// a file OpenCASCADE cannot parse, or one without any surface to mesh. A file that is partly
// readable loads what it can and lists what was skipped in `warnings`.
CadModel load_cad_file(const std::string& path, const TessellationOptions& opts = {});

}  // namespace pierce
