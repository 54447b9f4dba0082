#pragma once
// A face's trim classification answered from a grid over its (u, v) box (internal to pierce_cad:
// OpenCASCADE types). BRepTopAdaptor_FClass2d::Perform walks every point of every polygon of the
// face's wires per call, and builds a surface adaptor each time: on a plate with dozens of slots
// that is most of the B-rep thickness time (pierce_bench_cad_refine, sheet_heatsink). The grid
// answers the cells away from every wire with the classifier's own answer, asked once per
// connected region of such cells; points near a wire, or outside the box, go to the classifier.
#include <BRepTopAdaptor_FClass2d.hxx>
#include <TopAbs_State.hxx>
#include <TopoDS_Face.hxx>

#include <cstdint>
#include <vector>

namespace pierce {

class TrimGrid {
 public:
  // An empty grid (every point goes to the classifier).
  TrimGrid() = default;
  // The grid of `face` over its parameter box [umin, umax] x [vmin, vmax], each region's state
  // asked of `classifier` (built on the same face). A face whose wires cannot be discretised
  // (an edge without a curve on the face) gets an empty grid.
  TrimGrid(const TopoDS_Face& face, double umin, double umax, double vmin, double vmax,
           const BRepTopAdaptor_FClass2d& classifier);

  // Where (u, v) lies against the face's trim: TopAbs_IN or TopAbs_OUT where the grid knows,
  // TopAbs_UNKNOWN where the classifier must decide (near a wire, outside the box).
  TopAbs_State state(double u, double v) const {
    if (cells_.empty()) return TopAbs_UNKNOWN;
    const double fu = (u - u0_) * inv_du_, fv = (v - v0_) * inv_dv_;
    if (!(fu >= 0 && fu < nu_ && fv >= 0 && fv < nv_)) return TopAbs_UNKNOWN;
    return TopAbs_State(cells_[std::size_t(int(fv)) * std::size_t(nu_) + std::size_t(int(fu))]);
  }

 private:
  double u0_ = 0, v0_ = 0, inv_du_ = 0, inv_dv_ = 0;
  int nu_ = 0, nv_ = 0;
  std::vector<std::uint8_t> cells_;  // TopAbs_State per cell, row-major in v
};

}  // namespace pierce
