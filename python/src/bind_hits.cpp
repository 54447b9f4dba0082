// pierce._core.trace: every hit of many rays, as one structured array plus per-ray offsets.
#include <pybind11/stl.h>

#include <cmath>
#include <limits>

#include "common.h"
#include "pierce/error.h"
#include "progress.h"

namespace pierce::py {

namespace {

// One row of the structured array returned by trace (numpy dtype "pierce hit").
struct HitRecord {
  std::uint32_t ray;
  double t;
  std::uint32_t geom;
  std::uint32_t prim;
  float u, v;
  float ng[3];
  bool enter;
};

}  // namespace

// Through core's table, so the names and the ValueError's message are the CLI's.
KernelKind kernel_from_name(const std::string& name) { return parse_kernel_or_throw(name); }

std::string default_kernel_name() { return std::string(kernel_name(kDefaultKernel)); }

TieOrder tie_from_name(const std::string& name) { return parse_enum_or_throw<TieOrder>(name); }

void bind_hits(pyb::module_& m) {
  PYBIND11_NUMPY_DTYPE(HitRecord, ray, t, geom, prim, u, v, ng, enter);

  m.def(
      "kernels",
      [](bool include_double) { return kernel_names(include_double); },
      pyb::arg("include_double") = false,
      "Names of the kernels; all but 'epsilon' are exact and agree. include_double adds the kernels on a\n"
      "double-precision BVH, whose answers can differ where the input is not representable in float.");
  m.attr("DEFAULT_KERNEL") = default_kernel_name();
  m.def("is_exact", [](const std::string& name) { return is_exact(kernel_from_name(name)); }, pyb::arg("kernel"));

  m.def(
      "trace",
      [](PyScene& s, const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
         const pyb::handle& tmax, const std::string& kernel, std::size_t max_hits, const std::string& order,
         double epsilon_rel, const pyb::object& progress, CancelToken* cancel) {
        const KernelKind kind = kernel_from_name(kernel);
        KernelOptions opts;
        opts.order.tie = tie_from_name(order);
        opts.epsilon_rel = epsilon_rel;
        // Traced from the caller's arrays in place (converted once only if not float64), held by
        // `rays` until the call returns. They are read without the GIL: a write to them from
        // another thread meanwhile changes what is traced (a ray made bad then gets no hits).
        const RayArrays rays = ray_arrays(origins, directions, tmin, tmax);
        if (rays.size() > std::numeric_limits<std::uint32_t>::max())
          throw pyb::value_error("trace: at most 2^32-1 rays per call");

        HitBatch hits;
        PyScene::Use use(s);
        run_with_progress(progress, cancel, rays.size(), [&](ProgressState& st) {
          const Accel& accel = s.accel();
          trace_batch(accel, kind, rays.columns, max_hits, hits, opts, [&](std::size_t done, std::size_t) { return st.report(done); });
        });

        pyb::array_t<HitRecord> out(static_cast<pyb::ssize_t>(hits.hits.size()));
        pyb::array_t<std::int64_t> offsets(static_cast<pyb::ssize_t>(rays.size() + 1));
        HitRecord* rec = out.mutable_data();
        std::int64_t* off = offsets.mutable_data();
        for (std::size_t i = 0; i < rays.size(); ++i) {
          off[i] = static_cast<std::int64_t>(hits.offsets[i]);
          for (std::size_t k = hits.offsets[i]; k < hits.offsets[i + 1]; ++k) {
            const Hit& h = hits.hits[k];
            rec[k] = HitRecord{static_cast<std::uint32_t>(i), h.t, h.geom, h.prim, h.u, h.v, {h.ng.x, h.ng.y, h.ng.z}, h.enter};
          }
        }
        off[rays.size()] = static_cast<std::int64_t>(hits.hits.size());
        return pyb::make_tuple(out, offsets);
      },
      pyb::arg("scene"), pyb::arg("origins"), pyb::arg("directions"), pyb::kw_only(), pyb::arg("tmin") = 0.0,
      pyb::arg("tmax") = std::numeric_limits<double>::infinity(), pyb::arg("kernel") = default_kernel_name(),
      pyb::arg("max_hits") = 0, pyb::arg("order") = "geom_prim", pyb::arg("epsilon_rel") = 1e-5,
      pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Low-level: returns (hits, offsets); ray i's hits are hits[offsets[i]:offsets[i+1]].");
}

}  // namespace pierce::py
