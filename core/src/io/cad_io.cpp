#include "pierce/io/cad_io.h"

// OpenCASCADE is built with signal conversion: with OSD::SetSignal's handlers installed, a crash
// inside it (malformed STEP files can dereference null placements) jumps to the nearest
// OCC_CATCH_SIGNALS and becomes a Standard_Failure.
#ifndef OCC_CONVERT_SIGNALS
#define OCC_CONVERT_SIGNALS
#endif

#include <BRepBndLib.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <IMeshTools_Parameters.hxx>
#include <gp_Pnt2d.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <OSD.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

#include <algorithm>
#include <chrono>
#include <array>
#include <cctype>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <tuple>
#include <numbers>

#include "cad_faces.h"
#include "cad_split.h"
#include "pierce/error.h"

namespace pierce {

namespace {

constexpr std::size_t kMaxListedProblems = 10;
constexpr std::uint32_t kInvalidIndex = ~std::uint32_t(0);
constexpr std::size_t kMaxSplitTriangles = 4'000'000;  // per solid: edge splitting stops there

enum class CadFormat { step, iges, brep, unknown };

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

CadFormat format_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".step" || ext == ".stp") return CadFormat::step;
  if (ext == ".iges" || ext == ".igs") return CadFormat::iges;
  if (ext == ".brep" || ext == ".brp") return CadFormat::brep;
  return CadFormat::unknown;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw InputError(path + ": " + what); }

std::string label_name(const TDF_Label& label) {
  Handle(TDataStd_Name) n;
  if (label.IsNull() || !label.FindAttribute(TDataStd_Name::GetID(), n)) return {};
  return TCollection_AsciiString(n->Get()).ToCString();  // UTF-8
}

