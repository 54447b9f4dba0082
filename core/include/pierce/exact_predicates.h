#pragma once
// Exact orientation predicates on double coordinates (Shewchuk-style: a floating-point filter,
// then exact expansion arithmetic when the filter cannot decide). Used to decide "exactly
// coplanar" and "interiors overlap" without tolerances.
#include "pierce/vec3.h"

namespace pierce {

struct Vec2d {
  double x = 0, y = 0;
};

// Sign of (b-a) x (c-a): +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 collinear.
int orient2d(Vec2d a, Vec2d b, Vec2d c);

// Sign of ((b-a) x (c-a)) . (d-a): +1 when d lies on the side the normal of the
// counter-clockwise triangle a, b, c points to, 0 when the four points are coplanar.
int orient3d(Vec3d a, Vec3d b, Vec3d c, Vec3d d);

}  // namespace pierce
