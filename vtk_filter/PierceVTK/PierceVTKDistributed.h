#pragma once
// The Pierce filters under MPI (pvbatch, pvserver): geometry replicated, samples split.
//
// Every rank holds a piece of the input. Pierce's analyses are global queries (a thickness ray
// leaves through triangles another rank holds), so each rank gathers the whole surface, builds
// the same scene and BVH, and traces only its own samples; tables are reduced to rank 0.
//
// The gathered scene reproduces the serial one: solids are the input's non-empty leaves on any
// rank, in flat-index order (one solid for a data set), as in serial; each solid's triangles are
// put back in serial order by their original cell ids (the vtkOriginalCellIds array D3 writes,
// else the cell GlobalIds attribute; the triangles of one triangulated polygon keep their
// order). Ghost cells (vtkGhostType) are left out, so every triangle comes from exactly one
// rank. Triangle vertices are welded by position by the kernels, as in serial. When the ids are
// missing or repeat across ranks (the data was split before D3, e.g. by a source that makes
// pieces), the triangles are ordered by their coordinates instead, with a warning: the results
// are then exact and the same for any number of ranks, but may differ from a serial run in the
// last bits where two hits tie.
//
// One rank, no MPI controller, or the debug variable PIERCE_VTK_NO_GATHER=1: every rank
// analyses its own piece alone (serial behaviour; wrong under MPI, kept to test the tests).
#include <cstdint>
#include <string>
#include <vector>

#include <vtkType.h>

#include "PierceVTKStageTimer.h"

class vtkDataObject;
class vtkMultiProcessController;
class vtkTable;

namespace pierce_vtk {

struct Surfaces;

class Distribution {
public:
  Distribution();

  bool Distributed() const { return this->Size > 1; }
  int GetRank() const { return this->Rank; }
  int GetSize() const { return this->Size; }
  bool IsRoot() const { return this->Rank == 0; }

  // Collective: true on every rank when `ok` is true on every rank.
  bool AllTrue(bool ok) const;
  // Collective: the largest value over the ranks.
  double Max(double value) const;
  // Collective: the sum of the values of the ranks before this one.
  vtkIdType ExclusiveSum(vtkIdType value) const;
  // Collective: every rank's values, concatenated in rank order, on every rank
  // (`lengths`, when given, receives each rank's count).
  std::vector<double> AllGather(const std::vector<double>& values) const;
  std::vector<vtkIdType> AllGather(const std::vector<vtkIdType>& values, std::vector<vtkIdType>* lengths = nullptr) const;
  std::vector<char> AllGather(const std::vector<char>& values) const;
  // Collective: every rank's values, concatenated in rank order, on rank 0 (empty elsewhere).
  std::vector<double> GatherToRoot(const std::vector<double>& values) const;
  // Collective: the rows of every rank's table appended in rank order on rank 0; the other
  // ranks keep the columns with no rows (ParaView appends the ranks' tables on delivery).
  void GatherTableRows(vtkTable* table) const;
  // A table every rank computed in full: its rows kept on rank 0 only.
  void KeepTableOnRoot(vtkTable* table) const;

  // Collective: the surfaces of the whole input on every rank (see the top of this file), with
  // `solids` this rank's pieces. Refuses (false, `error` naming the size) when the replicated
  // surface would take more than `max_replicated_mb` MB per rank (<= 0: no limit). `info`
  // reports the replicated size. With `orient_outward`, solids of negative volume are flipped
  // in the scene (see ExtractSurfaces). In serial, ExtractSurfaces.
  bool ExtractSurfaces(vtkDataObject* input, double max_replicated_mb, bool orient_outward, Surfaces& out,
                       std::string& error, std::string& info) const;

private:
  vtkMultiProcessController* Controller = nullptr;
  int Rank = 0;
  int Size = 1;
};

// Distributed runs, collective: rank 0 prints `info` and the stage times of the slowest rank to
// the output window ("<filter> on N ranks: ...; gather 0.1 s (CPU 0.1 s), ..."). In serial only with
// PIERCE_VTK_TIMING=1 (for benchmarks; "gather" is then the surface extraction).
void ReportDistributedRun(const std::string& filter, const Distribution& distribution, const std::string& info,
                          const StageTimer& timer);

// Bytes per rank of a replicated surface: scene, exchange buffers and BVH.
double ReplicatedBytes(std::uint64_t points, std::uint64_t triangles);

}  // namespace pierce_vtk