std::string status_text(IFSelect_ReturnStatus s) {
  switch (s) {
    case IFSelect_RetVoid: return "no data found";
    case IFSelect_RetError: return "file could not be parsed";
    case IFSelect_RetFail: return "reading failed";
    case IFSelect_RetStop: return "reading stopped";
    default: return "unknown reader status";
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Collects solids as meshes, with the problems met on the way.
class Collector {
 public:
  Collector(std::string path, std::string stem, const TessellationOptions& opts)
      : path_(std::move(path)), stem_(std::move(stem)), opts_(opts) {}

  // The tessellation the shapes were meshed with (mesh_all), for meshing folded solids again.
  void set_tessellation(double deflection, double angle_rad) { deflection_ = deflection, angle_ = angle_rad; }

  // `proto` is the unlocated shape whose sub-shapes may carry names (XDE); `loc` places it.
  void add(const TopoDS_Shape& proto, const TopLoc_Location& loc, const std::string& name,
           const Handle(XCAFDoc_ShapeTool) & tool, const TDF_Label& label) {
    const std::string base = name.empty() ? stem_ : name;
    bool any = false;
    for (TopExp_Explorer ex(proto, TopAbs_SOLID); ex.More(); ex.Next()) {
      std::string n = base;
      TDF_Label sub;
      if (!tool.IsNull() && !label.IsNull() && tool->FindSubShape(label, ex.Current(), sub)) {
        const std::string sn = label_name(sub);
        if (!sn.empty()) n = base + "/" + sn;
      }
      mesh(ex.Current().Moved(loc), n, true);
      any = true;
    }
    for (TopExp_Explorer ex(proto, TopAbs_SHELL, TopAbs_SOLID); ex.More(); ex.Next()) {
      warn(base + ": a shell that is not a solid was loaded as a surface");
      mesh(ex.Current().Moved(loc), base, false);
      any = true;
    }
    // Faces outside shells (typical of IGES): one surface per shape.
    TopoDS_Compound loose;
    BRep_Builder b;
    b.MakeCompound(loose);
    std::size_t nloose = 0;
    for (TopExp_Explorer ex(proto, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) b.Add(loose, ex.Current()), ++nloose;
    if (nloose > 0) {
      warn(base + ": " + std::to_string(nloose) + " faces outside any solid were loaded as one surface");
      mesh(TopoDS_Shape(loose).Moved(loc), base, false);
      any = true;
    }
    if (!any) warn(base + ": no surface (wires or points only), skipped");
  }

  void warn(std::string w) { warnings.push_back(std::move(w)); }

  std::vector<CadSolid> solids;
  std::vector<std::string> warnings;
  double mesh_seconds = 0, remesh_seconds = 0;  // in mesh() in all, and meshing again there

 private:
  void mesh(const TopoDS_Shape& shape, const std::string& name, bool is_solid) {
    const auto t0 = std::chrono::steady_clock::now();
    struct Timer {
      double& total;
      std::chrono::steady_clock::time_point t0;
      ~Timer() { total += seconds_since(t0); }
    } timer{mesh_seconds, t0};
    CadSolid s;
    s.name = name;
    std::size_t unmeshed = collect(shape, s);
    TessellationCheck check;
    check.faces = s.link.faces->faces.size();
    check.folded_found = count_flag(s, kTriangleFolded);
    {
      std::vector<std::uint8_t> face_folded(check.faces, 0);
      for (std::size_t t = 0; t < s.triangles.size(); ++t)
        if (s.link.flags[t] & kTriangleFolded) face_folded[s.link.face[t]] = 1;
      for (auto f : face_folded) check.faces_folded += f;
    }
    // A fold is an artefact of the mesher (typically at small blends). The folded faces lose
    // their triangles and the solid is meshed again with the first mesh's edge parameters, a
    // quarter of the deflection and half the angle inside the faces, the other faces' meshes
    // allowed to stay: OpenCASCADE meshes the folded faces and those it must to keep the mesh
    // closed, reusing the edges' divisions elsewhere. This repeats until no fold is left or the
    // rounds are used up. Should the mesh open all the same, the whole solid is meshed again
    // with the finer parameters throughout, minimum sizes adjusted to the edges.
    double deflection = deflection_, angle = angle_;
    const std::size_t open_first = check.folded_found > 0 && opts_.fold_remesh_rounds > 0 ? open_edges(s) : 0;
    while (count_flag(s, kTriangleFolded) > 0 && check.remesh_rounds < opts_.fold_remesh_rounds) {
      deflection *= 0.25;
      angle = std::max(0.5 * angle, 2.0 * std::numbers::pi / 180.0);
      const auto tm = std::chrono::steady_clock::now();
      std::vector<Handle(Poly_Triangulation)> before;
      for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
        TopLoc_Location loc;
        before.push_back(BRep_Tool::Triangulation(TopoDS::Face(ex.Current()), loc));
      }
      std::vector<std::uint8_t> folds(s.link.faces->faces.size(), 0);
      for (std::size_t t = 0; t < s.triangles.size(); ++t)
        if (s.link.flags[t] & kTriangleFolded) folds[s.link.face[t]] = 1;
      for (std::size_t f = 0; f < folds.size(); ++f)
        if (folds[f]) BRep_Builder().UpdateFace(s.link.faces->faces[f].face, Handle(Poly_Triangulation)());
      IMeshTools_Parameters p = absolute_parameters(deflection_, angle_);
      p.DeflectionInterior = deflection;
      p.AngleInterior = angle;
      p.AllowQualityDecrease = Standard_True;
      BRepMesh_IncrementalMesh(shape, p);
      CadSolid redone;
      redone.name = name;
      std::size_t redone_unmeshed = collect(shape, redone);
      std::size_t changed = 0, k = 0;
      for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next(), ++k) {
        TopLoc_Location loc;
        changed += !same_mesh(BRep_Tool::Triangulation(TopoDS::Face(ex.Current()), loc), before[k]);
      }
      if (open_edges(redone) > open_first) {
        BRepTools::Clean(shape);
        p = absolute_parameters(deflection, angle);
        p.AdjustMinSize = Standard_True;
        p.ControlSurfaceDeflection = Standard_True;
        BRepMesh_IncrementalMesh(shape, p);
        changed = check.faces;
        redone = CadSolid{};
        redone.name = name;
        redone_unmeshed = collect(shape, redone);
      }
      remesh_seconds += seconds_since(tm);
      ++check.remesh_rounds;
      check.faces_remeshed += changed;
      s = std::move(redone);
      unmeshed = redone_unmeshed;
    }
    check.final_deflection = deflection;
    store_plane_pcurves(shape);
    if (unmeshed > 0) warn(name + ": " + std::to_string(unmeshed) + " faces could not be tessellated, skipped");
    if (s.triangles.empty()) {
      warn(name + ": nothing to tessellate, skipped");
      return;
    }
    weld(s);
    if (is_solid && signed_volume(s) < 0) {
      for (Tri& t : s.triangles) std::swap(t[1], t[2]);
      for (auto& uv : s.link.uv) std::swap(uv[2], uv[4]), std::swap(uv[3], uv[5]);
      for (CadFaces::Face& f : faces_of(s)) f.sign = -f.sign;
      warn(name + ": solid was inside out, turned right side out");
    }
    if (opts_.max_edge_length > 0 && !split_long_edges(s, opts_.max_edge_length, kMaxSplitTriangles))
      warn(name + ": splitting edges longer than " + std::to_string(opts_.max_edge_length) + " stopped at " +
           std::to_string(kMaxSplitTriangles) + " triangles; some edges stay longer");
    check.folded = count_flag(s, kTriangleFolded);
    check.slivers = count_flag(s, kTriangleSliver);
    s.link.check = check;
    if (check.folded_found > 0)
      warn(name + ": " + std::to_string(check.folded_found) + " folded triangles on " +
           std::to_string(check.faces_folded) + " faces" +
           (check.remesh_rounds > 0 ? ", meshed again " + std::to_string(check.remesh_rounds) + " times" : "") +
           (check.folded > 0 ? "; " + std::to_string(check.folded) + " left, flagged (thickness status tessellation)"
                             : "; none left"));
    solids.push_back(std::move(s));
  }

  // Stores the curves on the surface of the edges of planar faces that the file left out.
  // OpenCASCADE otherwise projects the edge's 3D curve onto the plane again on every request
  // (BRep_Tool::CurveOnPlane): the 3D solid classifier of the exact fallback asks for them many
  // times per call (pierce_bench_cad_refine, sheet_heatsink). The stored curve is the one the
  // projection gives, so every later answer is the same.
  static void store_plane_pcurves(const TopoDS_Shape& shape) {
    for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
      const TopoDS_Face& face = TopoDS::Face(f.Current());
      for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next())
        BRepLib::BuildPCurveForEdgeOnPlane(TopoDS::Edge(e.Current()), face);
    }
  }

  // Meshing parameters: this deflection (model units) and angle, faces meshed in parallel.
  static IMeshTools_Parameters absolute_parameters(double deflection, double angle) {
    IMeshTools_Parameters p;
    p.Deflection = deflection;
    p.Angle = angle;
    p.Relative = Standard_False;
    p.InParallel = Standard_True;
    return p;
  }

  // Whether two triangulations have the same nodes and triangles.
  static bool same_mesh(const Handle(Poly_Triangulation) & a, const Handle(Poly_Triangulation) & b) {
    if (a == b) return true;
    if (a.IsNull() || b.IsNull() || a->NbNodes() != b->NbNodes() || a->NbTriangles() != b->NbTriangles()) return false;
    for (Standard_Integer i = 1; i <= a->NbNodes(); ++i)
      if (a->Node(i).SquareDistance(b->Node(i)) != 0) return false;
    for (Standard_Integer i = 1; i <= a->NbTriangles(); ++i) {
      Standard_Integer a1, a2, a3, b1, b2, b3;
      a->Triangle(i).Get(a1, a2, a3);
      b->Triangle(i).Get(b1, b2, b3);
      if (a1 != b1 || a2 != b2 || a3 != b3) return false;
    }
    return true;
  }

  // Edges of the mesh, corners merged as weld() merges them, not shared by exactly two triangles:
  // a closed mesh has none.
  static std::size_t open_edges(const CadSolid& s) {
    CadSolid welded = s;
    weld(welded);
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * welded.triangles.size());
    for (const Tri& t : welded.triangles)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)];
        if (a != b) edges.push_back(std::uint64_t(std::min(a, b)) << 32 | std::max(a, b));
      }
    std::sort(edges.begin(), edges.end());
    std::size_t open = 0;
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      open += j - i != 2;
      i = j;
    }
    return open;
  }

  static std::size_t count_flag(const CadSolid& s, std::uint8_t flag) {
    std::size_t n = 0;
    for (auto f : s.link.flags) n += (f & flag) != 0;
    return n;
  }

  static std::vector<CadFaces::Face>& faces_of(CadSolid& s) {
    return const_cast<CadFaces&>(*s.link.faces).faces;  // still owned by this solid alone
  }

  // Appends every face's triangles to `s` with their link to the face, checked against it;
  // returns the number of faces without triangulation.
  std::size_t collect(const TopoDS_Shape& shape, CadSolid& s) {
    auto faces = std::make_shared<CadFaces>();
    faces->shape = shape;
    s.link.faces = faces;
    std::size_t unmeshed = 0;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
      const TopoDS_Face& face = TopoDS::Face(ex.Current());
      TopLoc_Location floc;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, floc);
      if (tri.IsNull() || tri->NbTriangles() == 0) {
        ++unmeshed;
        continue;
      }
      // Triangles follow the surface's parametric orientation; a reversed face's outside is the
      // other side. A mirroring placement flips every face alike (fixed below by the volume).
      const bool reversed = face.Orientation() == TopAbs_REVERSED;
      CadFaces::Face f;
      f.face = face;
      f.surface = BRep_Tool::Surface(face);
      f.sign = reversed ? -1.0 : 1.0;
      BRepTools::UVBounds(face, f.umin, f.umax, f.vmin, f.vmax);
      const auto face_index = std::uint32_t(faces->faces.size());
      const bool has_uv = tri->HasUVNodes() && !f.surface.IsNull();
      faces->faces.push_back(f);
      const gp_Trsf tr = floc.Transformation();
      const auto base = std::uint32_t(s.vertices.size());
      for (Standard_Integer i = 1; i <= tri->NbNodes(); ++i) {
        const gp_Pnt p = tri->Node(i).Transformed(tr);
        s.vertices.push_back({p.X(), p.Y(), p.Z()});
      }
      for (Standard_Integer i = 1; i <= tri->NbTriangles(); ++i) {
        Standard_Integer a, b, c;
        tri->Triangle(i).Get(a, b, c);
        if (reversed) std::swap(b, c);
        const Tri t{base + std::uint32_t(a - 1), base + std::uint32_t(b - 1), base + std::uint32_t(c - 1)};
        s.triangles.push_back(t);
        std::array<double, 6> uv{};
        std::uint8_t flags = 0;
        if (has_uv) {
          const Standard_Integer n[3] = {a, b, c};
          for (int k = 0; k < 3; ++k) {
            const gp_Pnt2d q = tri->UVNode(n[k]);
            uv[std::size_t(2 * k)] = q.X();
            uv[std::size_t(2 * k + 1)] = q.Y();
          }
          flags = check_triangle(f, s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]], uv);
        }
        s.link.face.push_back(face_index);
        s.link.uv.push_back(uv);
        s.link.flags.push_back(flags);
      }
    }
    return unmeshed;
  }

  // The triangle against its face: folded when its normal and the face's outward normal at the
  // triangle's centre (UV mean of its corners) make more than 90 degrees; a sliver when its
  // height is below 1e-6 of its longest edge.
  static std::uint8_t check_triangle(const CadFaces::Face& f, Vec3d a, Vec3d b, Vec3d c,
                                     const std::array<double, 6>& uv) {
    std::uint8_t flags = 0;
    const Vec3d n = cross(b - a, c - a);
    const double longest = std::max({length(b - a), length(c - b), length(a - c)});
    const double area2 = length(n);
    if (!(area2 > 1e-6 * longest * longest)) flags |= kTriangleSliver;
    if (!(area2 > 0)) return flags;
    auto normal_at = [&](double u, double v) {
      gp_Pnt p;
      gp_Vec du, dv;
      f.surface->D1(u, v, p, du, dv);
      const gp_Vec m = du.Crossed(dv) * f.sign;
      return Vec3d{m.X(), m.Y(), m.Z()};
    };
    Vec3d sn = normal_at((uv[0] + uv[2] + uv[4]) / 3.0, (uv[1] + uv[3] + uv[5]) / 3.0);
    if (!(length(sn) > 0)) {  // a singular point (pole, apex): the corners' normals instead
      sn = Vec3d{};
      for (int k = 0; k < 3; ++k) {
        const Vec3d m = normal_at(uv[std::size_t(2 * k)], uv[std::size_t(2 * k + 1)]);
        const double l = length(m);
        if (l > 0) sn = sn + m * (1.0 / l);
      }
    }
    if (length(sn) > 0 && dot(sn, n) < 0) flags |= kTriangleFolded;
    return flags;
  }

  // Faces are meshed separately: nodes on a shared edge (and on a periodic face's seam, whose two
  // sides are evaluated at parameters 0 and 2 pi) agree only up to rounding. Merging positions
  // closer than `eps` makes the mesh topologically closed and keeps the kernels watertight
  // there; triangles that collapse (at a sphere's poles) are dropped.
  static void weld(CadSolid& s) {
    BBoxd box;
    for (const Vec3d& p : s.vertices) box.extend(p);
    const double eps = 1e-9 * std::max(length(box.extent()), box.max_abs_coord());
    if (!(eps > 0)) return;
    struct Cell {
      std::int64_t x, y, z;
      bool operator<(const Cell& o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
    };
    auto cell_of = [&](Vec3d p) {
      return Cell{std::int64_t(std::floor(p.x / eps)), std::int64_t(std::floor(p.y / eps)),
                  std::int64_t(std::floor(p.z / eps))};
    };
    std::map<Cell, std::vector<std::uint32_t>> grid;
    std::vector<Vec3d> kept;
    std::vector<std::uint32_t> index(s.vertices.size());
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
      const Vec3d p = s.vertices[i];
      const Cell c = cell_of(p);
      std::uint32_t found = kInvalidIndex;
      for (std::int64_t dx = -1; dx <= 1 && found == kInvalidIndex; ++dx)
        for (std::int64_t dy = -1; dy <= 1 && found == kInvalidIndex; ++dy)
          for (std::int64_t dz = -1; dz <= 1 && found == kInvalidIndex; ++dz) {
            const auto it = grid.find({c.x + dx, c.y + dy, c.z + dz});
            if (it == grid.end()) continue;
            for (std::uint32_t k : it->second)
              if (max_abs(kept[k] - p) <= eps) {
                found = k;
                break;
              }
          }
      if (found == kInvalidIndex) {
        found = std::uint32_t(kept.size());
        kept.push_back(p);
        grid[c].push_back(found);
      }
      index[i] = found;
    }
    std::vector<Tri> tris;
    CadLink link;
    link.faces = s.link.faces;
    for (std::size_t i = 0; i < s.triangles.size(); ++i) {
      Tri t = s.triangles[i];
      for (auto& k : t) k = index[k];
      if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) {
        tris.push_back(t);
        link.face.push_back(s.link.face[i]);
        link.uv.push_back(s.link.uv[i]);
        link.flags.push_back(s.link.flags[i]);
      }
    }
    s.vertices = std::move(kept);
    s.triangles = std::move(tris);
    s.link = std::move(link);
  }

  static double signed_volume(const CadSolid& s) {
    BBoxd b;
    for (const Vec3d& p : s.vertices) b.extend(p);
    const Vec3d o = b.center();
    double vol = 0;
    for (const Tri& t : s.triangles)
      vol += dot(s.vertices[t[0]] - o, cross(s.vertices[t[1]] - o, s.vertices[t[2]] - o));
    return vol / 6.0;
  }

  std::string path_, stem_;
  TessellationOptions opts_;
  double deflection_ = 0, angle_ = 0;
};

