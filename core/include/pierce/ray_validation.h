#pragma once
// The rays a front end refuses before tracing, named by index: a non-finite origin or direction,
// a zero direction, a NaN tmin or tmax. (The kernels give such a ray no hits; a caller handing
// them over is better told.) One pass over the columns, nothing allocated unless a ray is bad.
#include <cstddef>
#include <optional>

#include "pierce/ray_columns.h"

namespace pierce {

struct InvalidRay {
  std::size_t ray;     // its index
  const char* reason;  // "origin is not finite", "direction is not finite", "direction is zero", "tmin/tmax is NaN"
};

// The lowest-index invalid ray, reason by the first failing check in the order listed above.
std::optional<InvalidRay> first_invalid_ray(const RayColumns& rays);

// Throws InputError("ray <index>: <reason>") for first_invalid_ray, if there is one.
void require_valid_rays(const RayColumns& rays);

}  // namespace pierce
