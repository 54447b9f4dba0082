#pragma once
// The input surfaces of the Pierce filters as a pierce::Scene, one geometry per solid.
//
// A vtkPolyData is one solid; any other vtkDataSet is one solid through its outer surface
// (vtkDataSetSurfaceFilter); a composite data set (multiblock, partitioned collection) gives one
// solid per non-empty leaf, named after its block. Polygons and strips are triangulated
// (vtkTriangleFilter) and vertices and lines dropped, so each solid's `surface` holds triangles
// only; point ids are unchanged (scene vertex i = point i) and triangle j is the scene's prim j.
// The filters attach their results to these surfaces.
#include <cstdint>
#include <string>
#include <vector>

#include <vtkType.h>

#include <vtkSmartPointer.h>

#include "pierce/scene.h"

class vtkDataObject;
class vtkFieldData;
class vtkInformationVector;
class vtkPolyData;

namespace pierce_vtk {

struct Solid {
  vtkSmartPointer<vtkPolyData> surface;  // triangles only
  std::string name;
  unsigned int flat_index = 0;  // the leaf's flat index in a composite input (0 otherwise)
  std::uint32_t id = 0;         // the solid's geometry in `scene` (its SolidId)
  // Distributed runs (PierceVTKDistributed.h): `surface` is this rank's piece of geometry `id`
  // of the gathered scene; its point i is scene vertex vertex_offset + i and its cell c is scene
  // triangle prim_of_cell[c]. Empty in serial, where point i is vertex i and cell c triangle c.
  std::vector<std::uint32_t> prim_of_cell;
  std::uint32_t vertex_offset = 0;
  bool from_volume = false;  // distributed runs: the boundary of a data set with 3D cells
};

struct Surfaces {
  pierce::Scene scene;
  std::vector<Solid> solids;          // serial: solids[g] is the scene's geometry g
  std::vector<std::string> warnings;  // input parts that were ignored
  bool distributed = false;           // scene = the surfaces of all ranks, solids = this rank's
  // Distributed runs: per scene geometry, the first vertex of each rank's points (one entry per
  // rank and one past the end); rank r's triangles use vertices [begin[r], begin[r + 1]) only.
  std::vector<std::vector<std::uint32_t>> rank_vertex_begin;
  int rank = 0;
};

// Scene triangle of cell c of `solid`.
inline std::uint32_t PrimOfCell(const Solid& solid, vtkIdType c) {
  return solid.prim_of_cell.empty() ? std::uint32_t(c) : solid.prim_of_cell[std::size_t(c)];
}

// The triangulated solids of the input without building a scene (see ExtractSurfaces; the
// distributed extraction builds the scene from all ranks' solids). With `allow_empty`, an input
// without cells gives no solids instead of an error; with `drop_ghost_cells` (distributed runs),
// cells flagged in vtkGhostType (duplicate or hidden) are left out and solids extracted from data
// sets with 3D cells are marked `from_volume`. Points are checked to be finite.
bool CollectSolids(vtkDataObject* input, std::vector<Solid>& solids, std::vector<std::string>& warnings,
                   std::string& error, bool allow_empty, bool drop_ghost_cells);

// Enclosed volume of a triangle mesh (divergence theorem); negative for inward-facing winding.
double SignedVolume(const std::vector<pierce::Vec3d>& vertices, const std::vector<pierce::Tri>& triangles);

// Builds `out` from the filter's input. Returns false with `error` naming the block and the
// problem when there is nothing to analyse (no input, no cells, only vertices or lines) or the
// input is invalid (non-finite or out-of-range point coordinates).
// With `orient_outward`, solids whose enclosed volume is negative (inward-facing winding, as
// some exporters write) enter the scene with their triangles flipped; the surfaces stay as given.
bool ExtractSurfaces(vtkDataObject* input, Surfaces& out, std::string& error, bool orient_outward = false);

// The output data object for "input surfaces with result arrays": vtkPolyData for a data set,
// a new instance of the input's type for a composite data set (nullptr for other types).
vtkSmartPointer<vtkDataObject> NewSurfaceOutput(vtkDataObject* input);

// RequestDataObject of filters whose output 0 is NewSurfaceOutput(input 0) and whose output 1
// (when present) is a vtkTable. Returns 0 when the input type is not supported.
int RequestSurfaceDataObject(vtkInformationVector** input, vtkInformationVector* output);

// Fills `output` (made by NewSurfaceOutput) with the solids' surfaces: the polydata itself, or
// the input's composite structure with every solid's leaf replaced (empty leaves stay empty).
void StoreSurfaces(const Surfaces& surfaces, vtkDataObject* input, vtkDataObject* output);

// Field data array "SolidNames": the name of solid id i (scene geometry i) at index i.
void AddSolidNames(const Surfaces& surfaces, vtkFieldData* field_data);

}  // namespace pierce_vtk