// Walks an XDE assembly tree: assemblies recurse with their components' placements, parts are
// meshed. Names are the path of label names from the top.
void walk(const Handle(XCAFDoc_ShapeTool) & tool, const TDF_Label& label, const TopLoc_Location& parent_loc,
          const std::string& parent_path, Collector& out) {
  TDF_Label proto = label;
  TopLoc_Location loc = parent_loc;
  if (XCAFDoc_ShapeTool::IsReference(label)) {
    XCAFDoc_ShapeTool::GetReferredShape(label, proto);
    loc = parent_loc * XCAFDoc_ShapeTool::GetLocation(label);
  }
  std::string name = label_name(proto);
  if (name.empty()) name = label_name(label);
  const std::string path = parent_path.empty() ? name : (name.empty() ? parent_path : parent_path + "/" + name);
  if (XCAFDoc_ShapeTool::IsAssembly(proto)) {
    TDF_LabelSequence comps;
    XCAFDoc_ShapeTool::GetComponents(proto, comps);
    for (Standard_Integer i = 1; i <= comps.Length(); ++i) walk(tool, comps.Value(i), loc, path, out);
    return;
  }
  out.add(XCAFDoc_ShapeTool::GetShape(proto), loc, path, tool, proto);
}

double auto_deflection(const std::vector<TopoDS_Shape>& shapes) {
  Bnd_Box box;
  for (const TopoDS_Shape& s : shapes) BRepBndLib::Add(s, box);
  if (box.IsVoid()) return 0.1;
  const double d = std::sqrt(box.SquareExtent());
  return d > 0 ? 1e-3 * d : 0.1;
}

