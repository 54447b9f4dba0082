#include "PierceVTKSurfaces.h"

#include <cmath>
#include <map>
#include <utility>
#include <sstream>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellTypes.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataObjectTree.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include "pierce/error.h"

namespace pierce_vtk {
namespace {

// Keeps only the 3-point cells of an already triangulated surface (vtkTriangleFilter passes
// degenerate polygons with fewer points through), with their cell data.
vtkSmartPointer<vtkPolyData> KeepTriangles(vtkPolyData* in, std::size_t& dropped) {
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(in->GetPoints());
  out->GetPointData()->PassData(in->GetPointData());
  out->GetFieldData()->PassData(in->GetFieldData());
  auto tris = vtkSmartPointer<vtkCellArray>::New();
  out->GetCellData()->CopyAllocate(in->GetCellData(), in->GetNumberOfPolys());
  const vtkIdType polys_begin = in->GetNumberOfVerts() + in->GetNumberOfLines();
  vtkCellArray* polys = in->GetPolys();
  auto ids = vtkSmartPointer<vtkIdList>::New();
  dropped = std::size_t(in->GetNumberOfCells() - in->GetNumberOfPolys());
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c) {
    polys->GetCellAtId(c, ids);
    if (ids->GetNumberOfIds() != 3) {
      ++dropped;
      continue;
    }
    const vtkIdType id = tris->InsertNextCell(ids);
    out->GetCellData()->CopyData(in->GetCellData(), polys_begin + c, id);
  }
  out->SetPolys(tris);
  return out;
}

bool IsTriangleSurface(vtkPolyData* pd) {
  return pd->GetNumberOfVerts() == 0 && pd->GetNumberOfLines() == 0 && pd->GetNumberOfStrips() == 0 &&
         pd->GetPolys()->IsHomogeneous() == 3;
}

// The triangles of one data set; nullptr when it has no cells at all. Fails on a data set that
// has cells but no surface ones (only vertices and lines).
bool Triangulate(vtkDataObject* data, const std::string& label, vtkSmartPointer<vtkPolyData>& result,
                 std::vector<std::string>& warnings, std::string& error) {
  result = nullptr;
  vtkSmartPointer<vtkPolyData> poly = vtkPolyData::SafeDownCast(data);
  if (!poly) {
    auto* ds = vtkDataSet::SafeDownCast(data);
    if (!ds) {
      error = label + " is a " + data->GetClassName() + ", not a data set with surfaces";
      return false;
    }
    if (ds->GetNumberOfCells() == 0) return true;
    auto surface = vtkSmartPointer<vtkDataSetSurfaceFilter>::New();
    surface->SetInputData(ds);
    surface->Update();
    poly = surface->GetOutput();
  }
  if (poly->GetNumberOfCells() == 0 || poly->GetNumberOfPoints() == 0) return true;
  const vtkIdType surface_cells = poly->GetNumberOfPolys() + poly->GetNumberOfStrips();
  if (surface_cells == 0) {
    std::ostringstream m;
    m << label << " has no polygons (" << poly->GetNumberOfVerts() << " vertex cells, " << poly->GetNumberOfLines()
      << " line cells): the analyses need triangulated surfaces";
    error = m.str();
    return false;
  }
  if (IsTriangleSurface(poly)) {
    result = vtkSmartPointer<vtkPolyData>::New();
    result->ShallowCopy(poly);
    return true;
  }
  auto triangulate = vtkSmartPointer<vtkTriangleFilter>::New();
  triangulate->SetInputData(poly);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  result = triangulate->GetOutput();
  std::size_t dropped = 0;
  if (!IsTriangleSurface(result)) result = KeepTriangles(result, dropped);
  const vtkIdType ignored = poly->GetNumberOfVerts() + poly->GetNumberOfLines() + vtkIdType(dropped);
  if (ignored > 0) {
    std::ostringstream m;
    m << label << ": " << ignored << " vertex, line or degenerate polygon cells ignored";
    warnings.push_back(m.str());
  }
  return true;
}

bool FindNonFinitePoint(vtkPolyData* pd, const std::string& label, std::string& error) {
  double p[3];
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i) {
    pd->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      std::ostringstream m;
      m << label << ": point " << i << " has a non-finite coordinate (" << p[0] << ", " << p[1] << ", " << p[2]
        << ")";
      error = m.str();
      return true;
    }
  }
  return false;
}

