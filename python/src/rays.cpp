// Ray batches between numpy arrays and pierce::Ray.
#include <cmath>

#include "common.h"
#include "pierce/error.h"

namespace pierce::py {

namespace {

// A scalar or one value per ray.
std::vector<double> per_ray(const pyb::handle& obj, std::size_t n, const char* what) {
  auto a = pyb::array_t<double, pyb::array::c_style | pyb::array::forcecast>::ensure(obj);
  if (!a) {
    PyErr_Clear();
    throw pyb::type_error(std::string(what) + " must be a number or an array of one number per ray");
  }
  if (a.ndim() == 0) return std::vector<double>(n, *a.data());
  if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != n)
    throw pyb::value_error(std::string(what) + " must be a number or have shape (" + std::to_string(n) + ",)");
  return std::vector<double>(a.data(), a.data() + n);
}

}  // namespace

std::vector<Ray> make_rays(const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
                           const pyb::handle& tmax) {
  const auto o = as_points(origins, "origins");
  const auto d = as_points(directions, "directions");
  if (o.shape(0) != d.shape(0))
    throw pyb::value_error("origins and directions must have the same length, got " + std::to_string(o.shape(0)) +
                           " and " + std::to_string(d.shape(0)));
  const std::size_t n = static_cast<std::size_t>(o.shape(0));
  const std::vector<double> lo = per_ray(tmin, n, "tmin");
  const std::vector<double> hi = per_ray(tmax, n, "tmax");
  std::vector<Ray> rays(n);
  const double* po = o.data();
  const double* pd = d.data();
  for (std::size_t i = 0; i < n; ++i) {
    Ray& r = rays[i];
    r.org = {po[3 * i], po[3 * i + 1], po[3 * i + 2]};
    r.dir = {pd[3 * i], pd[3 * i + 1], pd[3 * i + 2]};
    r.tmin = lo[i];
    r.tmax = hi[i];
    const std::string where = "ray " + std::to_string(i);
    if (!all_finite(r.org)) throw InputError(where + ": origin is not finite");
    if (!all_finite(r.dir)) throw InputError(where + ": direction is not finite");
    if (r.dir == Vec3d{}) throw InputError(where + ": direction is zero");
    if (std::isnan(r.tmin) || std::isnan(r.tmax)) throw InputError(where + ": tmin/tmax is NaN");
  }
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
