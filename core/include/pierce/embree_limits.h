#pragma once
// What Embree's BVH builder can hold. Its builder drops primitives whose bounds reach FLT_LARGE
// (1.844e18), which would lose hits silently. Scenes with coordinates beyond kEmbreeMaxCoord
// (2^59, leaving room for the boxes' padding) are therefore refused by the Embree-based kernels
// and built by Pierce's own binned builder instead of rtcBuildBVH.

namespace pierce {

inline constexpr double kEmbreeMaxCoord = 0x1p59;

}  // namespace pierce
