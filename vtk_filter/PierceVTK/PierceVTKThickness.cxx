#include "PierceVTKThickness.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <limits>
#include <set>
#include <tuple>
#include <utility>
#include <sstream>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdList.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKSurfaces.h"
#include "pierce/analysis/mesh_topology.h"

namespace pierce_vtk {

namespace pa = pierce::analysis;

void AttachThickness(const pa::ThicknessResult& result, Surfaces& surfaces, const VertexOwners* coincident) {
  const bool per_cell = result.per == pa::SampleAt::face;
  struct Arrays {
    vtkSmartPointer<vtkDoubleArray> thickness = vtkSmartPointer<vtkDoubleArray>::New();
    vtkSmartPointer<vtkUnsignedCharArray> thin = vtkSmartPointer<vtkUnsignedCharArray>::New();
    vtkSmartPointer<vtkUnsignedCharArray> status = vtkSmartPointer<vtkUnsignedCharArray>::New();
    vtkSmartPointer<vtkIntArray> solid = vtkSmartPointer<vtkIntArray>::New();
    vtkSmartPointer<vtkIntArray> region = vtkSmartPointer<vtkIntArray>::New();  // ThicknessResult::region
    vtkSmartPointer<vtkUnsignedCharArray> brep_faces;  // CAD input on its B-rep only
  };
  const bool with_brep_faces = !result.brep_faces.empty();
  std::vector<Arrays> arrays(surfaces.solids.size());
  for (std::size_t g = 0; g < surfaces.solids.size(); ++g) {
    vtkPolyData* surface = surfaces.solids[g].surface;
    const vtkIdType n = per_cell ? surface->GetNumberOfCells() : surface->GetNumberOfPoints();
    Arrays& a = arrays[g];
    a.thickness->SetName("Thickness");
    a.thin->SetName("Thin");
    a.status->SetName("ThicknessStatus");
    a.solid->SetName("SolidId");
    a.region->SetName("Region");
    a.region->SetNumberOfValues(n);
    a.region->Fill(-1);
    a.thickness->SetNumberOfValues(n);
    a.thin->SetNumberOfValues(n);
    a.status->SetNumberOfValues(n);
    a.solid->SetNumberOfValues(n);
    a.thickness->Fill(std::numeric_limits<double>::quiet_NaN());
    a.thin->Fill(0);
    a.status->Fill(static_cast<unsigned char>(pa::ThicknessStatus::no_normal));
    a.solid->Fill(static_cast<int>(surfaces.solids[g].id));
    if (with_brep_faces) {
      a.brep_faces = vtkSmartPointer<vtkUnsignedCharArray>::New();
      a.brep_faces->SetName("BRepFaces");
      a.brep_faces->SetNumberOfValues(n);
      a.brep_faces->Fill(0);
    }
  }
  // Result entries are (scene geometry, scene element); map them to this rank's solids.
  std::vector<int> local_of(surfaces.scene.geometries().size(), -1);
  for (std::size_t s = 0; s < surfaces.solids.size(); ++s) local_of[surfaces.solids[s].id] = int(s);
  std::vector<std::vector<vtkIdType>> cell_of_prim(surfaces.solids.size());  // distributed, per cell
  if (per_cell) {
    for (std::size_t s = 0; s < surfaces.solids.size(); ++s) {
      const Solid& solid = surfaces.solids[s];
      if (solid.prim_of_cell.empty()) continue;
      cell_of_prim[s].assign(surfaces.scene.geometry(solid.id).triangles.size(), -1);
      for (std::size_t c = 0; c < solid.prim_of_cell.size(); ++c) cell_of_prim[s][solid.prim_of_cell[c]] = vtkIdType(c);
    }
  }
  auto set_row = [&](Arrays& a, vtkIdType e, std::size_t i) {
    a.thickness->SetValue(e, result.thickness[i]);
    a.thin->SetValue(e, result.thin[i]);
    a.status->SetValue(e, static_cast<unsigned char>(result.status[i]));
    if (i < result.region.size()) a.region->SetValue(e, result.region[i]);
    if (with_brep_faces) a.brep_faces->SetValue(e, result.brep_faces[i]);
  };
  std::vector<std::vector<std::uint8_t>> has_row(surfaces.solids.size());
  for (std::size_t s = 0; s < surfaces.solids.size(); ++s) has_row[s].assign(std::size_t(arrays[s].thickness->GetNumberOfValues()), 0);
  for (std::size_t i = 0; i < result.size(); ++i) {
    const int s = local_of[result.solid[i]];
    if (s < 0) continue;
    const Solid& solid = surfaces.solids[std::size_t(s)];
    Arrays& a = arrays[std::size_t(s)];
    vtkIdType e = static_cast<vtkIdType>(result.element[i]);
    if (per_cell && !cell_of_prim[std::size_t(s)].empty()) {
      e = cell_of_prim[std::size_t(s)][std::size_t(e)];
    } else if (!per_cell) {
      e -= vtkIdType(solid.vertex_offset);
    }
    if (e < 0 || e >= a.thickness->GetNumberOfValues()) continue;  // another rank's element
    set_row(a, e, i);
    has_row[std::size_t(s)][std::size_t(e)] = 1;
  }
  if (coincident && !per_cell) {
    // Points whose sample another rank measured (along the cut) or that no triangle of this
    // rank uses (ghost points): the row of a coincident point, as serial gives every copy.
    std::vector<std::vector<std::uint32_t>> row_of_group(surfaces.scene.geometries().size());
    for (std::size_t i = 0; i < result.size(); ++i) {
      const std::uint32_t g = result.solid[i];
      std::vector<std::uint32_t>& rows = row_of_group[g];
      if (rows.empty()) rows.assign(surfaces.scene.geometry(g).vertices.size(), pierce::kInvalidId);
      std::uint32_t& row = rows[coincident->weld[g][result.element[i]]];
      if (row == pierce::kInvalidId) row = std::uint32_t(i);
    }
    for (std::size_t s = 0; s < surfaces.solids.size(); ++s) {
      const Solid& solid = surfaces.solids[s];
      const std::vector<std::uint32_t>& rows = row_of_group[solid.id];
      if (rows.empty()) continue;
      for (std::size_t e = 0; e < has_row[s].size(); ++e) {
        if (has_row[s][e]) continue;
        const std::uint32_t row = rows[coincident->weld[solid.id][solid.vertex_offset + e]];
        if (row != pierce::kInvalidId) set_row(arrays[s], vtkIdType(e), row);
      }
    }
  }
  for (std::size_t g = 0; g < surfaces.solids.size(); ++g) {
    vtkPolyData* surface = surfaces.solids[g].surface;
    vtkDataSetAttributes* data = per_cell ? static_cast<vtkDataSetAttributes*>(surface->GetCellData())
                                          : static_cast<vtkDataSetAttributes*>(surface->GetPointData());
    data->AddArray(arrays[g].thickness);
    data->AddArray(arrays[g].thin);
    data->AddArray(arrays[g].status);
    data->AddArray(arrays[g].solid);
    data->AddArray(arrays[g].region);
    if (arrays[g].brep_faces) data->AddArray(arrays[g].brep_faces);
    data->SetActiveScalars("Thickness");
  }
}

void WriteRegionTable(const pa::ThicknessResult& result, const pa::ThicknessOptions& options, vtkFieldData* field) {
  auto add = [&](auto array, const char* name, int components) {
    array->SetName(name);
    array->SetNumberOfComponents(components);
    field->AddArray(array);
    return array;
  };
  auto thick = add(vtkSmartPointer<vtkUnsignedCharArray>::New(), "RegionThick", 1);
  auto solid = add(vtkSmartPointer<vtkIntArray>::New(), "RegionSolid", 1);
  auto extreme = add(vtkSmartPointer<vtkDoubleArray>::New(), "RegionThickness", 1);
  auto area = add(vtkSmartPointer<vtkDoubleArray>::New(), "RegionArea", 1);
  auto samples = add(vtkSmartPointer<vtkIdTypeArray>::New(), "RegionSamples", 1);
  auto point = add(vtkSmartPointer<vtkDoubleArray>::New(), "RegionPoint", 3);
  auto exit = add(vtkSmartPointer<vtkDoubleArray>::New(), "RegionExit", 3);
  for (const auto* list : {&result.thin_regions, &result.thick_regions})
    for (const pa::ThicknessRegion& g : *list) {
      thick->InsertNextValue(g.thick ? 1 : 0);
      solid->InsertNextValue(static_cast<int>(g.solid));
      extreme->InsertNextValue(g.thickness);
      area->InsertNextValue(g.area);
      samples->InsertNextValue(static_cast<vtkIdType>(g.samples));
      point->InsertNextTuple3(g.point.x, g.point.y, g.point.z);
      exit->InsertNextTuple3(g.exit.x, g.exit.y, g.exit.z);
    }
  const auto [lo, hi] = pa::default_color_range(result.thickness, options.min_thickness);
  auto range = add(vtkSmartPointer<vtkDoubleArray>::New(), "ThicknessColorRange", 2);
  range->InsertNextTuple2(lo, hi);
}

void WriteThicknessTable(const std::vector<pa::SolidThickness>& solids, const std::vector<double>& percentile_list,
                         vtkTable* table) {
  auto column = [&](auto array, const std::string& name) {
    array->SetName(name.c_str());
    table->AddColumn(array);
    return array;
  };
  auto id = column(vtkSmartPointer<vtkIntArray>::New(), "SolidId");
  auto name = column(vtkSmartPointer<vtkStringArray>::New(), "Name");
  // The sample counts, in column order.
  static constexpr std::pair<const char*, std::size_t pa::SolidThickness::*> kCounts[] = {
      {"Elements", &pa::SolidThickness::elements}, {"Valid", &pa::SolidThickness::valid},
      {"NoExit", &pa::SolidThickness::no_exit},    {"NoNormal", &pa::SolidThickness::no_normal},
      {"Thin", &pa::SolidThickness::thin},         {"Tessellation", &pa::SolidThickness::tessellation}};
  std::vector<vtkSmartPointer<vtkIdTypeArray>> counts;
  for (const auto& count : kCounts) counts.push_back(column(vtkSmartPointer<vtkIdTypeArray>::New(), count.first));
  auto on_brep = column(vtkSmartPointer<vtkUnsignedCharArray>::New(), "OnBRep");
  // Min, Max, Mean and P<q> per percentile: NaN for a solid without a valid sample.
  std::vector<vtkSmartPointer<vtkDoubleArray>> statistics;
  for (const char* title : {"Min", "Max", "Mean"})
    statistics.push_back(column(vtkSmartPointer<vtkDoubleArray>::New(), title));
  for (const double q : percentile_list) {
    std::ostringstream n;
    n << 'P' << q;
    statistics.push_back(column(vtkSmartPointer<vtkDoubleArray>::New(), n.str()));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const pa::SolidThickness& s : solids) {
    id->InsertNextValue(static_cast<int>(s.geom));
    name->InsertNextValue(s.name);
    for (std::size_t k = 0; k < counts.size(); ++k)
      counts[k]->InsertNextValue(static_cast<vtkIdType>(s.*kCounts[k].second));
    on_brep->InsertNextValue(s.exact ? 1 : 0);
    std::vector<double> values{s.summary.min, s.summary.max, s.summary.mean};
    for (std::size_t k = 0; k < percentile_list.size(); ++k)
      values.push_back(k < s.summary.percentiles.size() ? s.summary.percentiles[k].second : nan);
    const bool any = s.summary.count > 0;
    for (std::size_t k = 0; k < statistics.size(); ++k) statistics[k]->InsertNextValue(any ? values[k] : nan);
  }
}

namespace {

// Per point of each solid: whether one of its triangles uses it.
std::vector<std::uint8_t> UsedPoints(vtkPolyData* surface) {
  std::vector<std::uint8_t> used(std::size_t(surface->GetNumberOfPoints()), 0);
  auto ids = vtkSmartPointer<vtkIdList>::New();
  vtkCellArray* polys = surface->GetPolys();
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c) {
    polys->GetCellAtId(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) used[std::size_t(ids->GetId(k))] = 1;
  }
  return used;
}

}  // namespace

