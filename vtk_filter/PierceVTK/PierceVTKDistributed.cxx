#include "PierceVTKDistributed.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <iomanip>
#include <map>
#include <sstream>
#include <tuple>
#include <unordered_set>
#include <utility>

#include <vtkAbstractArray.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommunicator.h>
#include <vtkDataObjectTree.h>
#include <vtkIdList.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPoints.h>
#include <vtkMultiProcessController.h>
#include <vtkOutputWindow.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include "PierceVTKSurfaces.h"
#include "pierce/error.h"

namespace pierce_vtk {
namespace {

template <typename T>
std::vector<T> AllGatherValues(vtkMultiProcessController* c, int size, const std::vector<T>& values,
                               std::vector<vtkIdType>* lengths_out) {
  const vtkIdType n = vtkIdType(values.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size));
  c->AllGather(&n, lengths.data(), 1);
  vtkIdType total = 0;
  for (int r = 0; r < size; ++r) {
    offsets[std::size_t(r)] = total;
    total += lengths[std::size_t(r)];
  }
  std::vector<T> all(static_cast<std::size_t>(total));
  if (total > 0) {
    T dummy{};
    c->AllGatherV(values.empty() ? &dummy : values.data(), all.data(), n, lengths.data(), offsets.data());
  }
  if (lengths_out) *lengths_out = std::move(lengths);
  return all;
}

// The key that puts a triangle back in serial order: its input cell's original id.
vtkDataArray* OriginalCellIds(vtkPolyData* surface) {
  vtkDataArray* ids = surface->GetCellData()->GetArray("vtkOriginalCellIds");
  if (!ids) ids = surface->GetCellData()->GetGlobalIds();
  return ids && ids->GetNumberOfComponents() == 1 ? ids : nullptr;
}

vtkIdType IdAt(vtkDataArray* ids, vtkIdType c) {
  if (auto* typed = vtkIdTypeArray::SafeDownCast(ids)) return typed->GetValue(c);
  return vtkIdType(ids->GetTuple1(c));
}

// Each triangle's original cell id and its rank among the triangles of that id: the triangles
// of one triangulated polygon share the id and follow each other. False (keys empty) without
// ids, or when an id comes back after other ids — two input cells with one id, as when the data
// was split into pieces before D3: the ids cannot restore the serial order.
bool OriginalKeys(vtkPolyData* surface, std::vector<vtkIdType>& keys, std::vector<vtkIdType>& seqs) {
  keys.clear();
  seqs.clear();
  vtkDataArray* ids = OriginalCellIds(surface);
  if (!ids) return false;
  const vtkIdType n = surface->GetNumberOfPolys();
  keys.resize(std::size_t(n));
  seqs.resize(std::size_t(n));
  std::unordered_set<vtkIdType> seen;
  seen.reserve(std::size_t(n));
  for (vtkIdType c = 0; c < n; ++c) {
    const vtkIdType key = IdAt(ids, c);
    keys[std::size_t(c)] = key;
    if (c > 0 && key == keys[std::size_t(c) - 1]) {
      seqs[std::size_t(c)] = seqs[std::size_t(c) - 1] + 1;
    } else if (!seen.insert(key).second) {
      keys.clear();
      seqs.clear();
      return false;
    }
  }
  return true;
}

// One rank's piece of one solid in the gathered buffers.
struct Piece {
  int rank = 0;
  vtkIdType points = 0, triangles = 0;
  bool has_ids = false;
  bool from_volume = false;
  std::size_t point_begin = 0;  // in the gathered coordinates (3 doubles a point)
  std::size_t id_begin = 0;     // in the gathered triangle records (5 ids a triangle)
};

struct GlobalSolid {
  std::string name;
  std::vector<Piece> pieces;  // in rank order
};

constexpr vtkIdType kHeaderFields = 5;  // flat index, points, triangles, has ids, from a volume
constexpr vtkIdType kTriFields = 5;     // a, b, c, original id, rank within that id

}  // namespace

