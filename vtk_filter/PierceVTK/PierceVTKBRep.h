#pragma once
// CAD input of the Pierce filters: the B-rep behind the solids vtkPierceCADReader read.
//
// The reader tags each cell with the link of its triangle to the B-rep it was tessellated from:
// BRepModel (the model's key in this process's registry, pierce/io/cad_registry.h), BRepSolid,
// BRepTriangle, BRepFace, BRepUV (the (u, v) of its corners on the face), and TessellationFolded. Cell arrays
// survive D3, block and surface extraction; field data would not.
//
// A solid is measured on its exact B-rep when every one of its cells carries the link, its model
// is still registered in this process, and every triangle is, bit for bit, the one it names as
// loaded (corners in order, face and (u, v): pierce::cad_triangle_hash), so nothing was moved,
// cut or remeshed after reading. Otherwise it is measured on
// its mesh, and a warning says why. Folded-triangle flags are used either way. Under MPI every
// rank's cells are gathered first, so each rank knows the links of the whole scene (a ray
// leaves through another rank's triangles) and a solid is on its B-rep on every rank or on none.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pierce {
class CadSurfaces;
}

namespace pierce_vtk {

class Distribution;
struct Surfaces;

struct CadInput {
  // Per scene geometry, 1 on its triangles the reader flagged as folded (one entry per triangle,
  // or none when its cells lack TessellationFolded), for ThicknessOptions::tessellation_flags;
  // empty when no solid has flags.
  std::vector<std::vector<std::uint8_t>> folded;
  std::shared_ptr<const pierce::CadSurfaces> exact;  // null when no solid is measured on its B-rep
  std::vector<std::string> warnings;                 // linked solids measured on their mesh, and why
};

// Collective under MPI.
CadInput FindCadInput(const Surfaces& surfaces, const Distribution& distribution);

}  // namespace pierce_vtk
