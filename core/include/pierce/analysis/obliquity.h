#pragma once
// The angle at which a ray meets a surface, for shotlines, effects, and the VTK ray classifier.
#include "pierce/hit.h"
#include "pierce/vec3.h"

namespace pierce::analysis {

// Angle in degrees between a ray direction and a surface's normal, in [0, 90]; NaN for an invalid
// hit or a zero normal. 0 means the ray meets the surface head-on.
double obliquity_deg(Vec3d dir, const Hit& h);

}  // namespace pierce::analysis
