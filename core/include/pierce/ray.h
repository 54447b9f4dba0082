#pragma once
// A ray segment origin + t * dir, t in [tmin, tmax]. Input precision is double;
// kernels convert once per ray.
#include <limits>

#include "pierce/vec3.h"

namespace pierce {

struct Ray {
  Vec3d org;
  Vec3d dir;
  double tmin = 0.0;
  double tmax = std::numeric_limits<double>::infinity();
};

}  // namespace pierce
