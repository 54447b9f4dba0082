#pragma once
// Image encoders for analysis output: PNG (through libspng) and VTK XML ImageData (.vti, ASCII).
#include <span>
#include <string>
#include <vector>

#include "pierce/vec3.h"

namespace pierce {

// PNG bytes for a width x height image with `channels` samples per pixel (1 grey, 3 RGB, 4 RGBA)
// of `bits` (8 or 16) each. `samples` holds width*height*channels values in [0, 1] (clamped; NaN
// becomes 0), rows from the top, row-major. Throws std::invalid_argument on bad sizes and
// std::runtime_error if libspng fails.
std::string encode_png(int width, int height, int channels, int bits, std::span<const double> samples);

// VTK XML ImageData: a width x height x 1 image, point data arrays of width*height values each
// (x fastest, rows from the bottom as VTK counts them), with origin and spacing.
struct VtiArray {
  std::string name;
  std::vector<double> values;
};
std::string encode_vti(int width, int height, Vec3d origin, Vec3d spacing, const std::vector<VtiArray>& arrays);

}  // namespace pierce