namespace {
int RankOfVertex(const std::vector<std::uint32_t>& begin, std::uint32_t v) {
  return int(std::upper_bound(begin.begin(), begin.end(), v) - begin.begin()) - 1;
}
}  // namespace

VertexOwners FindVertexOwners(const Surfaces& surfaces) {
  VertexOwners o;
  const std::size_t n = surfaces.scene.geometries().size();
  o.weld.resize(n);
  o.owner.resize(n);
  for (std::size_t g = 0; g < n; ++g) {
    const pierce::Geometry& geo = surfaces.scene.geometry(std::uint32_t(g));
    const std::vector<std::uint32_t>& begin = surfaces.rank_vertex_begin[g];
    o.weld[g] = pa::weld_by_position(geo.vertices);
    o.owner[g].assign(geo.vertices.size(), std::numeric_limits<int>::max());
    for (const pierce::Tri& t : geo.triangles)
      for (const std::uint32_t v : t) {
        int& owner = o.owner[g][o.weld[g][v]];
        owner = std::min(owner, RankOfVertex(begin, v));
      }
  }
  return o;
}

std::vector<std::vector<std::uint8_t>> OwnSampleMask(const Surfaces& surfaces, bool per_cell,
                                                     const VertexOwners& owners) {
  std::vector<std::vector<std::uint8_t>> mask(surfaces.scene.geometries().size());
  for (std::size_t g = 0; g < mask.size(); ++g) {
    const pierce::Geometry& geo = surfaces.scene.geometry(std::uint32_t(g));
    mask[g].assign(per_cell ? geo.triangles.size() : geo.vertices.size(), 0);
  }
  for (const Solid& solid : surfaces.solids) {
    std::vector<std::uint8_t>& m = mask[solid.id];
    if (per_cell) {
      for (vtkIdType c = 0; c < solid.surface->GetNumberOfCells(); ++c) m[PrimOfCell(solid, c)] = 1;
    } else {
      const std::vector<std::uint8_t> used = UsedPoints(solid.surface);
      for (std::size_t i = 0; i < used.size(); ++i) {
        const std::uint32_t v = solid.vertex_offset + std::uint32_t(i);
        if (used[i] && owners.owner[solid.id][owners.weld[solid.id][v]] == surfaces.rank) m[v] = 1;
      }
    }
  }
  return mask;
}

