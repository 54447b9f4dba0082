// Shotlines (BRL-CAD nirt), CSG expressions, point classification and ray-grid quantities (gqa).
#include <pybind11/stl.h>

#include <limits>

#include "common.h"
#include "pierce/analysis/gqa.h"
#include "pierce/analysis/shotline.h"
#include "progress.h"

namespace pierce::py {

namespace {

using namespace pierce::analysis;

// One shotline row; its solids are solids[first:first + count]; in_geom/out_geom -1 where none.
struct ShotRecord {
  std::uint32_t ray;
  std::uint8_t kind;  // SHOT_KINDS index
  double t_in, t_out;
  double in_point[3];
  double out_point[3];
  double los, obliquity_in, obliquity_out, normal_thickness;
  std::int64_t in_geom, out_geom;
  std::uint64_t first;
  std::uint32_t count;
};

std::int64_t id_or_minus_one(std::uint32_t g) { return g == kInvalidId ? -1 : std::int64_t{g}; }

pyb::dict shot_arrays(const ShotResult& r) {
  std::size_t n_solids = 0;
  for (const auto& row : r.rows) n_solids += row.solids.size();
  pyb::array_t<ShotRecord> recs(static_cast<pyb::ssize_t>(r.rows.size()));
  pyb::array_t<std::uint32_t> solids(static_cast<pyb::ssize_t>(n_solids));
  ShotRecord* out = recs.mutable_data();
  std::uint32_t* so = solids.mutable_data();
  std::size_t base = 0;
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const ShotRow& x = r.rows[i];
    out[i] = {x.ray, static_cast<std::uint8_t>(x.kind), x.t_in, x.t_out,
              {x.in_point.x, x.in_point.y, x.in_point.z}, {x.out_point.x, x.out_point.y, x.out_point.z},
              x.los, x.obliquity_in, x.obliquity_out, x.normal_thickness,
              id_or_minus_one(x.in_geom), id_or_minus_one(x.out_geom), base,
              static_cast<std::uint32_t>(x.solids.size())};
    std::copy(x.solids.begin(), x.solids.end(), so + base);
    base += x.solids.size();
  }
  pyb::dict d;
  d["rows"] = recs;
  d["solids"] = solids;
  d["rays"] = r.rays;
  d["rays_hitting"] = r.rays_hitting;
  d["unmatched_leaves"] = r.unmatched_leaves;
  d["unclosed"] = r.unclosed;
  return d;
}

}  // namespace

