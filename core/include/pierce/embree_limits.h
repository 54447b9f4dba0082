#pragma once
// What Embree's BVH can hold. Its builder drops primitives whose bounds reach FLT_LARGE
// (1.844e18), which would lose hits silently, so the Embree-based kernels refuse scenes with
// coordinates beyond kEmbreeMaxCoord (2^59, leaving room for the boxes' padding). Pierce's own
// builder computes its SAH areas in float below the same bound and in double above it.

namespace pierce {

inline constexpr double kEmbreeMaxCoord = 0x1p59;

}  // namespace pierce
