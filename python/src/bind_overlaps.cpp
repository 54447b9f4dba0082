// Overlap diagnostics: coplanar triangle pairs, interference along rays, per-triangle heat maps,
// solid pairs classified as clash, contact or clearance.
#include <pybind11/stl.h>

#include <cmath>

#include "common.h"
#include "pierce/analysis/overlaps.h"
#include "pierce/analysis/solid_pairs.h"
#include "progress.h"

namespace pierce::py {

namespace {

using namespace pierce::analysis;

struct CoplanarPairRecord {
  std::uint32_t geom_a, prim_a, geom_b, prim_b;
  double area;
  double centroid[3];
  bool exact;
  bool same_facing;
};

struct InterferenceRecord {
  std::uint32_t ray, a, b;
  double t_enter, t_exit, depth;
  double entry[3];
  double exit[3];
};

// A new numpy array with one Record per element of `items`, converted by to_record.
template <class Record, class Item, class ToRecord>
pyb::array_t<Record> record_array(const std::vector<Item>& items, ToRecord to_record) {
  pyb::array_t<Record> a(static_cast<pyb::ssize_t>(items.size()));
  Record* out = a.mutable_data();
  for (std::size_t i = 0; i < items.size(); ++i) out[i] = to_record(items[i]);
  return a;
}

template <typename T>
pyb::array_t<std::uint64_t> offsets_array(const std::vector<T>& v) {
  return record_array<std::uint64_t>(v, [](const T& offset) { return static_cast<std::uint64_t>(offset); });
}

pyb::array_t<CoplanarPairRecord> coplanar_pairs_array(const CoplanarReport& r) {
  return record_array<CoplanarPairRecord>(r.pairs, [](const CoplanarPair& p) {
    return CoplanarPairRecord{p.geom_a, p.prim_a, p.geom_b, p.prim_b, p.area,
                              {p.centroid.x, p.centroid.y, p.centroid.z}, p.exact, p.same_facing};
  });
}

pyb::array_t<InterferenceRecord> intervals_array(const RayOverlapReport& r) {
  return record_array<InterferenceRecord>(r.intervals, [](const Interference& x) {
    return InterferenceRecord{x.ray, x.a, x.b, x.t_enter, x.t_exit, x.depth, {x.entry.x, x.entry.y, x.entry.z},
                              {x.exit.x, x.exit.y, x.exit.z}};
  });
}

}  // namespace

void bind_overlaps(pyb::module_& m) {
  PYBIND11_NUMPY_DTYPE(CoplanarPairRecord, geom_a, prim_a, geom_b, prim_b, area, centroid, exact, same_facing);
  PYBIND11_NUMPY_DTYPE(InterferenceRecord, ray, a, b, t_enter, t_exit, depth, entry, exit);

  // --- coplanar triangle pairs ---
  pyb::class_<CoplanarSolidPair>(m, "CoplanarSolidPair", "Coplanar overlaps between solids a and b (a == b: inside one).")
      .def_readonly("a", &CoplanarSolidPair::a)
      .def_readonly("b", &CoplanarSolidPair::b)
      .def_readonly("pairs", &CoplanarSolidPair::pairs)
      .def_readonly("exact_pairs", &CoplanarSolidPair::exact_pairs)
      .def_readonly("same_facing", &CoplanarSolidPair::same_facing, "duplicated faces")
      .def_readonly("opposite_facing", &CoplanarSolidPair::opposite_facing, "contacts")
      .def_readonly("area", &CoplanarSolidPair::area)
      .def_readonly("where", &CoplanarSolidPair::where)
      .def("__repr__", pair_repr<CoplanarSolidPair>("CoplanarSolidPair", [](const CoplanarSolidPair& p) {
        return std::to_string(p.pairs) + " pairs, area " + std::to_string(p.area);
      }));
  pyb::class_<CoplanarReport>(m, "CoplanarReport")
      .def_readonly("tolerance", &CoplanarReport::tolerance)
      .def_property_readonly("pairs", &coplanar_pairs_array,
                             "structured array: geom_a, prim_a, geom_b, prim_b, area, centroid[3], exact, same_facing")
      .def_readonly("solid_pairs", &CoplanarReport::solid_pairs)
      .def_readonly("completed", &CoplanarReport::completed);

  m.def(
      "coplanar_overlaps",
      [](PyScene& s, double tolerance, double min_area_rel, const pyb::object& progress, CancelToken* cancel) {
        CoplanarOptions o;
        o.tolerance = tolerance;
        o.min_area_rel = min_area_rel;
        return run_analysis(s, progress, cancel, 0,
                            [&](const Progress& p) { return find_coplanar_overlaps(s.scene, o, p); });
      },
      pyb::arg("scene"), pyb::kw_only(), pyb::arg("tolerance") = 0.0, pyb::arg("min_area_rel") = 1e-9,
      pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Triangle pairs lying in the same plane and overlapping there: duplicated faces (same facing) and\n"
      "contacts between touching solids (opposite facing). tolerance 0: exactly coplanar pairs only.");

  // --- interference and coplanar statistics along rays ---
  pyb::class_<CoplanarRayStats>(m, "CoplanarRayStats", "Gribble et al.'s coplanar-hit statistic.")
      .def_readonly("rays", &CoplanarRayStats::rays)
      .def_readonly("rays_hitting", &CoplanarRayStats::rays_hitting)
      .def_readonly("rays_equal_t", &CoplanarRayStats::rays_equal_t)
      .def_readonly("rays_within_eps", &CoplanarRayStats::rays_within_eps)
      .def_readonly("epsilon", &CoplanarRayStats::epsilon)
      .def_property_readonly("share_equal", &CoplanarRayStats::share_equal)
      .def_property_readonly("share_within_eps", &CoplanarRayStats::share_within_eps);
  pyb::class_<InterferencePair>(m, "InterferencePair", "Solids a < b whose insides overlap along rays.")
      .def_readonly("a", &InterferencePair::a)
      .def_readonly("b", &InterferencePair::b)
      .def_readonly("count", &InterferencePair::count)
      .def_readonly("max_depth", &InterferencePair::max_depth, "largest line-of-sight depth inside both")
      .def_readonly("max_depth_entry", &InterferencePair::max_depth_entry)
      .def_readonly("max_depth_ray", &InterferencePair::max_depth_ray)
      .def_readonly("axis_max_depth", &InterferencePair::axis_max_depth)
      .def_readonly("penetration", &InterferencePair::penetration,
                    "smallest over axes of the largest axis-parallel depth (NaN: no axis ray)")
      .def("__repr__", pair_repr<InterferencePair>("InterferencePair", [](const InterferencePair& p) {
        return std::to_string(p.count) + " intervals, max depth " + std::to_string(p.max_depth) + ", penetration " +
               std::to_string(p.penetration);
      }));
  pyb::class_<ContactPair>(m, "ContactPair", "Solids a < b touching at a shared surface (no overlap).")
      .def_readonly("a", &ContactPair::a)
      .def_readonly("b", &ContactPair::b)
      .def_readonly("count", &ContactPair::count)
      .def_readonly("where", &ContactPair::where)
      .def("__repr__", pair_repr<ContactPair>("ContactPair", [](const ContactPair& p) {
        return std::to_string(p.count) + " rays";
      }));
  pyb::class_<RayOverlapReport>(m, "RayOverlapReport")
      .def_readonly("coplanar", &RayOverlapReport::coplanar)
      .def_property_readonly("intervals", &intervals_array,
                             "structured array: ray, a, b, t_enter, t_exit, depth, entry[3], exit[3]")
      .def_readonly("interferences", &RayOverlapReport::interferences)
      .def_readonly("contacts", &RayOverlapReport::contacts)
      .def_readonly("rays_ending_inside", &RayOverlapReport::rays_ending_inside)
      .def_property_readonly("tri_offset", [](const RayOverlapReport& r) { return offsets_array(r.tri_offset); })
      .def_property_readonly("coplanar_hits", [](const RayOverlapReport& r) { return vector_array(r.coplanar_hits); })
      .def_property_readonly("interference_hits",
                             [](const RayOverlapReport& r) { return vector_array(r.interference_hits); })
      .def_readonly("completed", &RayOverlapReport::completed);

  m.def(
      "axis_grid_rays",
      [](const PyScene& s, int n, std::vector<int> axes) {
        if (n < 1) throw pyb::value_error("axis_grid_rays: n must be >= 1");
        for (int a : axes)
          if (a < 0 || a > 2) throw pyb::value_error("axis_grid_rays: axes are 0 (x), 1 (y), 2 (z)");
        return rays_to_arrays(axis_grid_rays(s.scene.bounds(), n, axes));
      },
      pyb::arg("scene"), pyb::arg("n"), pyb::arg("axes") = std::vector<int>{0, 1, 2},
      "n x n parallel rays along each axis through the scene bounds: (origins, directions, tmin, tmax).");

  m.def(
      "ray_overlaps",
      [](PyScene& s, const pyb::object& origins, const pyb::object& directions, const pyb::handle& tmin,
         const pyb::handle& tmax, int grid, std::vector<int> axes, const std::string& kernel, double epsilon_rel,
         double tie_tolerance_rel, bool keep_intervals, const pyb::object& progress, CancelToken* cancel) {
        std::vector<Ray> rays;
        if (origins.is_none() != directions.is_none())
          throw pyb::value_error("ray_overlaps: give both origins and directions, or neither (grid rays)");
        if (!origins.is_none()) {
          rays = make_rays(origins, directions, tmin, tmax);
        } else {
          if (grid < 1) throw pyb::value_error("ray_overlaps: grid must be >= 1");
          for (int a : axes)
            if (a < 0 || a > 2) throw pyb::value_error("ray_overlaps: axes are 0 (x), 1 (y), 2 (z)");
          rays = axis_grid_rays(s.scene.bounds(), grid, axes);
        }
        RayOverlapOptions o;
        o.kernel = kernel_from_name(kernel);
        o.epsilon_rel = epsilon_rel;
        o.tie_tolerance_rel = tie_tolerance_rel;
        o.keep_intervals = keep_intervals;
        return run_analysis(s, progress, cancel, rays.size(),
                            [&](const Progress& p) { return analyse_ray_overlaps(s.accel(), rays, o, p); });
      },
      pyb::arg("scene"), pyb::arg("origins") = pyb::none(), pyb::arg("directions") = pyb::none(), pyb::kw_only(),
      pyb::arg("tmin") = 0.0, pyb::arg("tmax") = std::numeric_limits<double>::infinity(), pyb::arg("grid") = 64,
      pyb::arg("axes") = std::vector<int>{0, 1, 2}, pyb::arg("kernel") = default_kernel_name(), pyb::arg("epsilon_rel") = 1e-5,
      pyb::arg("tie_tolerance_rel") = 1e-6, pyb::arg("keep_intervals") = true, pyb::arg("progress") = pyb::none(),
      pyb::arg("cancel") = nullptr,
      "Solid-solid interference along rays (BRL-CAD's OVERLAP report), contacts, and the coplanar-hit\n"
      "statistic. Rays: the given ones, else grid x grid rays along each of `axes` through the bounds.");

  m.def(
      "triangle_overlap_arrays",
      [](const PyScene& s, const CoplanarReport* coplanar, const RayOverlapReport* rays) {
        const TriangleOverlapArrays a = triangle_overlap_arrays(s.scene, coplanar, rays);
        pyb::dict d;
        d["tri_offset"] = offsets_array(a.tri_offset);
        d["solid"] = vector_array(a.solid);
        d["coplanar_count"] = vector_array(a.coplanar_count);
        d["coplanar_partner"] = vector_array(a.coplanar_partner);
        d["coplanar_hits"] = vector_array(a.coplanar_hits);
        d["interference_hits"] = vector_array(a.interference_hits);
        d["overlap_count"] = vector_array(a.overlap_count);
        return d;
      },
      pyb::arg("scene"), pyb::arg("coplanar") = nullptr, pyb::arg("rays") = nullptr,
      "Per-triangle heat-map arrays (triangle (g, p) at tri_offset[g] + p) from either or both reports.");

  // --- solid pairs: clash, contact, clearance ---
  pyb::class_<SolidPair>(m, "SolidPair",
                         "Solids solid_a < solid_b that clash, touch or come within the clearance; fields that do\n"
                         "not apply to the kind are NaN (point_b of a contact).")
      .def_readonly("solid_a", &SolidPair::solid_a)
      .def_readonly("solid_b", &SolidPair::solid_b)
      .def_property_readonly("kind", [](const SolidPair& p) { return std::string(enum_name(p.kind)); },
                             "'clash', 'contact' or 'clearance'")
      .def_readonly("gap", &SolidPair::gap, "contact: 0; clearance: the smallest distance")
      .def_readonly("depth", &SolidPair::depth, "clash: how far one must move to clear the other")
      .def_readonly("overlap_length", &SolidPair::overlap_length, "clash: longest overlap along a ray")
      .def_readonly("volume", &SolidPair::volume, "clash: shared volume estimated from the ray grid")
      .def_readonly("point", &SolidPair::point)
      .def_readonly("point_b", &SolidPair::point_b)
      .def("__repr__", [](const SolidPair& p) {
        const std::string kind(enum_name(p.kind));
        const double v = p.kind == PairKind::clash ? p.depth : p.gap;
        return "<pierce.SolidPair " + std::to_string(p.solid_a) + "-" + std::to_string(p.solid_b) + ": " + kind +
               (p.kind == PairKind::clash ? ", depth " : ", gap ") + std::to_string(v) + ">";
      });
  pyb::class_<SolidPairReport>(m, "SolidPairReport")
      .def_readonly("clearance", &SolidPairReport::clearance)
      .def_readonly("pairs", &SolidPairReport::pairs, "clash (deepest first), contact, clearance (nearest first)")
      .def_property_readonly("tri_offset", [](const SolidPairReport& r) { return offsets_array(r.tri_offset); })
      .def_property_readonly("triangle_clearance",
                             [](const SolidPairReport& r) { return vector_array(r.triangle_clearance); },
                             "per triangle: distance to the nearest other solid, capped at clearance")
      .def_readonly("completed", &SolidPairReport::completed);

  m.def(
      "clearance",
      [](PyScene& s, double clearance, int grid, const std::string& kernel, const pyb::object& progress,
         CancelToken* cancel) {
        if (!(clearance >= 0) || !std::isfinite(clearance))
          throw pyb::value_error("clearance: clearance must be a finite number >= 0");
        if (grid < 1) throw pyb::value_error("clearance: grid must be >= 1");
        SolidPairOptions o;
        o.clearance = clearance;
        o.grid_n = grid;
        o.kernel = kernel_from_name(kernel);
        return run_analysis(s, progress, cancel, 0,
                            [&](const Progress& p) { return analyse_solid_pairs(s.accel(), o, p); });
      },
      pyb::arg("scene"), pyb::kw_only(), pyb::arg("clearance") = 0.0, pyb::arg("grid") = 128,
      pyb::arg("kernel") = default_kernel_name(), pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Every pair of solids within `clearance`: clash (interiors overlap along grid x grid rays per axis),\n"
      "contact (faces lie on one another, gap 0) or clearance (exact smallest distance below `clearance`).");
}

}  // namespace pierce::py
