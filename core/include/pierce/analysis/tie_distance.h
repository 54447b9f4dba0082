#pragma once
// The length below which the analyses take crossings as simultaneous, or as the surface a ray
// starts on: a fraction of the scene's size and of its distance from the origin (where float
// and double spacing grow), so it scales with the model and its placement alike.
#include "pierce/scene.h"

namespace pierce::analysis {

inline double tie_distance(const Scene& scene, double tie_tolerance_rel) {
  return tie_tolerance_rel * (scene.scale() + scene.bounds().max_abs_coord());
}

}  // namespace pierce::analysis