std::vector<std::vector<std::uint8_t>> AllSampleMask(const Surfaces& surfaces, bool per_cell,
                                                     const VertexOwners& owners) {
  std::vector<std::vector<std::uint8_t>> mask(surfaces.scene.geometries().size());
  for (std::size_t g = 0; g < mask.size(); ++g) {
    const pierce::Geometry& geo = surfaces.scene.geometry(std::uint32_t(g));
    if (per_cell) {
      mask[g].assign(geo.triangles.size(), 1);  // every triangle comes from exactly one rank
      continue;
    }
    mask[g].assign(geo.vertices.size(), 0);
    const std::vector<std::uint32_t>& begin = surfaces.rank_vertex_begin[g];
    for (const pierce::Tri& t : geo.triangles)
      for (const std::uint32_t v : t)
        mask[g][v] = owners.owner[g][owners.weld[g][v]] == RankOfVertex(begin, v);
  }
  return mask;
}

pa::ThicknessResult AssembleThickness(const pierce::Accel& accel, const pa::ThicknessOptions& options,
                                      const pa::ThicknessResult& mine, const Distribution& distribution) {
  // Per row: solid, element, point, normal, thickness, status, B-rep faces, exit triangle (-1:
  // none). Every rank holds the whole scene, so triangle ids mean the same on all.
  constexpr std::size_t kFields = 12;
  std::vector<double> rows;
  rows.reserve(mine.size() * kFields);
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const pierce::Vec3d p = mine.point[i], n = mine.normal[i];
    rows.insert(rows.end(), {double(mine.solid[i]), double(mine.element[i]), p.x, p.y, p.z, n.x, n.y, n.z,
                             mine.thickness[i], double(mine.status[i]),
                             mine.brep_faces.empty() ? 0.0 : double(mine.brep_faces[i]),
                             mine.exit_triangle[i] == pierce::kInvalidId ? -1.0 : double(mine.exit_triangle[i])});
  }
  const std::vector<double> all = distribution.AllGather(rows);
  std::vector<pa::MeasuredSample> measured(all.size() / kFields);
  for (std::size_t r = 0; r < measured.size(); ++r) {
    const double* f = all.data() + r * kFields;
    pa::MeasuredSample& m = measured[r];
    m.solid = std::uint32_t(f[0]);
    m.element = std::uint32_t(f[1]);
    m.point = {f[2], f[3], f[4]};
    m.normal = {f[5], f[6], f[7]};
    m.thickness = f[8];
    m.status = static_cast<pa::ThicknessStatus>(int(f[9]));
    m.brep_faces = static_cast<std::uint8_t>(f[10]);
    m.exit_triangle = f[11] < 0 ? pierce::kInvalidId : std::uint32_t(f[11]);
  }
  return pa::assemble_thickness(accel, options, measured);
}