void mesh_all(const std::vector<TopoDS_Shape>& shapes, const TessellationOptions& opts, CadModel& model,
              Collector& out) {
  const auto t0 = std::chrono::steady_clock::now();
  model.linear_deflection = opts.linear_deflection > 0 ? opts.linear_deflection : auto_deflection(shapes);
  const double angle = opts.angular_deflection_deg * std::numbers::pi / 180.0;
  for (const TopoDS_Shape& s : shapes) BRepMesh_IncrementalMesh(s, model.linear_deflection, false, angle, true);
  model.times.mesh += seconds_since(t0);
  out.set_tessellation(model.linear_deflection, angle);
}

// Load-time failures of individual entities ("skipped"), from the reader's check list.
void report_checks(const Handle(XSControl_WorkSession) & ws, const std::string& what, CadModel& model) {
  if (ws.IsNull()) return;
  const Interface_CheckIterator checks = ws->ModelCheckList();
  std::size_t failed = 0;
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& c = checks.Value();
    if (c.IsNull() || !c->HasFailed()) continue;
    if (++failed <= kMaxListedProblems) {
      const std::string msg = c->NbFails() > 0 ? std::string(c->CFail(1)) : std::string("unreadable");
      model.warnings.push_back(checks.Number() > 0
                                   ? what + " entity #" + std::to_string(checks.Number()) + " skipped: " + msg
                                   : what + " file: " + msg);
    }
  }
  if (failed > kMaxListedProblems)
    model.warnings.push_back(std::to_string(failed - kMaxListedProblems) + " more " + what + " entities skipped");
}