bool AddSolid(Surfaces& out, Solid solid, const std::string& label, bool orient_outward, std::string& error) {
  vtkPolyData* surface = solid.surface;
  std::vector<pierce::Vec3d> vertices(std::size_t(surface->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i) {
    double p[3];
    surface->GetPoint(i, p);
    vertices[std::size_t(i)] = {p[0], p[1], p[2]};
  }
  std::vector<pierce::Tri> triangles;
  triangles.reserve(std::size_t(surface->GetNumberOfPolys()));
  vtkCellArray* polys = surface->GetPolys();
  auto ids = vtkSmartPointer<vtkIdList>::New();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c) {
    polys->GetCellAtId(c, ids);
    triangles.push_back({std::uint32_t(ids->GetId(0)), std::uint32_t(ids->GetId(1)), std::uint32_t(ids->GetId(2))});
  }
  if (orient_outward && SignedVolume(vertices, triangles) < 0.0) {
    for (pierce::Tri& t : triangles) std::swap(t[1], t[2]);
    out.warnings.push_back(label + " faces inward (negative volume): analysed with its triangles flipped");
  }
  try {
    out.scene.add_mesh(std::move(vertices), std::move(triangles), solid.name, label);
  } catch (const pierce::InputError& e) {
    error = e.what();
    return false;
  }
  solid.id = std::uint32_t(out.solids.size());
  out.solids.push_back(std::move(solid));
  return true;
}

vtkSmartPointer<vtkDataObjectTreeIterator> LeafIterator(vtkDataObjectTree* tree) {
  vtkSmartPointer<vtkDataObjectTreeIterator> it;
  it.TakeReference(tree->NewTreeIterator());
  it->VisitOnlyLeavesOn();
  it->SkipEmptyNodesOn();
  it->TraverseSubTreeOn();
  return it;
}

// Whether a data set has 3D cells (its surface is then a boundary the filter extracts).
bool HasVolumeCells(vtkDataObject* data) {
  auto* ds = vtkDataSet::SafeDownCast(data);
  if (!ds || vtkPolyData::SafeDownCast(ds) || ds->GetNumberOfCells() == 0) return false;
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(ds)) {
    vtkUnsignedCharArray* types = grid->GetDistinctCellTypesArray();
    for (vtkIdType i = 0; types && i < types->GetNumberOfTuples(); ++i)
      if (vtkCellTypes::GetDimension(types->GetValue(i)) == 3) return true;
    return false;
  }
  // Structured data sets have one cell type.
  return vtkCellTypes::GetDimension(static_cast<unsigned char>(ds->GetCellType(0))) == 3;
}

// The surface without the cells vtkGhostType flags as duplicate or hidden (points unchanged).
vtkSmartPointer<vtkPolyData> DropGhostCells(vtkPolyData* in) {
  vtkDataArray* ghosts = in->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  if (!ghosts) return in;
  const int flags = vtkDataSetAttributes::DUPLICATECELL | vtkDataSetAttributes::HIDDENCELL;
  bool any = false;
  for (vtkIdType c = 0; c < in->GetNumberOfCells() && !any; ++c) any = (int(ghosts->GetTuple1(c)) & flags) != 0;
  if (!any) return in;
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(in->GetPoints());
  out->GetPointData()->PassData(in->GetPointData());
  out->GetFieldData()->PassData(in->GetFieldData());
  auto tris = vtkSmartPointer<vtkCellArray>::New();
  auto kept = vtkSmartPointer<vtkIdList>::New();
  auto to = vtkSmartPointer<vtkIdList>::New();
  vtkCellArray* polys = in->GetPolys();
  tris->AllocateEstimate(polys->GetNumberOfCells(), 3);
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c) {
    if ((int(ghosts->GetTuple1(c)) & flags) != 0) continue;
    polys->GetCellAtId(c, npts, pts);
    to->InsertNextId(tris->InsertNextCell(npts, pts));
    kept->InsertNextId(c);
  }
  out->GetCellData()->CopyAllocate(in->GetCellData(), kept->GetNumberOfIds());
  out->GetCellData()->CopyData(in->GetCellData(), kept, to);
  out->SetPolys(tris);
  out->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  return out;
}

}  // namespace

// Divergence theorem; negative for a closed surface with inward-facing (clockwise) winding.
double SignedVolume(const std::vector<pierce::Vec3d>& v, const std::vector<pierce::Tri>& tris) {
  if (v.empty()) return 0.0;
  const pierce::Vec3d o = v.front();  // relative coordinates: no cancellation far from the origin
  double six_volume = 0.0;
  for (const pierce::Tri& t : tris) six_volume += pierce::dot(v[t[0]] - o, pierce::cross(v[t[1]] - o, v[t[2]] - o));
  return six_volume / 6.0;
}

