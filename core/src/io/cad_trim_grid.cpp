#include "cad_trim_grid.h"

#include <BRep_Tool.hxx>
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>

namespace pierce {

namespace {

// Cells of a face's grid: the square of kCellsPerSegment times the square root of its wires'
// segment count (finer where the wires are detailed: a plate with dozens of slots), that count
// within [kMinGridCells, kMaxGridCells]; shared between the directions as the (u, v) box's sides
// on the surface (square cells on a long face too), each direction within [kMinSideCells,
// kMaxGridCells]. One byte per cell, at most 64 kB per face.
constexpr double kCellsPerSegment = 6;
constexpr int kMinGridCells = 64, kMaxGridCells = 256, kMinSideCells = 48;
// Points per curved edge of the discretised wires (a straight edge needs its two ends).
constexpr int kCurveSamples = 64;
// How far past the discretised wires a cell stays unknown, in units of the discretisation's own
// largest deviation from its curves (per direction). The classifier's polygon has at least 8
// points per curved edge (Geom2dInt_Geom2dCurveTool::NbSamples, times 4), so it deviates at
// most (64 / 8)^2 = 64 times as much; its "on" band is that deviation (FlecheU/V, at least its
// tolerance), which the cell of slack added below covers.
constexpr double kDeviationMargin = 2 * 64.0;
constexpr int kSlackCells = 1;

struct Segment {
  gp_Pnt2d a, b;
};

}  // namespace

TrimGrid::TrimGrid(const TopoDS_Face& face, double umin, double umax, double vmin, double vmax,
                   const BRepTopAdaptor_FClass2d& classifier) {
  if (!(umax > umin && vmax > vmin) || !std::isfinite(umax - umin) || !std::isfinite(vmax - vmin)) return;
  std::vector<Segment> segments;
  double dev_u = 0, dev_v = 0;
  try {
    for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      double f = 0, l = 0;
      const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, face, f, l);
      if (c.IsNull() || !std::isfinite(f) || !std::isfinite(l)) return;  // no grid: the classifier decides
      const Geom2dAdaptor_Curve ac(c, f, l);
      const int n = ac.GetType() == GeomAbs_Line ? 2 : kCurveSamples;
      gp_Pnt2d prev = ac.Value(f);
      for (int k = 1; k < n; ++k) {
        const double t = f + (l - f) * k / (n - 1);
        const gp_Pnt2d p = ac.Value(t);
        if (n > 2) {
          const gp_Pnt2d mid = ac.Value(f + (l - f) * (k - 0.5) / (n - 1));
          dev_u = std::max(dev_u, std::abs(mid.X() - 0.5 * (prev.X() + p.X())));
          dev_v = std::max(dev_v, std::abs(mid.Y() - 0.5 * (prev.Y() + p.Y())));
        }
        segments.push_back({prev, p});
        prev = p;
      }
    }
  } catch (const Standard_Failure&) {
    return;
  }
  if (segments.empty()) return;

  const double su = umax - umin, sv = vmax - vmin;
  const double cells_per_side =
      std::clamp(kCellsPerSegment * std::sqrt(double(segments.size())), double(kMinGridCells), double(kMaxGridCells));
  // The box's sides on the surface (polylines along the middle iso-lines): the aspect of the
  // face as its points are spread; the parameters' own where that is not measurable.
  double aspect = std::sqrt(su / sv);
  try {
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
    if (!surface.IsNull()) {
      constexpr int kPieces = 8;
      double lu = 0, lv = 0;
      const double um = 0.5 * (umin + umax), vm = 0.5 * (vmin + vmax);
      for (int k = 0; k < kPieces; ++k) {
        lu += surface->Value(umin + su * k / kPieces, vm).Distance(surface->Value(umin + su * (k + 1) / kPieces, vm));
        lv += surface->Value(um, vmin + sv * k / kPieces).Distance(surface->Value(um, vmin + sv * (k + 1) / kPieces));
      }
      if (lu > 0 && lv > 0 && std::isfinite(lu / lv)) aspect = std::sqrt(lu / lv);
    }
  } catch (const Standard_Failure&) {
  }
  const int nu = int(std::clamp(cells_per_side * aspect, double(kMinSideCells), double(kMaxGridCells)));
  const int nv = int(std::clamp(cells_per_side / aspect, double(kMinSideCells), double(kMaxGridCells)));
  const double du = su / nu, dv = sv / nv;
  const double mu = kSlackCells * du + kDeviationMargin * dev_u, mv = kSlackCells * dv + kDeviationMargin * dev_v;
  constexpr auto kUnset = std::uint8_t(TopAbs_IN + 100), kNear = std::uint8_t(TopAbs_UNKNOWN);
  std::vector<std::uint8_t> cells(std::size_t(nu) * nv, kUnset);
  auto clamp_u = [&](double u) { return std::clamp(int(std::floor((u - umin) / du)), 0, nu - 1); };
  auto clamp_v = [&](double v) { return std::clamp(int(std::floor((v - vmin) / dv)), 0, nv - 1); };
  // Every cell within the margin of a segment is near a wire: each segment is cut into pieces no
  // longer than a cell, and the cells their boxes, widened by the margin, overlap are marked.
  for (const Segment& s : segments) {
    const double lu = s.b.X() - s.a.X(), lv = s.b.Y() - s.a.Y();
    const double pieces = std::ceil(std::max(std::abs(lu) / du, std::abs(lv) / dv));
    if (!std::isfinite(pieces)) return;
    const int np = std::max(1, int(std::min(pieces, 4.0 * kMaxGridCells)));
    for (int k = 0; k < np; ++k) {
      const double t0 = double(k) / np, t1 = double(k + 1) / np;
      const double ua = s.a.X() + lu * t0, ub = s.a.X() + lu * t1, va = s.a.Y() + lv * t0, vb = s.a.Y() + lv * t1;
      const int i0 = clamp_u(std::min(ua, ub) - mu), i1 = clamp_u(std::max(ua, ub) + mu);
      const int j0 = clamp_v(std::min(va, vb) - mv), j1 = clamp_v(std::max(va, vb) + mv);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) cells[std::size_t(j) * nu + std::size_t(i)] = kNear;
    }
  }
  // The cells of one region (4-connected, no cell near a wire between them) lie on one side of
  // every wire, the classifier's polygons included: its answer at one cell's centre is its answer
  // everywhere in the region. The cells on the box's rim stay unknown (the classifier shifts
  // points outside its polygons' box by a period on periodic surfaces).
  for (int i = 0; i < nu; ++i) cells[std::size_t(i)] = cells[std::size_t(nv - 1) * nu + std::size_t(i)] = kNear;
  for (int j = 0; j < nv; ++j) cells[std::size_t(j) * nu] = cells[std::size_t(j) * nu + std::size_t(nu - 1)] = kNear;
  std::vector<std::size_t> region, todo;
  for (std::size_t c0 = 0; c0 < cells.size(); ++c0) {
    if (cells[c0] != kUnset) continue;
    region.clear();
    todo.assign(1, c0);
    cells[c0] = kNear;  // visited; set to the region's state below
    while (!todo.empty()) {
      const std::size_t c = todo.back();
      todo.pop_back();
      region.push_back(c);
      const int i = int(c % std::size_t(nu)), j = int(c / std::size_t(nu));
      const int ni[4] = {i - 1, i + 1, i, i}, nj[4] = {j, j, j - 1, j + 1};
      for (int k = 0; k < 4; ++k) {
        if (ni[k] < 0 || ni[k] >= nu || nj[k] < 0 || nj[k] >= nv) continue;
        const std::size_t n = std::size_t(nj[k]) * nu + std::size_t(ni[k]);
        if (cells[n] == kUnset) cells[n] = kNear, todo.push_back(n);
      }
    }
    const int i = int(c0 % std::size_t(nu)), j = int(c0 / std::size_t(nu));
    TopAbs_State st = TopAbs_UNKNOWN;
    try {
      st = classifier.Perform(gp_Pnt2d(umin + (i + 0.5) * du, vmin + (j + 0.5) * dv));
    } catch (const Standard_Failure&) {
      st = TopAbs_UNKNOWN;
    }
    if (st != TopAbs_IN && st != TopAbs_OUT) st = TopAbs_UNKNOWN;
    for (std::size_t c : region) cells[c] = std::uint8_t(st);
  }
  u0_ = umin, v0_ = vmin, inv_du_ = 1.0 / du, inv_dv_ = 1.0 / dv;
  nu_ = nu, nv_ = nv;
  cells_ = std::move(cells);
}

}  // namespace pierce
