#pragma once
// CAD files through OpenCASCADE (library target pierce_cad, so pierce_core stays free of OCCT):
// STEP (.step .stp), IGES (.iges .igs) and BREP (.brep .brp). Every solid becomes one triangle
// mesh, tessellated with BRepMesh_IncrementalMesh and wound outward (faces with TopAbs_REVERSED
// orientation are flipped; a solid whose mesh encloses negative volume is turned right side out).
// STEP and IGES go through XDE (XCAF) so part and assembly names are kept: a solid is named by
// its assembly path, e.g. "bracket_assy/bolt", with "#2", "#3"... for repeated names.
#include <string>
#include <vector>

#include "pierce/scene.h"

namespace pierce {

struct TessellationOptions {
  // Maximum distance between the surface and its triangles, in model units (mm for STEP and
  // IGES, which OpenCASCADE converts to mm). 0: 0.1% of the model's bounding-box diagonal.
  double linear_deflection = 0;
  double angular_deflection_deg = 15;  // maximum angle between adjacent triangles' normals
};

struct CadSolid {
  std::string name;
  std::vector<Vec3d> vertices;  // welded: one per distinct position
  std::vector<Tri> triangles;
};

struct CadModel {
  std::vector<CadSolid> solids;
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