bool CollectSolids(vtkDataObject* input, std::vector<Solid>& solids, std::vector<std::string>& warnings,
                   std::string& error, bool allow_empty, bool drop_ghost_cells) {
  solids.clear();
  if (!input) {
    error = "no input";
    return false;
  }
  auto add = [&](vtkSmartPointer<vtkPolyData> surface, std::string name, unsigned int flat, const std::string& label,
                 vtkDataObject* source) {
    if (drop_ghost_cells) surface = DropGhostCells(surface);
    if (FindNonFinitePoint(surface, label, error)) return false;
    Solid solid;
    solid.surface = surface;
    solid.name = std::move(name);
    solid.flat_index = flat;
    solid.from_volume = drop_ghost_cells && HasVolumeCells(source);  // distributed runs only
    solids.push_back(std::move(solid));
    return true;
  };
  if (auto* tree = vtkDataObjectTree::SafeDownCast(input)) {
    std::string first_problem;
    auto it = LeafIterator(tree);
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
      const unsigned int flat = it->GetCurrentFlatIndex();
      std::string name;
      if (it->HasCurrentMetaData() && it->GetCurrentMetaData()->Has(vtkCompositeDataSet::NAME()))
        name = it->GetCurrentMetaData()->Get(vtkCompositeDataSet::NAME());
      if (name.empty()) name = "block " + std::to_string(flat);
      const std::string label = "block '" + name + "'";
      vtkSmartPointer<vtkPolyData> surface;
      std::string problem;
      if (!Triangulate(it->GetCurrentDataObject(), label, surface, warnings, problem)) {
        // A composite input may mix solids with curves or points: skip those blocks.
        warnings.push_back(problem + "; block skipped");
        if (first_problem.empty()) first_problem = problem;
        continue;
      }
      if (!surface) continue;
      if (!add(surface, name, flat, label, it->GetCurrentDataObject())) return false;
    }
    if (solids.empty() && !allow_empty) {
      error = first_problem.empty() ? "the composite input has no cells" : first_problem;
      return false;
    }
    return true;
  }
  if (vtkDataSet::SafeDownCast(input) == nullptr) {
    error = std::string("unsupported input type ") + input->GetClassName();
    return false;
  }
  vtkSmartPointer<vtkPolyData> surface;
  if (!Triangulate(input, "input", surface, warnings, error)) return false;
  if (!surface) {
    if (allow_empty) return true;
    error = "the input has no cells";
    return false;
  }
  return add(surface, "", 0, "input", input);
}

bool ExtractSurfaces(vtkDataObject* input, Surfaces& out, std::string& error, bool orient_outward) {
  out = Surfaces{};
  std::vector<Solid> solids;
  if (!CollectSolids(input, solids, out.warnings, error, false, false)) return false;
  for (Solid& solid : solids) {
    const std::string label = vtkDataObjectTree::SafeDownCast(input) ? "block '" + solid.name + "'" : "input";
    if (!AddSolid(out, std::move(solid), label, orient_outward, error)) return false;
  }
  return true;
}

vtkSmartPointer<vtkDataObject> NewSurfaceOutput(vtkDataObject* input) {
  if (vtkDataObjectTree::SafeDownCast(input)) return vtkSmartPointer<vtkDataObject>::Take(input->NewInstance());
  if (vtkDataSet::SafeDownCast(input)) return vtkSmartPointer<vtkPolyData>::New();
  return nullptr;
}

int RequestSurfaceDataObject(vtkInformationVector** input, vtkInformationVector* output) {
  vtkDataObject* in = vtkDataObject::GetData(input[0], 0);
  if (!in) return 0;
  vtkInformation* out_info = output->GetInformationObject(0);
  vtkDataObject* current = vtkDataObject::GetData(out_info);
  vtkSmartPointer<vtkDataObject> wanted = NewSurfaceOutput(in);
  if (!wanted) return 0;
  if (!current || std::string(current->GetClassName()) != wanted->GetClassName())
    out_info->Set(vtkDataObject::DATA_OBJECT(), wanted);
  if (output->GetNumberOfInformationObjects() > 1) {
    vtkInformation* table_info = output->GetInformationObject(1);
    if (!vtkTable::GetData(table_info)) table_info->Set(vtkDataObject::DATA_OBJECT(), vtkSmartPointer<vtkTable>::New());
  }
  return 1;
}

void StoreSurfaces(const Surfaces& surfaces, vtkDataObject* input, vtkDataObject* output) {
  if (auto* out_poly = vtkPolyData::SafeDownCast(output)) {
    if (!surfaces.solids.empty()) out_poly->ShallowCopy(surfaces.solids.front().surface);
    return;
  }
  auto* in_tree = vtkDataObjectTree::SafeDownCast(input);
  auto* out_tree = vtkDataObjectTree::SafeDownCast(output);
  if (!in_tree || !out_tree) return;
  out_tree->CopyStructure(in_tree);
  std::map<unsigned int, const Solid*> by_flat;
  for (const Solid& s : surfaces.solids) by_flat[s.flat_index] = &s;
  auto it = LeafIterator(in_tree);
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
    const auto found = by_flat.find(it->GetCurrentFlatIndex());
    if (found != by_flat.end()) {
      out_tree->SetDataSet(it, found->second->surface);
    } else {
      out_tree->SetDataSet(it, vtkSmartPointer<vtkPolyData>::New());
    }
  }
}

void AddSolidNames(const Surfaces& surfaces, vtkFieldData* field_data) {
  auto names = vtkSmartPointer<vtkStringArray>::New();
  names->SetName("SolidNames");
  for (const pierce::Geometry& g : surfaces.scene.geometries()) names->InsertNextValue(g.name);
  field_data->AddArray(names);
}

}  // namespace pierce_vtk
