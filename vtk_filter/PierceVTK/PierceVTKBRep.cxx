#include "PierceVTKBRep.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKSurfaces.h"
#include "pierce/io/cad_registry.h"
#include "pierce/io/cad_surfaces.h"

namespace pierce_vtk {

namespace {

// One cell's record, as doubles (gathered under MPI): geometry, triangle, flags (kHasLink,
// kHasFolded, kFolded), model key (< 2^52, exact in a double), solid, triangle in the solid as
// loaded, face, (u, v) of 3 corners.
constexpr std::size_t kFields = 13;
constexpr int kHasLink = 1, kHasFolded = 2, kFolded = 4;

struct CellArrays {
  vtkDataArray* model = nullptr;
  vtkDataArray* solid = nullptr;
  vtkDataArray* triangle = nullptr;
  vtkDataArray* face = nullptr;
  vtkDataArray* uv = nullptr;
  vtkDataArray* folded = nullptr;

  explicit CellArrays(vtkPolyData* surface) {
    vtkCellData* cells = surface->GetCellData();
    const vtkIdType n = surface->GetNumberOfCells();
    auto get = [&](const char* name, int components) -> vtkDataArray* {
      vtkDataArray* a = cells->GetArray(name);
      return a && a->GetNumberOfComponents() == components && a->GetNumberOfTuples() == n ? a : nullptr;
    };
    model = get("BRepModel", 1);
    solid = get("BRepSolid", 1);
    triangle = get("BRepTriangle", 1);
    face = get("BRepFace", 1);
    uv = get("BRepUV", 6);
    folded = get("TessellationFolded", 1);
  }
  bool Linked() const { return model && solid && triangle && face && uv; }
  bool Any() const { return Linked() || folded; }
};

// This rank's records (every cell of the solids that carry any of the arrays).
std::vector<double> LocalRecords(const Surfaces& surfaces) {
  std::vector<double> records;
  for (const Solid& solid : surfaces.solids) {
    const CellArrays arrays(solid.surface);
    if (!arrays.Any()) continue;
    for (vtkIdType c = 0; c < solid.surface->GetNumberOfCells(); ++c) {
      int flags = 0;
      std::array<double, kFields - 3> link{};
      if (arrays.Linked()) {
        flags |= kHasLink;
        link[0] = arrays.model->GetTuple1(c);
        link[1] = arrays.solid->GetTuple1(c);
        link[2] = arrays.triangle->GetTuple1(c);
        link[3] = arrays.face->GetTuple1(c);
        arrays.uv->GetTuple(c, link.data() + 4);
      }
      if (arrays.folded) flags |= kHasFolded | (arrays.folded->GetTuple1(c) != 0 ? kFolded : 0);
      records.insert(records.end(), {double(solid.id), double(PrimOfCell(solid, c)), double(flags)});
      records.insert(records.end(), link.begin(), link.end());
    }
  }
  return records;
}

// One geometry's cells as gathered.
struct GeometryLink {
  std::size_t linked = 0, with_folded = 0;
  bool one_model = true;  // every linked cell names the same model and solid
  double model = 0, solid = 0;
  std::vector<std::int64_t> loaded_triangle;  // per triangle, BRepTriangle
  pierce::CadLink link;
};

// A geometry as the warnings name it.
std::string Label(const pierce::Geometry& geometry) {
  return geometry.name.empty() ? std::string("the input") : "'" + geometry.name + "'";
}

// Whether geometry `g`'s link can be used; if not, why (empty when it has no link at all).
bool UseLink(const Surfaces& surfaces, std::uint32_t g, GeometryLink& gl, std::string& why) {
  const pierce::Geometry& geometry = surfaces.scene.geometry(g);
  const std::size_t n = geometry.triangles.size();
  const std::string name = Label(geometry);
  if (gl.linked == 0) return false;
  if (gl.linked < n || !gl.one_model) {
    why = name +
          ": only some of its cells carry one B-rep link (BRepModel, BRepSolid, BRepTriangle, BRepFace, BRepUV), "
          "as after merging it with other data: measured on its mesh";
    return false;
  }
  const std::shared_ptr<const pierce::RegisteredCadModel> model =
    pierce::registered_cad_model(static_cast<std::int64_t>(gl.model));
  if (!model) {
    why = name + ": its B-rep is not loaded in this process (the model the Pierce CAD reader read has been released, "
                 "or the data were read by another process): measured on its mesh. Read the file again with the "
                 "Pierce CAD reader to measure on the B-rep";
    return false;
  }
  if (!(gl.solid >= 0 && gl.solid < double(model->solids.size())) || !model->solids[std::size_t(gl.solid)].faces) {
    why = name + ": its BRepSolid does not name a solid of its model: measured on its mesh";
    return false;
  }
  const pierce::RegisteredCadModel::Solid& loaded = model->solids[std::size_t(gl.solid)];
  std::size_t unlinked = 0;
  for (std::size_t t = 0; t < n; ++t) {
    const std::int64_t k = gl.loaded_triangle[t];
    const pierce::Tri& tri = geometry.triangles[t];
    const std::array<pierce::Vec3d, 3> corners{geometry.vertices[tri[0]], geometry.vertices[tri[1]],
                                               geometry.vertices[tri[2]]};
    unlinked += !(k >= 0 && std::size_t(k) < loaded.triangle_hash.size() &&
                  pierce::cad_triangle_hash(corners, gl.link.face[t], gl.link.uv[t]) ==
                    loaded.triangle_hash[std::size_t(k)]);
  }
  gl.link.faces = loaded.faces;
  if (unlinked > 0) {
    why = name + ": " + std::to_string(unlinked) + " of its " + std::to_string(n) +
          " triangles no longer lie on the B-rep faces they were read from (moved, cut or remeshed after reading?): "
          "measured on its mesh";
    gl.link.faces = nullptr;
    return false;
  }
  return true;
}

}  // namespace

CadInput FindCadInput(const Surfaces& surfaces, const Distribution& distribution) {
  CadInput out;
  const std::vector<double> mine = LocalRecords(surfaces);
  if (distribution.AllTrue(mine.empty())) return out;  // no CAD input on any rank
  const std::vector<double> all = distribution.Distributed() ? distribution.AllGather(mine) : mine;

  const std::size_t n_geometries = surfaces.scene.geometries().size();
  std::vector<GeometryLink> links(n_geometries);
  for (std::size_t g = 0; g < n_geometries; ++g) {
    const std::size_t n = surfaces.scene.geometry(std::uint32_t(g)).triangles.size();
    links[g].link.face.assign(n, 0);
    links[g].link.uv.assign(n, {});
    links[g].link.flags.assign(n, 0);
    links[g].loaded_triangle.assign(n, -1);
  }
  for (std::size_t r = 0; r + kFields <= all.size(); r += kFields) {
    const double* x = all.data() + r;
    const auto g = std::size_t(x[0]), prim = std::size_t(x[1]);
    const int flags = int(x[2]);
    if (g >= n_geometries || prim >= links[g].link.flags.size()) continue;
    GeometryLink& gl = links[g];
    if (flags & kHasFolded) {
      ++gl.with_folded;
      gl.link.flags[prim] = (flags & kFolded) ? pierce::kTriangleFolded : 0;
    }
    if (!(flags & kHasLink)) continue;
    if (gl.linked++ == 0) {
      gl.model = x[3];
      gl.solid = x[4];
    }
    gl.one_model = gl.one_model && x[3] == gl.model && x[4] == gl.solid;
    gl.loaded_triangle[prim] = std::int64_t(x[5]);
    gl.link.face[prim] = x[6] >= 0 && x[6] < 4294967296.0 ? std::uint32_t(x[6]) : 0;
    std::copy(x + 7, x + 13, gl.link.uv[prim].begin());
  }

  // Fold flags where every cell of a geometry has them (the link's flags hold them either way).
  std::vector<std::vector<std::uint8_t>> folded(n_geometries);
  bool any_folded = false;
  for (std::size_t g = 0; g < n_geometries; ++g) {
    const std::vector<std::uint8_t>& flags = links[g].link.flags;
    if (flags.empty() || links[g].with_folded != flags.size()) continue;
    folded[g].reserve(flags.size());
    for (const std::uint8_t f : flags) folded[g].push_back((f & pierce::kTriangleFolded) ? 1 : 0);
    any_folded = true;
  }
  if (any_folded) out.folded = std::move(folded);

  // Each geometry on its B-rep on every rank or on none (a rank may lack the registered model).
  std::vector<char> usable(n_geometries, 0);
  std::vector<std::string> why(n_geometries);
  for (std::size_t g = 0; g < n_geometries; ++g)
    usable[g] = UseLink(surfaces, std::uint32_t(g), links[g], why[g]) ? 1 : 0;
  std::vector<char> everywhere = usable;
  if (distribution.Distributed()) {
    const std::vector<char> every_rank = distribution.AllGather(usable);
    for (std::size_t k = 0; k < every_rank.size(); ++k) everywhere[k % n_geometries] &= every_rank[k];
  }
  std::vector<pierce::CadLink> final_links(n_geometries);
  bool any = false;
  for (std::size_t g = 0; g < n_geometries; ++g) {
    if (everywhere[g]) {
      final_links[g] = std::move(links[g].link);
      any = true;
    } else if (usable[g]) {
      why[g] = Label(surfaces.scene.geometry(std::uint32_t(g))) +
               ": its B-rep is not loaded on every rank: measured on its mesh";
    }
    if (!why[g].empty()) out.warnings.push_back(why[g]);
  }
  if (any) out.exact = std::make_shared<pierce::CadSurfaces>(std::move(final_links));
  return out;
}

}  // namespace pierce_vtk
