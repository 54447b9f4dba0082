// Ray batches between numpy arrays and pierce::Ray.
#include "common.h"
#include "pierce/ray_validation.h"

namespace pierce::py {

namespace {

// A number (one value for every ray) or one value per ray; a float64 array is read where it is.
DoubleColumn per_ray(const pyb::handle& obj, std::size_t n, const char* what, pyb::array& keep) {
  if (pyb::isinstance<pyb::array_t<double>>(obj)) {
    keep = pyb::reinterpret_borrow<pyb::array>(obj);
  } else {
    keep = pyb::array_t<double, pyb::array::forcecast>::ensure(obj);
    if (!keep) {
      PyErr_Clear();
      throw pyb::type_error(std::string(what) + " must be a number or an array of one number per ray");
    }
  }
  if (keep.ndim() == 0) return DoubleColumn::constant(DoubleColumn::per_ray(keep.data())[0]);
  if (keep.ndim() != 1 || static_cast<std::size_t>(keep.shape(0)) != n)
    throw pyb::value_error(std::string(what) + " must be a number or have shape (" + std::to_string(n) + ",)");
  return DoubleColumn::per_ray(keep.data(), keep.strides(0));
}

Vec3Column rows(const pyb::array& a) { return {a.data(), a.strides(0), a.strides(1)}; }

}  // namespace

RayArrays ray_arrays(const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
                     const pyb::handle& tmax) {
  RayArrays r;
  r.origins = as_point_rows(origins, "origins");
  r.directions = as_point_rows(directions, "directions");
  if (r.origins.shape(0) != r.directions.shape(0))
    throw pyb::value_error("origins and directions must have the same length, got " +
                           std::to_string(r.origins.shape(0)) + " and " + std::to_string(r.directions.shape(0)));
  const std::size_t n = static_cast<std::size_t>(r.origins.shape(0));
  r.columns.count = n;
  r.columns.origins = rows(r.origins);
  r.columns.directions = rows(r.directions);
  r.columns.tmin = per_ray(tmin, n, "tmin", r.tmin);
  r.columns.tmax = per_ray(tmax, n, "tmax", r.tmax);
  require_valid_rays(r.columns);
  return r;
}

std::vector<Ray> make_rays(const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
                           const pyb::handle& tmax) {
  const RayArrays arrays = ray_arrays(origins, directions, tmin, tmax);
  std::vector<Ray> rays(arrays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) rays[i] = arrays.columns[i];
  return rays;
}

pyb::tuple rays_to_arrays(const std::vector<Ray>& rays) {
  const auto n = static_cast<pyb::ssize_t>(rays.size());
  pyb::array_t<double> org({n, pyb::ssize_t{3}}), dir({n, pyb::ssize_t{3}}), lo(n), hi(n);
  double *po = org.mutable_data(), *pd = dir.mutable_data(), *pl = lo.mutable_data(), *ph = hi.mutable_data();
  for (std::size_t i = 0; i < rays.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      po[3 * i + k] = rays[i].org[k];
      pd[3 * i + k] = rays[i].dir[k];
    }
    pl[i] = rays[i].tmin;
    ph[i] = rays[i].tmax;
  }
  return pyb::make_tuple(org, dir, lo, hi);
}

}  // namespace pierce::py
