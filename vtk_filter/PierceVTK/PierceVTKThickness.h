#pragma once
// vtkPierceThickness's conversions: results to VTK arrays on the solids' surfaces and to a
// per-solid statistics table.
#include <cstdint>
#include <string>
#include <vector>

#include "pierce/analysis/thickness.h"

class vtkFieldData;
class vtkTable;

namespace pierce_vtk {

class Distribution;
struct Surfaces;

// Point (per vertex) or cell (per face) arrays Thickness, Thin, ThicknessStatus, SolidId on each
// solid's surface, and BRepFaces when the result has them (CAD input on its B-rep: the faces
// sampled at the element, 2 or more at a vertex on an edge); Thickness becomes the active scalars.
// Distributed runs per vertex pass `coincident`: a point without a row of its own (one another
// rank measured, or a ghost point no triangle of this rank uses) takes a coincident point's row.
struct VertexOwners;
void AttachThickness(const pierce::analysis::ThicknessResult& result, Surfaces& surfaces,
                     const VertexOwners* coincident = nullptr);

// Field data: the region table, one tuple per Region id (thin regions, then thick ones):
// RegionThick, RegionSolid, RegionThickness, RegionArea, RegionSamples, RegionPoint, RegionExit; and
// ThicknessColorRange, the default colour range (default_color_range of the finite thickness
// values and options.min_thickness).
void WriteRegionTable(const pierce::analysis::ThicknessResult& result, const pierce::analysis::ThicknessOptions& options,
                      vtkFieldData* field);

// One row per solid: SolidId, Name, Elements, Valid, NoExit, NoNormal, Thin, Tessellation,
// OnBRep (1: measured on the exact B-rep), Min, Max, Mean and the percentiles as P<q> (one column
// per entry of `percentiles`).
void WriteThicknessTable(const std::vector<pierce::analysis::SolidThickness>& solids,
                         const std::vector<double>& percentiles, vtkTable* table);

// Distributed runs, per vertex: which rank measures each group of coincident vertices (the
// points along a cut belong to two ranks' pieces): the lowest rank whose triangles use it.
struct VertexOwners {
  std::vector<std::vector<std::uint32_t>> weld;   // per geometry: weld_by_position
  std::vector<std::vector<int>> owner;            // per geometry and group (its first vertex)
};
VertexOwners FindVertexOwners(const Surfaces& surfaces);

// Distributed runs: sample_mask selecting this rank's samples in the gathered scene: its
// triangles, or the vertex groups it owns (`owners`, per vertex), so that nothing is measured
// twice.
std::vector<std::vector<std::uint8_t>> OwnSampleMask(const Surfaces& surfaces, bool per_cell,
                                                     const VertexOwners& owners);

// Distributed runs: the union of every rank's OwnSampleMask, computed on each rank.
std::vector<std::vector<std::uint8_t>> AllSampleMask(const Surfaces& surfaces, bool per_cell,
                                                     const VertexOwners& owners);

// Distributed runs, collective: the whole map on every rank, as serial computes it (regions
// included), from each rank's `mine` (measured with its OwnSampleMask); `options` carry
// AllSampleMask. See pierce::analysis::assemble_thickness.
pierce::analysis::ThicknessResult AssembleThickness(const pierce::Accel& accel,
                                                    const pierce::analysis::ThicknessOptions& options,
                                                    const pierce::analysis::ThicknessResult& mine,
                                                    const Distribution& distribution);

// Distributed runs, collective: "samples measured per rank: a + b = n" (per vertex, a group of
// coincident vertices is one sample), for the run report.
std::string DescribeSampleSplit(const pierce::analysis::ThicknessResult& result, bool per_cell,
                                const VertexOwners& owners, const Distribution& distribution);

// Distributed runs, collective: the per-solid statistics of every rank's samples as attached to
// its surfaces (AttachThickness), on rank 0 (empty elsewhere). Per vertex, points of one solid at
// the same position count once (two ranks share the points along their cut).
std::vector<pierce::analysis::SolidThickness> GatherThicknessStatistics(
  const Surfaces& surfaces, bool per_cell, const pierce::analysis::ThicknessOptions& options,
  const Distribution& distribution);

}  // namespace pierce_vtk
