// pierce.partitions: per-ray intervals inside solids (Roth 1982 / BRL-CAD partitions).
#include <pybind11/stl.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <limits>

#include "common.h"
#include "pierce/analysis/ray_partitions.h"
#include "progress.h"

namespace pierce::py {

namespace {

// One partition; in_*/out_* are -1 where the interval was clipped to the ray's ends.
struct PartitionRecord {
  std::uint32_t ray;
  double t_in, t_out;
  std::uint64_t first;  // its solids: solids[first:first + count]
  std::uint32_t count;  // >= 2: overlap
  std::int64_t in_geom, in_prim;
  float in_ng[3];
  std::int64_t out_geom, out_prim;
  float out_ng[3];
};

struct Worker {
  HitIterator it;
  PartitionBuilder builder;
  std::vector<Hit> hits;
};

void fill_hit(const Hit& h, std::int64_t& geom, std::int64_t& prim, float (&ng)[3]) {
  geom = h.valid() ? std::int64_t{h.geom} : -1;
  prim = h.valid() ? std::int64_t{h.prim} : -1;
  ng[0] = h.ng.x, ng[1] = h.ng.y, ng[2] = h.ng.z;
}

}  // namespace

void bind_partitions(pyb::module_& m) {
  PYBIND11_NUMPY_DTYPE(PartitionRecord, ray, t_in, t_out, first, count, in_geom, in_prim, in_ng, out_geom, out_prim,
                       out_ng);

  m.def(
      "partitions",
      [](PyScene& s, const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
         const pyb::handle& tmax, const std::string& kernel, const pyb::object& progress, CancelToken* cancel) {
        const KernelKind kind = kernel_from_name(kernel);
        if (!is_exact(kind)) throw pyb::value_error("partitions: kernel must be exact (not 'epsilon')");
        const std::vector<Ray> rays = make_rays(origins, directions, tmin, tmax);
        std::vector<RayPartitions> per_ray(rays.size());
        PyScene::Use use(s);
        run_with_progress(progress, cancel, rays.size(), [&](ProgressState& st) {
          const Accel& accel = s.accel();
          KernelOptions ko;
          ko.order.tie = TieOrder::leave_before_enter;
          const std::size_t n_geoms = s.scene.geometries().size();
          tbb::enumerable_thread_specific<Worker> workers(
              [&] { return Worker{HitIterator(accel, kind, ko), PartitionBuilder(n_geoms), {}}; });
          std::atomic<std::size_t> done{0};
          tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 128), [&](const auto& range) {
            if (st.cancelled()) return;
            Worker& w = workers.local();
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
              // Trace the whole line so solids the ray starts inside are known, then clip.
              w.hits.clear();
              collect_hits(w.it, full_line_ray(rays[i], s.scene.bounds()), 0, w.hits);
              w.builder.build(w.hits, per_ray[i]);
              clip_partitions(per_ray[i], rays[i].tmin, rays[i].tmax);
            }
            st.report(done.fetch_add(range.size()) + range.size());
          });
        });

        std::size_t n_parts = 0, n_solids = 0;
        for (const auto& p : per_ray) n_parts += p.partitions.size(), n_solids += p.solids.size();
        pyb::array_t<PartitionRecord> recs(static_cast<pyb::ssize_t>(n_parts));
        pyb::array_t<std::uint32_t> solids(static_cast<pyb::ssize_t>(n_solids));
        pyb::array_t<std::int64_t> offsets(static_cast<pyb::ssize_t>(rays.size() + 1));
        pyb::array_t<std::uint32_t> unmatched(static_cast<pyb::ssize_t>(rays.size())),
            unclosed(static_cast<pyb::ssize_t>(rays.size()));
        PartitionRecord* r = recs.mutable_data();
        std::uint32_t* so = solids.mutable_data();
        std::size_t k = 0, base = 0;
        for (std::size_t i = 0; i < per_ray.size(); ++i) {
          const RayPartitions& p = per_ray[i];
          offsets.mutable_data()[i] = static_cast<std::int64_t>(k);
          unmatched.mutable_data()[i] = p.unmatched_leaves;
          unclosed.mutable_data()[i] = p.unclosed;
          for (const Partition& q : p.partitions) {
            PartitionRecord& x = r[k++];
            x.ray = static_cast<std::uint32_t>(i);
            x.t_in = q.t_in;
            x.t_out = q.t_out;
            x.first = base + q.first;
            x.count = q.count;
            fill_hit(q.in_hit, x.in_geom, x.in_prim, x.in_ng);
            fill_hit(q.out_hit, x.out_geom, x.out_prim, x.out_ng);
          }
          std::copy(p.solids.begin(), p.solids.end(), so + base);
          base += p.solids.size();
        }
        offsets.mutable_data()[rays.size()] = static_cast<std::int64_t>(k);
        pyb::dict d;
        d["partitions"] = recs;
        d["solids"] = solids;
        d["offsets"] = offsets;
        d["unmatched_leaves"] = unmatched;
        d["unclosed"] = unclosed;
        return d;
      },
      pyb::arg("scene"), pyb::arg("origins"), pyb::arg("directions"), pyb::kw_only(), pyb::arg("tmin") = 0.0,
      pyb::arg("tmax") = std::numeric_limits<double>::infinity(), pyb::arg("kernel") = default_kernel_name(),
      pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Low-level: dict with 'partitions' (structured array, by ray then t), 'solids', 'offsets' (ray i's\n"
      "partitions are partitions[offsets[i]:offsets[i+1]]), 'unmatched_leaves' and 'unclosed' per ray.");
}

}  // namespace pierce::py
