#pragma once
// Rays as columns: origins and directions as rows of three doubles, tmin and tmax as one double
// per ray or one for every ray, each read through a pointer and byte strides from where the
// caller keeps them (a NumPy array, a std::vector<Ray>, any strided float64 buffer). A view: it
// copies nothing and the arrays must outlive it. Values are read as their bytes (std::memcpy),
// so any alignment and negative strides are fine, and a Ray built from the columns holds exactly
// the doubles stored there.
#include <cstddef>
#include <cstring>
#include <limits>
#include <span>
#include <type_traits>

#include "pierce/ray.h"

namespace pierce {

namespace detail {
inline double load_double(const std::byte* at) {
  double v;
  std::memcpy(&v, at, sizeof v);
  return v;
}
}  // namespace detail

// Rows of three doubles: row i's component c is at data + i * row_stride + c * component_stride
// (strides in bytes, as NumPy gives them).
struct Vec3Column {
  const void* data = nullptr;
  std::ptrdiff_t row_stride = 3 * sizeof(double);
  std::ptrdiff_t component_stride = sizeof(double);

  Vec3d operator[](std::size_t i) const {
    const std::byte* row = static_cast<const std::byte*>(data) + static_cast<std::ptrdiff_t>(i) * row_stride;
    return {detail::load_double(row), detail::load_double(row + component_stride),
            detail::load_double(row + 2 * component_stride)};
  }
};

// One double per ray at data + i * stride (bytes), or `value` for every ray when data is null.
struct DoubleColumn {
  const void* data = nullptr;
  std::ptrdiff_t stride = sizeof(double);
  double value = 0.0;

  static DoubleColumn constant(double v) { return {nullptr, 0, v}; }
  static DoubleColumn per_ray(const void* data, std::ptrdiff_t stride = sizeof(double)) { return {data, stride, 0.0}; }

  double operator[](std::size_t i) const {
    if (!data) return value;
    return detail::load_double(static_cast<const std::byte*>(data) + static_cast<std::ptrdiff_t>(i) * stride);
  }
};

// `count` rays; ray i is {origins[i], directions[i], tmin[i], tmax[i]}.
struct RayColumns {
  std::size_t count = 0;
  Vec3Column origins;
  Vec3Column directions;
  DoubleColumn tmin = DoubleColumn::constant(0.0);
  DoubleColumn tmax = DoubleColumn::constant(std::numeric_limits<double>::infinity());
  // The same rays as an array of Rays, when they are one (columns_of): traced in place.
  const Ray* as_rays = nullptr;

  std::size_t size() const { return count; }
  Ray operator[](std::size_t i) const { return {origins[i], directions[i], tmin[i], tmax[i]}; }
};

// The columns of an array of Rays (strides of sizeof(Ray)): columns_of(rays)[i] == rays[i].
inline RayColumns columns_of(std::span<const Ray> rays) {
  static_assert(std::is_standard_layout_v<Ray> && std::is_standard_layout_v<Vec3d>);
  constexpr auto stride = static_cast<std::ptrdiff_t>(sizeof(Ray));
  constexpr auto component = static_cast<std::ptrdiff_t>(offsetof(Vec3d, y) - offsetof(Vec3d, x));
  static_assert(offsetof(Vec3d, z) - offsetof(Vec3d, y) == offsetof(Vec3d, y) - offsetof(Vec3d, x));
  RayColumns c;
  if (rays.empty()) return c;
  const auto* base = reinterpret_cast<const std::byte*>(rays.data());
  c.count = rays.size();
  c.origins = {base + offsetof(Ray, org) + offsetof(Vec3d, x), stride, component};
  c.directions = {base + offsetof(Ray, dir) + offsetof(Vec3d, x), stride, component};
  c.tmin = DoubleColumn::per_ray(base + offsetof(Ray, tmin), stride);
  c.tmax = DoubleColumn::per_ray(base + offsetof(Ray, tmax), stride);
  c.as_rays = rays.data();
  return c;
}

}  // namespace pierce