// The plain reader under the XDE one (STEP wraps it, IGES derives from it).
XSControl_Reader& plain_reader(STEPCAFControl_Reader& r) { return r.ChangeReader(); }
XSControl_Reader& plain_reader(IGESCAFControl_Reader& r) { return r; }

// STEP and IGES through XDE.
template <typename Reader>
void load_xde(const std::string& path, const char* what, const TessellationOptions& opts, CadModel& model,
              Collector& out) {
  Reader reader;
  reader.SetNameMode(true);
  reader.SetColorMode(false);
  reader.SetLayerMode(false);
  const IFSelect_ReturnStatus st = reader.ReadFile(path.c_str());
  if (st != IFSelect_RetDone) fail(path, std::string("not a readable ") + what + " file (" + status_text(st) + ")");
  const Handle(XSControl_WorkSession) ws = plain_reader(reader).WS();
  report_checks(ws, what, model);
  const Standard_Integer roots = reader.NbRootsForTransfer();
  if (roots == 0) fail(path, std::string("no shape to load in this ") + what + " file");

  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  struct Closer {
    Handle(TDocStd_Document) & d;
    ~Closer() {
      if (!d.IsNull() && d->CanClose() == CDM_CCS_OK) XCAFApp_Application::GetApplication()->Close(d);
    }
  } closer{doc};
  if (!reader.Transfer(doc)) fail(path, std::string("no shape could be converted from this ") + what + " file");
  std::size_t untransferred = 0;
  for (Standard_Integer i = 1; i <= roots; ++i) {
    const Handle(Standard_Transient) root = plain_reader(reader).RootForTransfer(i);
    if (root.IsNull() || ws->TransferReader()->HasResult(root)) continue;
    if (++untransferred <= kMaxListedProblems)
      model.warnings.push_back(std::string(what) + " entity #" + std::to_string(ws->Model()->Number(root)) + " (" +
                               root->DynamicType()->Name() + ") could not be converted, skipped");
  }
  if (untransferred > kMaxListedProblems)
    model.warnings.push_back(std::to_string(untransferred - kMaxListedProblems) + " more roots skipped");

  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDF_LabelSequence free;
  tool->GetFreeShapes(free);
  std::vector<TopoDS_Shape> shapes;
  for (Standard_Integer i = 1; i <= free.Length(); ++i) shapes.push_back(XCAFDoc_ShapeTool::GetShape(free.Value(i)));
  mesh_all(shapes, opts, model, out);
  for (Standard_Integer i = 1; i <= free.Length(); ++i) walk(tool, free.Value(i), TopLoc_Location(), "", out);
}

