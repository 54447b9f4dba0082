#pragma once
// Small 3-vector value type used by scene, BVH and kernels.
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace pierce {

template <typename T>
struct Vec3 {
  T x{}, y{}, z{};

  constexpr Vec3() = default;
  constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  template <typename U>
  constexpr explicit Vec3(const Vec3<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

  constexpr T& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
  // By value through a small array rather than a chain of selects: with a run-time index (the
  // triangle test's per-ray axes) this is a load, not two data-dependent branches.
  constexpr T operator[](std::size_t i) const {
    const T v[3] = {x, y, z};
    return v[i];
  }

  friend constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend constexpr Vec3 operator*(Vec3 a, T s) { return {a.x * s, a.y * s, a.z * s}; }
  friend constexpr Vec3 operator*(T s, Vec3 a) { return {a.x * s, a.y * s, a.z * s}; }
  friend constexpr bool operator==(Vec3 a, Vec3 b) = default;
};

using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;

template <typename T> constexpr T dot(Vec3<T> a, Vec3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <typename T> constexpr Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T> constexpr Vec3<T> vmin(Vec3<T> a, Vec3<T> b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T> constexpr Vec3<T> vmax(Vec3<T> a, Vec3<T> b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <typename T> T length(Vec3<T> a) { return std::sqrt(dot(a, a)); }
template <typename T> T max_abs(Vec3<T> a) { return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}); }
template <typename T> bool all_finite(Vec3<T> a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace pierce