double ReplicatedBytes(std::uint64_t points, std::uint64_t triangles) {
  // Scene (24 B a vertex, 13 B a triangle), exchange buffers (24 B a point, 40 B a triangle),
  // the ordering records (48 B a triangle) and the BVH (about 64 B a triangle).
  return double(points) * 48.0 + double(triangles) * (13.0 + 40.0 + 48.0 + 64.0);
}

Distribution::Distribution() {
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  const char* no_gather = std::getenv("PIERCE_VTK_NO_GATHER");
  if (c && c->GetNumberOfProcesses() > 1 && !(no_gather && std::string(no_gather) == "1")) {
    this->Controller = c;
    this->Rank = c->GetLocalProcessId();
    this->Size = c->GetNumberOfProcesses();
  }
}

bool Distribution::AllTrue(bool ok) const {
  if (!this->Distributed()) return ok;
  const int mine = ok ? 1 : 0;
  int all = 0;
  this->Controller->AllReduce(&mine, &all, 1, vtkCommunicator::MIN_OP);
  return all == 1;
}

double Distribution::Max(double value) const {
  if (!this->Distributed()) return value;
  double all = value;
  this->Controller->AllReduce(&value, &all, 1, vtkCommunicator::MAX_OP);
  return all;
}

vtkIdType Distribution::ExclusiveSum(vtkIdType value) const {
  if (!this->Distributed()) return 0;
  const std::vector<vtkIdType> all = this->AllGather(std::vector<vtkIdType>{value});
  vtkIdType sum = 0;
  for (int r = 0; r < this->Rank; ++r) sum += all[std::size_t(r)];
  return sum;
}

std::vector<double> Distribution::AllGather(const std::vector<double>& values) const {
  if (!this->Distributed()) return values;
  return AllGatherValues(this->Controller, this->Size, values, nullptr);
}

std::vector<vtkIdType> Distribution::AllGather(const std::vector<vtkIdType>& values,
                                               std::vector<vtkIdType>* lengths) const {
  if (!this->Distributed()) {
    if (lengths) *lengths = {vtkIdType(values.size())};
    return values;
  }
  return AllGatherValues(this->Controller, this->Size, values, lengths);
}

std::vector<char> Distribution::AllGather(const std::vector<char>& values) const {
  if (!this->Distributed()) return values;
  return AllGatherValues(this->Controller, this->Size, values, nullptr);
}

std::vector<double> Distribution::GatherToRoot(const std::vector<double>& values) const {
  if (!this->Distributed()) return values;
  const vtkIdType n = vtkIdType(values.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(this->Size)), offsets(static_cast<std::size_t>(this->Size));
  this->Controller->AllGather(&n, lengths.data(), 1);
  vtkIdType total = 0;
  for (int r = 0; r < this->Size; ++r) {
    offsets[std::size_t(r)] = total;
    total += lengths[std::size_t(r)];
  }
  std::vector<double> all(this->IsRoot() ? std::size_t(total) : 0);
  if (total > 0) {
    double dummy = 0;
    this->Controller->GatherV(values.empty() ? &dummy : values.data(), all.empty() ? &dummy : all.data(), n,
                              lengths.data(), offsets.data(), 0);
  }
  return all;
}

namespace {
// The table with its own column arrays (writers may share them with other outputs).
void DetachColumns(vtkTable* table) {
  auto copy = vtkSmartPointer<vtkTable>::New();
  copy->DeepCopy(table);
  table->ShallowCopy(copy);
}
}  // namespace

void Distribution::KeepTableOnRoot(vtkTable* table) const {
  if (!this->Distributed() || this->IsRoot()) return;
  DetachColumns(table);
  table->SetNumberOfRows(0);
}

void Distribution::GatherTableRows(vtkTable* table) const {
  if (!this->Distributed()) return;
  std::vector<vtkSmartPointer<vtkDataObject>> tables;
  this->Controller->Gather(table, tables, 0);
  DetachColumns(table);
  if (!this->IsRoot()) {
    table->SetNumberOfRows(0);
    return;
  }
  for (std::size_t r = 1; r < tables.size(); ++r) {
    auto* other = vtkTable::SafeDownCast(tables[r]);
    if (!other || other->GetNumberOfRows() == 0) continue;
    const vtkIdType at = table->GetNumberOfRows();
    for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c) {
      vtkAbstractArray* column = table->GetColumn(c);
      vtkAbstractArray* from = other->GetColumnByName(column->GetName());
      if (from) column->InsertTuples(at, other->GetNumberOfRows(), 0, from);
    }
  }
}