std::string DescribeSampleSplit(const pa::ThicknessResult& result, bool per_cell, const VertexOwners& owners,
                                const Distribution& distribution) {
  vtkIdType measured = 0;
  for (std::size_t i = 0; i < result.size(); ++i)
    measured += per_cell || owners.weld[result.solid[i]][result.element[i]] == result.element[i];
  const std::vector<vtkIdType> all = distribution.AllGather(std::vector<vtkIdType>{measured});
  std::ostringstream m;
  m << "samples measured per rank: ";
  vtkIdType sum = 0;
  for (std::size_t r = 0; r < all.size(); ++r) {
    m << (r ? " + " : "") << all[r];
    sum += all[r];
  }
  m << " = " << sum;
  return m.str();
}

std::vector<pa::SolidThickness> GatherThicknessStatistics(const Surfaces& surfaces, bool per_cell,
                                                          const pa::ThicknessOptions& options,
                                                          const Distribution& distribution) {
  // (solid, x, y, z, thickness, status, thin) per own sample.
  constexpr std::size_t kFields = 7;
  std::vector<double> mine;
  for (const Solid& solid : surfaces.solids) {
    vtkDataSetAttributes* data = per_cell ? static_cast<vtkDataSetAttributes*>(solid.surface->GetCellData())
                                          : static_cast<vtkDataSetAttributes*>(solid.surface->GetPointData());
    vtkDataArray* thickness = data->GetArray("Thickness");
    vtkDataArray* status = data->GetArray("ThicknessStatus");
    vtkDataArray* thin = data->GetArray("Thin");
    const std::vector<std::uint8_t> used = per_cell ? std::vector<std::uint8_t>{} : UsedPoints(solid.surface);
    const vtkIdType n = thickness ? thickness->GetNumberOfTuples() : 0;
    for (vtkIdType e = 0; e < n; ++e) {
      double x[3] = {0, 0, 0};
      if (!per_cell) {
        if (!used[std::size_t(e)]) continue;
        solid.surface->GetPoint(e, x);
      }
      mine.insert(mine.end(), {double(solid.id), x[0], x[1], x[2], thickness->GetTuple1(e), status->GetTuple1(e),
                               thin->GetTuple1(e)});
    }
  }
  const std::vector<double> all = distribution.GatherToRoot(mine);
  std::vector<pa::SolidThickness> solids;
  if (!distribution.IsRoot()) return solids;
  const std::size_t n_solids = surfaces.scene.geometries().size();
  std::vector<std::vector<double>> values(n_solids);
  solids.resize(n_solids);
  std::set<std::tuple<std::uint32_t, double, double, double>> seen;
  for (std::size_t i = 0; i + kFields <= all.size(); i += kFields) {
    const std::uint32_t g = std::uint32_t(all[i]);
    if (!per_cell && !seen.insert({g, all[i + 1], all[i + 2], all[i + 3]}).second) continue;
    pa::SolidThickness& st = solids[g];
    ++st.elements;
    const auto status = static_cast<pa::ThicknessStatus>(int(all[i + 5]));
    st.no_exit += status == pa::ThicknessStatus::no_exit;
    st.no_normal += status == pa::ThicknessStatus::no_normal;
    st.tessellation += status == pa::ThicknessStatus::tessellation;
    st.thin += all[i + 6] != 0;
    if (std::isfinite(all[i + 4])) values[g].push_back(all[i + 4]);
  }
  for (std::size_t g = 0; g < n_solids; ++g) {
    solids[g].geom = std::uint32_t(g);
    solids[g].name = surfaces.scene.geometry(std::uint32_t(g)).name;
    solids[g].valid = values[g].size();
    solids[g].exact = options.exact && options.exact->covers(std::uint32_t(g));
    solids[g].summary = pa::summarize(std::move(values[g]), options.percentiles, options.histogram_bins);
  }
  return solids;
}

}  // namespace pierce_vtk
