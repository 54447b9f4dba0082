#pragma once
// Shared pieces of the bindings: the Python-side scene (scene + lazily built acceleration
// structures) and numpy conversion helpers.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include "pierce/analysis/exact_surface.h"
#include "pierce/io/cad_io.h"
#include "pierce/kernel.h"
#include "pierce/kernel_names.h"
#include "pierce/progress.h"
#include "pierce/ray_columns.h"
#include "pierce/scene.h"
#include "progress.h"

namespace pierce::py {

namespace pyb = pybind11;

// A Scene plus the acceleration structures over it, built on first use and dropped when
// geometry is added. Long calls mark the scene busy so it cannot change under them.
class PyScene {
 public:
  Scene scene;
  // CAD files (add_model_files): per geometry its link to the B-rep (empty for meshes), and the
  // exact surfaces over them that thickness maps sample (null when there is no CAD geometry).
  std::vector<CadLink> cad;
  std::shared_ptr<const analysis::ExactSurfaces> exact;

  // Builds the acceleration structures if needed. Call without the GIL.
  const Accel& accel();

  // While alive, add_mesh refuses to run (a call on another thread is reading the scene).
  class Use {
   public:
    explicit Use(PyScene& s) : s_(s) { ++s_.users_; }
    ~Use() { --s_.users_; }
    Use(const Use&) = delete;
    Use& operator=(const Use&) = delete;

   private:
    PyScene& s_;
  };
  bool in_use() const { return users_.load() > 0; }
  void invalidate_accel() { accel_.reset(); }

 private:
  std::mutex accel_mutex_;
  std::unique_ptr<Accel> accel_;
  std::atomic<int> users_{0};
};

// Runs `analysis(progress)` on a worker thread (run_with_progress) with `s` marked in use, and
// returns its result on the heap for the Python object to own. `analysis` reports through the
// pierce::Progress it is given; `total` is the initial total (0 when unknown).
template <class Analysis>
auto run_analysis(PyScene& s, const pyb::object& progress, CancelToken* cancel, std::size_t total, Analysis analysis) {
  auto result = std::make_unique<decltype(analysis(Progress{}))>();
  PyScene::Use use(s);
  run_with_progress(progress, cancel, total, [&](ProgressState& st) {
    *result = analysis([&st](std::size_t done, std::size_t all) { return st.report(done, all); });
  });
  return result;
}

// (N, 3) float64 rows from any array-like (lists, float32, non-contiguous): no copy when the
// input already is C-contiguous float64. `what` names the argument in error messages.
pyb::array_t<double, pyb::array::c_style> as_points(const pyb::handle& obj, const char* what);

// as_points, but a float64 array in native byte order is returned as it is, whatever its strides
// (read it through its strides, e.g. as a Vec3Column); anything else is converted once.
pyb::array as_point_rows(const pyb::handle& obj, const char* what);

// Checked copy into Vec3d rows.
std::vector<Vec3d> to_vec3d(const pyb::array_t<double, pyb::array::c_style>& a);

// (M, 3) triangle indices from any integer array-like, checked to be >= 0 and < 2^32.
std::vector<Tri> to_triangles(const pyb::handle& obj, const char* what);

// A read-only numpy view of `count` rows of `cols` elements at `data`, keeping `owner` alive.
template <typename T>
pyb::array readonly_view(const T* data, std::size_t count, std::size_t cols, const pyb::handle& owner) {
  std::vector<pyb::ssize_t> shape{static_cast<pyb::ssize_t>(count)};
  std::vector<pyb::ssize_t> strides{static_cast<pyb::ssize_t>(sizeof(T) * (cols ? cols : 1))};
  if (cols) {
    shape.push_back(static_cast<pyb::ssize_t>(cols));
    strides.push_back(sizeof(T));
  }
  pyb::array a(pyb::dtype::of<T>(), shape, strides, data, owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

// A new (N,) numpy array holding a copy of `v`.
template <typename T>
pyb::array_t<T> vector_array(const std::vector<T>& v) {
  pyb::array_t<T> a(static_cast<pyb::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}

// The __repr__ of a record of solids a and b: "<pierce.<type> a-b: <details(p)>>".
template <class Pair, class Details>
auto pair_repr(const char* type, Details details) {
  return [type = std::string(type), details](const Pair& p) {
    return "<pierce." + type + " " + std::to_string(p.a) + "-" + std::to_string(p.b) + ": " + details(p) + ">";
  };
}

// The getter of a read-only property viewing the vector member `column` of the bound object
// (kept alive by the view): (N,) for numbers, (N, 3) for Vec3 rows.
template <class Owner, class Element>
auto readonly_column(std::vector<Element> Owner::*column) {
  return [column](pyb::object self) {
    const std::vector<Element>& v = self.cast<const Owner&>().*column;
    if constexpr (std::is_arithmetic_v<Element>) return readonly_view(v.data(), v.size(), 0, self);
    else return readonly_view(v.empty() ? nullptr : &v.data()->x, v.size(), 3, self);
  };
}

KernelKind kernel_from_name(const std::string& name);
// kDefaultKernel's name: the default of every `kernel` argument.
std::string default_kernel_name();
TieOrder tie_from_name(const std::string& name);

// Rays as columns over (N, 3) origins and directions and a scalar or per-ray tmin/tmax, checked
// (ValueError/TypeError on shapes, InputError naming the first bad ray: non-finite origin or
// direction, zero direction, NaN bounds). float64 arrays are read where they are, whatever their
// strides; other array-likes are converted once and the copy is held here.
struct RayArrays {
  pyb::array origins, directions, tmin, tmax;  // what `columns` points into
  RayColumns columns;
  std::size_t size() const { return columns.size(); }
};
RayArrays ray_arrays(const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
                     const pyb::handle& tmax);

// ray_arrays' rays as a vector, for the analyses that take a list of Rays.
std::vector<Ray> make_rays(const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
                           const pyb::handle& tmax);
// (origins, directions, tmin, tmax) arrays of a ray list.
pyb::tuple rays_to_arrays(const std::vector<Ray>& rays);

// (2, 3) array: min corner, max corner.
pyb::array_t<double> bounds_array(const BBoxd& b);

void bind_scene(pyb::module_& m);
void bind_hits(pyb::module_& m);
void bind_thickness(pyb::module_& m);
void bind_overlaps(pyb::module_& m);
void bind_partitions(pyb::module_& m);
void bind_shotline(pyb::module_& m);
void bind_io(pyb::module_& m);

}  // namespace pierce::py

// Vec3d <-> (x, y, z) tuple, so result structs convert without wrapper classes.
namespace pybind11::detail {
template <>
struct type_caster<pierce::Vec3d> {
  PYBIND11_TYPE_CASTER(pierce::Vec3d, const_name("tuple[float, float, float]"));
  bool load(handle src, bool) {
    if (!isinstance<sequence>(src) || isinstance<str>(src)) return false;
    const auto seq = reinterpret_borrow<sequence>(src);
    if (seq.size() != 3) return false;
    value = {seq[0].cast<double>(), seq[1].cast<double>(), seq[2].cast<double>()};
    return true;
  }
  static handle cast(const pierce::Vec3d& v, return_value_policy, handle) {
    return make_tuple(v.x, v.y, v.z).release();
  }
};
}  // namespace pybind11::detail
