#include "pierce/ray_validation.h"

#include <cmath>
#include <string>

#include "pierce/error.h"

namespace pierce {

std::optional<InvalidRay> first_invalid_ray(const RayColumns& rays) {
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray r = rays[i];
    if (!all_finite(r.org)) return InvalidRay{i, "origin is not finite"};
    if (!all_finite(r.dir)) return InvalidRay{i, "direction is not finite"};
    if (r.dir == Vec3d{}) return InvalidRay{i, "direction is zero"};
    if (std::isnan(r.tmin) || std::isnan(r.tmax)) return InvalidRay{i, "tmin/tmax is NaN"};
  }
  return std::nullopt;
}

void require_valid_rays(const RayColumns& rays) {
  if (const auto bad = first_invalid_ray(rays))
    throw InputError("ray " + std::to_string(bad->ray) + ": " + bad->reason);
}

}  // namespace pierce