void bind_shotline(pyb::module_& m) {
  PYBIND11_NUMPY_DTYPE(ShotRecord, ray, kind, t_in, t_out, in_point, out_point, los, obliquity_in, obliquity_out,
                       normal_thickness, in_geom, out_geom, first, count);
  m.attr("SHOT_KINDS") = pyb::make_tuple("solid", "overlap", "region", "gap");
  static_assert(static_cast<int>(ShotKind::gap) == 3);

  m.def(
      "check_csg",
      [](const PyScene& s, const std::string& expr) {
        const CsgExpr e = parse_csg(expr, s.scene);
        return e.solids();
      },
      pyb::arg("scene"), pyb::arg("expr"),
      "Parses a CSG expression (union/intersection/difference over solid names, \"quoted\" names, #N ids)\n"
      "against the scene; returns the geometry ids it uses. Raises pierce.InputError on a bad expression.");

  m.def(
      "shoot",
      [](PyScene& s, const pyb::handle& origins, const pyb::handle& directions, const pyb::handle& tmin,
         const pyb::handle& tmax, const std::string& kernel, const std::optional<std::string>& csg,
         double tie_tolerance_rel, const pyb::object& progress, CancelToken* cancel) {
        const std::vector<Ray> rays = make_rays(origins, directions, tmin, tmax);
        ShotOptions o;
        o.kernel = kernel_from_name(kernel);
        o.tie_tolerance_rel = tie_tolerance_rel;
        std::optional<CsgExpr> expr;
        if (csg) expr = parse_csg(*csg, s.scene);
        o.csg = expr ? &*expr : nullptr;
        const auto result = run_analysis(s, progress, cancel, rays.size(),
                                         [&](const Progress& p) { return shoot(s.accel(), rays, o, p); });
        return shot_arrays(*result);
      },
      pyb::arg("scene"), pyb::arg("origins"), pyb::arg("directions"), pyb::kw_only(), pyb::arg("tmin") = 0.0,
      pyb::arg("tmax") = std::numeric_limits<double>::infinity(), pyb::arg("kernel") = default_kernel_name(),
      pyb::arg("csg") = pyb::none(), pyb::arg("tie_tolerance_rel") = 1e-6, pyb::arg("progress") = pyb::none(),
      pyb::arg("cancel") = nullptr, "Low-level: see pierce.shotlines.");

  m.def(
      "classify_points",
      [](PyScene& s, const pyb::handle& points, const std::string& csg, const std::string& kernel,
         double tolerance_rel, const pyb::object& progress, CancelToken* cancel) {
        const auto p = as_points(points, "points");
        const std::vector<Vec3d> pts = to_vec3d(p);
        for (std::size_t i = 0; i < pts.size(); ++i)
          if (!all_finite(pts[i])) throw pyb::value_error("point " + std::to_string(i) + " is not finite");
        const CsgExpr expr = parse_csg(csg, s.scene);
        const KernelKind kind = kernel_from_name(kernel);
        std::vector<std::uint8_t> cls(pts.size(), 0);
        PyScene::Use use(s);
        run_with_progress(progress, cancel, pts.size(), [&](ProgressState& st) {
          PointClassifier classifier(s.accel(), expr, kind, tolerance_rel);
          for (std::size_t i = 0; i < pts.size(); ++i) {
            cls[i] = static_cast<std::uint8_t>(classifier.classify(pts[i]));
            if ((i & 1023) == 1023 && !st.report(i + 1)) return;
          }
          st.report(pts.size());
        });
        return vector_array(cls);
      },
      pyb::arg("scene"), pyb::arg("points"), pyb::arg("csg"), pyb::kw_only(), pyb::arg("kernel") = default_kernel_name(),
      pyb::arg("tolerance_rel") = 1e-6, pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Per point: 0 outside, 1 inside, 2 on the boundary of the CSG expression (POINT_CLASSES).");
  m.attr("POINT_CLASSES") = pyb::tuple(pyb::cast(enum_names<PointClass>()));

  // --- gqa ---
  pyb::class_<GqaQuantities>(m, "GqaQuantities")
      .def_readonly("name", &GqaQuantities::name)
      .def_readonly("geoms", &GqaQuantities::geoms)
      .def_readonly("volume", &GqaQuantities::volume)
      .def_readonly("centroid", &GqaQuantities::centroid)
      .def_readonly("axis_volume", &GqaQuantities::axis_volume)
      .def_readonly("crossings", &GqaQuantities::crossings)
      .def_readonly("change", &GqaQuantities::change)
      .def("__repr__", [](const GqaQuantities& q) {
        return "<pierce.GqaQuantities '" + q.name + "' volume " + std::to_string(q.volume) + ">";
      });
  pyb::class_<GqaPair>(m, "GqaPair")
      .def_readonly("a", &GqaPair::a)
      .def_readonly("b", &GqaPair::b)
      .def_readonly("count", &GqaPair::count)
      .def_readonly("max_depth", &GqaPair::max_depth)
      .def_readonly("at", &GqaPair::at)
      .def_readonly("axis_max_depth", &GqaPair::axis_max_depth)
      .def_readonly("penetration", &GqaPair::penetration)
      .def_readonly("volume", &GqaPair::volume)
      .def("__repr__", pair_repr<GqaPair>("GqaPair", [](const GqaPair& p) {
        return std::to_string(p.count) + " intervals, penetration " + std::to_string(p.penetration);
      }));
  pyb::class_<GqaPass>(m, "GqaPass")
      .def_readonly("n", &GqaPass::n)
      .def_readonly("rays", &GqaPass::rays)
      .def_readonly("seconds", &GqaPass::seconds)
      .def_readonly("worst_change", &GqaPass::worst_change)
      .def_readonly("worst", &GqaPass::worst);
  pyb::class_<GqaResult>(m, "GqaResult")
      .def_readonly("solids", &GqaResult::solids)
      .def_readonly("regions", &GqaResult::regions)
      .def_readonly("overlaps", &GqaResult::overlaps)
      .def_readonly("gaps", &GqaResult::gaps)
      .def_readonly("passes", &GqaResult::passes)
      .def_readonly("n", &GqaResult::n)
      .def_readonly("tolerance", &GqaResult::tolerance)
      .def_readonly("converged", &GqaResult::converged)
      .def_readonly("completed", &GqaResult::completed)
      .def_readonly("unmatched_leaves", &GqaResult::unmatched_leaves)
      .def_readonly("unclosed", &GqaResult::unclosed);

  m.def(
      "gqa",
      [](PyScene& s, double tolerance, int start_n, int max_n, const std::string& kernel,
         const std::vector<std::string>& regions, double tie_tolerance_rel, double gap_min, double gap_max,
         const pyb::object& progress, CancelToken* cancel) {
        GqaOptions o;
        o.tolerance = tolerance;
        o.start_n = start_n;
        o.max_n = max_n;
        o.kernel = kernel_from_name(kernel);
        for (const auto& r : regions) o.regions.push_back(parse_csg(r, s.scene));
        o.tie_tolerance_rel = tie_tolerance_rel;
        o.gap_min = gap_min;
        o.gap_max = gap_max;
        // Progress is per pass; report it as rays done within the current pass.
        return run_analysis(s, progress, cancel, 0, [&](const Progress& p) {
          return run_gqa(s.accel(), o, [&](int, std::size_t d, std::size_t t) { return p(d, t); });
        });
      },
      pyb::arg("scene"), pyb::kw_only(), pyb::arg("tolerance") = 1e-3, pyb::arg("start_n") = 0,
      pyb::arg("max_n") = 1024, pyb::arg("kernel") = default_kernel_name(), pyb::arg("regions") = std::vector<std::string>{},
      pyb::arg("tie_tolerance_rel") = 1e-6, pyb::arg("gap_min") = 0.0,
      pyb::arg("gap_max") = std::numeric_limits<double>::infinity(), pyb::arg("progress") = pyb::none(),
      pyb::arg("cancel") = nullptr,
      "Volume, centroid and crossings per solid (and CSG region) from refined ray grids along x, y, z, with\n"
      "overlaps and gaps between solids (BRL-CAD gqa).");
}

}  // namespace pierce::py