void load_brep(const std::string& path, const TessellationOptions& opts, CadModel& model, Collector& out) {
  TopoDS_Shape shape;
  BRep_Builder builder;
  if (!BRepTools::Read(shape, path.c_str(), builder) || shape.IsNull()) fail(path, "not a readable BREP file");
  mesh_all({shape}, opts, model, out);
  out.add(shape, TopLoc_Location(), "", Handle(XCAFDoc_ShapeTool)(), TDF_Label());
}

// Repeated names get "#2", "#3", ... in order.
void make_names_unique(std::vector<CadSolid>& solids) {
  std::map<std::string, int> seen;
  for (CadSolid& s : solids) {
    const int k = ++seen[s.name];
    if (k > 1) s.name.append("#").append(std::to_string(k));
  }
}

// While alive, OpenCASCADE's handlers catch crashes (SIGSEGV, SIGBUS, SIGILL, SIGFPE) so they
// become exceptions; every other signal keeps the application's handler (Ctrl-C handling in
// the CLI, Python, FreeCAD), and all handlers are restored afterwards.
class CrashToException {
 public:
  CrashToException() {
    for (int s = 1; s < kSignals; ++s) sigaction(s, nullptr, &saved_[std::size_t(s)]);
    OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
    for (int s = 1; s < kSignals; ++s)
      if (!converted(s)) sigaction(s, &saved_[std::size_t(s)], nullptr);
  }
  ~CrashToException() {
    for (int s = 1; s < kSignals; ++s) sigaction(s, &saved_[std::size_t(s)], nullptr);
  }
  CrashToException(const CrashToException&) = delete;
  CrashToException& operator=(const CrashToException&) = delete;