bool Distribution::ExtractSurfaces(vtkDataObject* input, double max_replicated_mb, bool orient_outward, Surfaces& out,
                                   std::string& error, std::string& info) const {
  info.clear();
  if (!this->Distributed()) return pierce_vtk::ExtractSurfaces(input, out, error, orient_outward);
  out = Surfaces{};
  out.distributed = true;
  out.rank = this->Rank;

  // This rank's solids, without ghost cells; an empty piece is fine.
  std::vector<Solid> local;
  std::string local_error;
  const bool ok = CollectSolids(input, local, out.warnings, local_error, true, true);
  if (!this->AllTrue(ok)) {
    error = ok ? "another rank could not read its piece of the input (see its message)" : local_error;
    return false;
  }

  // Headers and names first, so that every rank knows the size before the geometry moves.
  std::vector<vtkIdType> header;
  std::vector<char> names;
  std::vector<std::vector<vtkIdType>> keys(local.size()), seqs(local.size());
  for (std::size_t s = 0; s < local.size(); ++s) {
    vtkPolyData* surface = local[s].surface;
    const bool has_ids = OriginalKeys(surface, keys[s], seqs[s]);
    header.insert(header.end(), {vtkIdType(local[s].flat_index), surface->GetNumberOfPoints(),
                                 surface->GetNumberOfPolys(), has_ids ? 1 : 0, local[s].from_volume ? 1 : 0});
    names.insert(names.end(), local[s].name.begin(), local[s].name.end());
    names.push_back('\0');
  }
  std::vector<vtkIdType> header_lengths;
  const std::vector<vtkIdType> headers = this->AllGather(header, &header_lengths);
  const std::vector<char> all_names = this->AllGather(names);

  std::map<unsigned int, GlobalSolid> solids;  // by flat index: serial solid order
  {
    std::size_t h = 0, name_at = 0, point_at = 0, id_at = 0;
    for (int r = 0; r < this->Size; ++r) {
      const std::size_t end = h + std::size_t(header_lengths[std::size_t(r)]);
      for (; h < end; h += kHeaderFields) {
        Piece piece;
        piece.rank = r;
        piece.points = headers[h + 1];
        piece.triangles = headers[h + 2];
        piece.has_ids = headers[h + 3] != 0;
        piece.from_volume = headers[h + 4] != 0;
        piece.point_begin = point_at;
        piece.id_begin = id_at;
        point_at += 3 * std::size_t(piece.points);
        id_at += std::size_t(kTriFields * piece.triangles);
        const std::string name(all_names.data() + name_at);
        name_at += name.size() + 1;
        GlobalSolid& solid = solids[unsigned(headers[h])];
        if (solid.pieces.empty()) solid.name = name;
        solid.pieces.push_back(piece);
      }
    }
  }
  std::uint64_t total_points = 0, total_triangles = 0;
  for (const auto& [flat, solid] : solids)
    for (const Piece& p : solid.pieces) {
      total_points += std::uint64_t(p.points);
      total_triangles += std::uint64_t(p.triangles);
    }
  const double mb = ReplicatedBytes(total_points, total_triangles) / 1e6;
  std::ostringstream size;
  size << "the replicated surface (" << solids.size() << " solids, " << total_triangles << " triangles, "
       << total_points << " points, gathered from " << this->Size << " ranks) takes about " << std::fixed
       << std::setprecision(1) << mb << " MB on every rank";
  if (max_replicated_mb > 0 && mb > max_replicated_mb) {
    std::ostringstream m;
    m << size.str() << ", more than the limit of " << max_replicated_mb
      << " MB (MaxReplicatedMB): not analysed. Raise the limit if the ranks have the memory, or use fewer ranks per "
         "node";
    error = m.str();
    return false;
  }
  if (solids.empty()) {
    error = "the input has no cells on any rank";
    return false;
  }
  // A volume split between ranks: each piece's boundary includes the cut, which is no surface
  // of the solid. Refuse rather than measure walls that are not there.
  for (const auto& [flat, solid] : solids) {
    int volume_pieces = 0;
    for (const Piece& p : solid.pieces) volume_pieces += p.from_volume ? 1 : 0;
    if (volume_pieces > 1) {
      const std::string label = vtkDataObjectTree::SafeDownCast(input) ? "block '" + solid.name + "'" : "the input";
      error = label + " is a volume (3D cells) split between " + std::to_string(volume_pieces) +
              " ranks: its pieces' boundaries include the cuts, which are no surface of the solid. Extract its surface "
              "where it is whole (Extract Surface before D3, or on data read on one rank), then spread that surface "
              "with D3";
      return false;
    }
  }
  info = size.str();

  // The geometry: every rank's points and triangles (a, b, c, original id, rank within the id).
  std::vector<double> points;
  std::vector<vtkIdType> tris;
  points.reserve(std::size_t(3 * total_points));
  tris.reserve(std::size_t(kTriFields) * std::size_t(total_triangles) / std::size_t(this->Size));
  for (std::size_t s = 0; s < local.size(); ++s) {
    vtkPolyData* surface = local[s].surface;
    const vtkIdType n_points = surface->GetNumberOfPoints();
    if (auto* xyz = vtkDoubleArray::SafeDownCast(surface->GetPoints()->GetData())) {
      points.insert(points.end(), xyz->GetPointer(0), xyz->GetPointer(0) + 3 * n_points);
    } else {
      for (vtkIdType i = 0; i < n_points; ++i) {
        double p[3];
        surface->GetPoint(i, p);
        points.insert(points.end(), {p[0], p[1], p[2]});
      }
    }
    vtkCellArray* polys = surface->GetPolys();
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c) {
      polys->GetCellAtId(c, npts, pts);
      const bool keyed = !keys[s].empty();
      tris.insert(tris.end(), {pts[0], pts[1], pts[2], keyed ? keys[s][std::size_t(c)] : 0,
                               keyed ? seqs[s][std::size_t(c)] : 0});
    }
    keys[s] = {};
    seqs[s] = {};
  }
  const std::vector<double> all_points = this->AllGather(points);
  const std::vector<vtkIdType> all_tris = this->AllGather(tris);
  points.clear();
  tris.clear();

  std::map<unsigned int, std::uint32_t> id_of_flat;
  struct Record {
    vtkIdType key, seq;
    int rank;
    vtkIdType cell;
    pierce::Tri tri;
  };
  for (const auto& [flat, solid] : solids) {
    const std::uint32_t g = std::uint32_t(id_of_flat.size());
    id_of_flat[flat] = g;
    std::vector<pierce::Vec3d> vertices;
    std::vector<Record> records;
    bool ids = true;
    std::map<int, std::uint32_t> own_offset;
    constexpr std::uint32_t kUnset = ~std::uint32_t(0);
    std::vector<std::uint32_t> rank_begin(std::size_t(this->Size) + 1, kUnset);
    for (const Piece& p : solid.pieces) {
      const std::uint32_t offset = std::uint32_t(vertices.size());
      rank_begin[std::size_t(p.rank)] = offset;
      if (p.rank == this->Rank) own_offset[p.rank] = offset;
      for (vtkIdType i = 0; i < p.points; ++i) {
        const double* x = all_points.data() + p.point_begin + 3 * std::size_t(i);
        vertices.push_back({x[0], x[1], x[2]});
      }
      ids = ids && p.has_ids;
      for (vtkIdType c = 0; c < p.triangles; ++c) {
        const vtkIdType* t = all_tris.data() + p.id_begin + std::size_t(kTriFields * c);
        records.push_back({t[3], t[4], p.rank, c,
                           {offset + std::uint32_t(t[0]), offset + std::uint32_t(t[1]), offset + std::uint32_t(t[2])}});
      }
    }
    auto by_id = [](const Record& a, const Record& b) {
      return std::tie(a.key, a.seq, a.rank, a.cell) < std::tie(b.key, b.seq, b.rank, b.cell);
    };
    if (ids) {
      std::sort(records.begin(), records.end(), by_id);
      for (std::size_t i = 1; i < records.size() && ids; ++i)
        ids = !(records[i].key == records[i - 1].key && records[i].seq == records[i - 1].seq);
    }
    const std::string label = vtkDataObjectTree::SafeDownCast(input) ? "block '" + solid.name + "'" : "input";
    if (!ids) {
      // No usable original ids: an order that depends on the geometry only.
      auto corners = [&](const Record& r) {
        std::array<double, 9> c;
        for (int k = 0; k < 3; ++k) {
          const pierce::Vec3d& v = vertices[r.tri[std::size_t(k)]];
          c[std::size_t(3 * k)] = v.x;
          c[std::size_t(3 * k + 1)] = v.y;
          c[std::size_t(3 * k + 2)] = v.z;
        }
        return c;
      };
      std::sort(records.begin(), records.end(), [&](const Record& a, const Record& b) {
        const auto ca = corners(a), cb = corners(b);
        if (ca != cb) return ca < cb;
        return std::tie(a.rank, a.cell) < std::tie(b.rank, b.cell);
      });
      if (this->IsRoot())
        out.warnings.push_back(label +
                               ": no original cell ids that are unique across the ranks (vtkOriginalCellIds from D3 "
                               "of data read on one rank, or cell GlobalIds): triangles ordered by position. The "
                               "results are exact and the same on any number of ranks, but can differ from a serial "
                               "run in the last bits where hits tie");
    }
    rank_begin[std::size_t(this->Size)] = std::uint32_t(vertices.size());
    for (int r = this->Size - 1; r >= 0; --r)  // ranks without a piece: empty blocks
      if (rank_begin[std::size_t(r)] == kUnset) rank_begin[std::size_t(r)] = rank_begin[std::size_t(r) + 1];
    out.rank_vertex_begin.push_back(std::move(rank_begin));
    std::vector<pierce::Tri> triangles;
    triangles.reserve(records.size());
    for (const Record& r : records) triangles.push_back(r.tri);
    if (orient_outward && SignedVolume(vertices, triangles) < 0.0) {
      for (pierce::Tri& t : triangles) std::swap(t[1], t[2]);
      if (this->IsRoot())
        out.warnings.push_back(label + " faces inward (negative volume): analysed with its triangles flipped");
    }
    // This rank's piece: its cells' places in the global order.
    for (Solid& s : local) {
      if (s.flat_index != flat) continue;
      s.id = g;
      s.vertex_offset = own_offset.count(this->Rank) ? own_offset[this->Rank] : 0;
      s.prim_of_cell.assign(std::size_t(s.surface->GetNumberOfPolys()), 0);
      for (std::size_t i = 0; i < records.size(); ++i)
        if (records[i].rank == this->Rank) s.prim_of_cell[std::size_t(records[i].cell)] = std::uint32_t(i);
    }
    try {
      out.scene.add_mesh(std::move(vertices), std::move(triangles), solid.name, label);
    } catch (const pierce::InputError& e) {
      error = e.what();  // the same on every rank: every rank has the same scene
      return false;
    }
  }
  out.solids = std::move(local);
  return true;
}

void ReportDistributedRun(const std::string& filter, const Distribution& distribution, const std::string& info,
                          const StageTimer& timer) {
  const char* timing = std::getenv("PIERCE_VTK_TIMING");
  if (!distribution.Distributed() && !(timing && std::string(timing) == "1")) return;
  std::ostringstream m;
  if (distribution.Distributed())
    m << filter << " on " << distribution.GetSize() << " ranks: " << info << "; times of the slowest rank:";
  else
    m << filter << " in one process; times:";
  const char* sep = " ";
  for (const StageTimer::Times& t : timer.Stages()) {
    m << sep << t.name << ' ' << std::setprecision(4) << distribution.Max(t.wall) << " s (CPU "
      << distribution.Max(t.cpu) << " s)";
    sep = ", ";
  }
  if (distribution.IsRoot()) vtkOutputWindowDisplayText((m.str() + "\n").c_str());
}

}  // namespace pierce_vtk
