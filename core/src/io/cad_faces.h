#pragma once
// The B-rep faces of one loaded solid (internal to pierce_cad: OpenCASCADE types).
#include <Geom_Surface.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <array>
#include <vector>

#include "pierce/io/cad_io.h"

namespace pierce {

struct CadFaces {
  struct Face {
    TopoDS_Face face;              // placed where the solid is
    Handle(Geom_Surface) surface;  // with the placement applied (evaluates in model coordinates)
    double sign = 1;               // +1 when dSu x dSv points out of the solid, -1 otherwise
    double umin = 0, umax = 0, vmin = 0, vmax = 0;  // the face's parameter range (trimmed)
  };
  std::vector<Face> faces;
  TopoDS_Shape shape;  // the solid (or surface) the faces belong to, placed
};

}  // namespace pierce