 private:
  static constexpr int kSignals = 32;
  static bool converted(int s) { return s == SIGSEGV || s == SIGBUS || s == SIGILL || s == SIGFPE; }
  std::array<struct sigaction, kSignals> saved_{};
};

// Runs f with OpenCASCADE failures and crashes turned into InputError naming the file.
template <typename F>
void guarded(const std::string& path, F&& f) {
  try {
    OCC_CATCH_SIGNALS
    f();
  } catch (const Standard_Failure& e) {
    const char* msg = e.GetMessageString();
    fail(path, std::string("OpenCASCADE failed on this file (") + e.DynamicType()->Name() +
                   (msg && *msg ? std::string(": ") + msg : std::string()) + ")");
  }
}

// Keeps OpenCASCADE's console messages (transfer statistics, parse errors) off stdout during a
// load: problems reach the caller as warnings or errors instead.
class QuietMessenger {
 public:
  QuietMessenger() : messenger_(Message::DefaultMessenger()) {
    if (messenger_.IsNull()) return;
    saved_ = messenger_->Printers();
    messenger_->ChangePrinters().Clear();
  }
  ~QuietMessenger() {
    if (!messenger_.IsNull()) messenger_->ChangePrinters() = saved_;
  }
  QuietMessenger(const QuietMessenger&) = delete;
  QuietMessenger& operator=(const QuietMessenger&) = delete;

 private:
  Handle(Message_Messenger) messenger_;
  Message_SequenceOfPrinters saved_;
};

// OpenCASCADE's XDE application and the signal handlers are process-wide: one load at a time.
std::mutex& load_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

bool is_cad_file(const std::string& path) { return format_of(path) != CadFormat::unknown; }

CadModel load_cad_file(const std::string& path, const TessellationOptions& opts) {
  const CadFormat fmt = format_of(path);
  if (fmt == CadFormat::unknown)
    fail(path, "unknown CAD format '" + lower_extension(path) + "' (expected .step, .stp, .iges, .igs, .brep or .brp)");
  if (!(opts.linear_deflection >= 0) || !std::isfinite(opts.linear_deflection))
    throw InputError("tessellation: linear deflection must be a positive number (0 for automatic)");
  if (!(opts.angular_deflection_deg > 0 && opts.angular_deflection_deg < 180))
    throw InputError("tessellation: angular deflection must be in (0, 180) degrees");
  if (opts.fold_remesh_rounds < 0 || opts.fold_remesh_rounds > 10)
    throw InputError("tessellation: fold remesh rounds must be in 0..10");
  if (!(opts.max_edge_length >= 0) || !std::isfinite(opts.max_edge_length))
    throw InputError("tessellation: the maximum edge length must be a positive length (0 for no splitting)");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail(path, "cannot open file (no such file)");
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "cannot read: not a regular file");
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open file");
    if (in.peek() == std::ifstream::traits_type::eof()) fail(path, "file is empty");
  }
  CadModel model;
  model.units = fmt == CadFormat::brep ? "model units" : "mm";
  Collector out(path, std::filesystem::path(path).stem().string(), opts);
  {
    const std::lock_guard<std::mutex> lock(load_mutex());
    const CrashToException crash_guard;
    const QuietMessenger quiet;
    const auto t0 = std::chrono::steady_clock::now();
    guarded(path, [&] {
      switch (fmt) {
        case CadFormat::step: load_xde<STEPCAFControl_Reader>(path, "STEP", opts, model, out); break;
        case CadFormat::iges: load_xde<IGESCAFControl_Reader>(path, "IGES", opts, model, out); break;
        case CadFormat::brep: load_brep(path, opts, model, out); break;
        case CadFormat::unknown: break;
      }
    });
    // Reading is what neither meshing nor checking took.
    model.times.mesh += out.remesh_seconds;
    model.times.check = out.mesh_seconds - out.remesh_seconds;
    model.times.read = std::max(0.0, seconds_since(t0) - model.times.mesh - model.times.check);
  }
  model.solids = std::move(out.solids);
  model.warnings.insert(model.warnings.end(), out.warnings.begin(), out.warnings.end());
  if (model.solids.empty()) fail(path, "no solid or surface could be tessellated");
  make_names_unique(model.solids);
  return model;
}

}  // namespace pierce
