// pierce.thickness: wall-thickness maps (ray, cone, sphere), results as zero-copy numpy views.
#include <pybind11/stl.h>

#include <limits>
#include <optional>

#include "common.h"
#include "pierce/analysis/thickness.h"
#include "progress.h"

namespace pierce::py {

namespace {

using namespace pierce::analysis;

ThicknessOptions make_options(const PyScene& s, const std::string& method, const std::string& per,
                              double max_distance, double min_thickness, double max_thickness, int cone_rays, double cone_angle,
                              const std::string& cone_aggregate, int sphere_max_iterations, double tie_tolerance_rel,
                              const std::string& kernel, std::vector<std::uint32_t> solids,
                              const std::optional<std::vector<double>>& percentiles, int histogram_bins) {
  ThicknessOptions o;
  o.method = parse_enum_or_throw<ThicknessMethod>(method);
  o.per = parse_enum_or_throw<SampleAt>(per);
  o.max_distance = max_distance;
  o.min_thickness = min_thickness;
  o.max_thickness = max_thickness;
  o.cone_rays = cone_rays;
  o.cone_angle_deg = cone_angle;
  o.cone_aggregate = parse_enum_or_throw<ConeAggregate>(cone_aggregate);
  o.sphere_max_iterations = sphere_max_iterations;
  o.tie_tolerance_rel = tie_tolerance_rel;
  o.kernel = kernel_from_name(kernel);
  o.solids = std::move(solids);
  if (percentiles) o.percentiles = *percentiles;
  o.histogram_bins = histogram_bins;
  o.exact = s.exact.get();
  for (auto g : o.solids)
    if (g >= s.scene.geometries().size())
      throw pyb::value_error("thickness: solid " + std::to_string(g) + " is not in the scene (it has " +
                             std::to_string(s.scene.geometries().size()) + " geometries)");
  return o;
}

// Geometry ids from `ids`, one integer for all n items or an array of one per item, each in the
// scene. `what` names the argument in the type and shape errors; out_of_scene(i, id) is the
// message for item i's id outside the scene.
template <class Message>
std::vector<std::uint32_t> geometry_ids(const PyScene& s, const pyb::handle& ids, std::size_t n,
                                        const std::string& what, Message out_of_scene) {
  auto g = pyb::array_t<std::int64_t, pyb::array::c_style | pyb::array::forcecast>::ensure(ids);
  if (!g) {
    PyErr_Clear();
    throw pyb::type_error(what + " must be an integer or an array of geometry ids");
  }
  if (g.ndim() > 1 || (g.ndim() == 1 && static_cast<std::size_t>(g.size()) != n))
    throw pyb::value_error(what + " must be one id or one per point");
  std::vector<std::uint32_t> geom(n);
  const auto n_geoms = static_cast<std::int64_t>(s.scene.geometries().size());
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t v = g.ndim() == 0 ? *g.data() : g.data()[i];
    if (v < 0 || v >= n_geoms) throw pyb::value_error(out_of_scene(i, v));
    geom[i] = static_cast<std::uint32_t>(v);
  }
  return geom;
}

}  // namespace

void bind_thickness(pyb::module_& m) {
  pyb::class_<Histogram>(m, "Histogram")
      .def_readonly("edges", &Histogram::edges, "bins + 1 increasing edges")
      .def_readonly("counts", &Histogram::counts, "counts[i]: values in [edges[i], edges[i+1]) (last bin closed)");

  pyb::class_<Summary>(m, "Summary", "Statistics over the finite values.")
      .def_readonly("count", &Summary::count)
      .def_readonly("min", &Summary::min)
      .def_readonly("max", &Summary::max)
      .def_readonly("mean", &Summary::mean)
      .def_readonly("percentiles", &Summary::percentiles, "[(q in 0..100, value), ...]")
      .def_readonly("histogram", &Summary::histogram)
      .def(
          "percentile",
          [](const Summary& s, double q) {
            for (const auto& [k, v] : s.percentiles)
              if (k == q) return v;
            throw pyb::key_error("percentile " + std::to_string(q) + " was not computed");
          },
          pyb::arg("q"))
      .def("__repr__", [](const Summary& s) {
        return "<pierce.Summary count=" + std::to_string(s.count) + " min=" + std::to_string(s.min) +
               " mean=" + std::to_string(s.mean) + " max=" + std::to_string(s.max) + ">";
      });

  pyb::class_<SolidThickness>(m, "SolidThickness", "Per-solid thickness statistics.")
      .def_readonly("geom", &SolidThickness::geom)
      .def_readonly("name", &SolidThickness::name)
      .def_readonly("elements", &SolidThickness::elements)
      .def_readonly("valid", &SolidThickness::valid)
      .def_readonly("no_exit", &SolidThickness::no_exit)
      .def_readonly("no_normal", &SolidThickness::no_normal)
      .def_readonly("thin", &SolidThickness::thin)
      .def_readonly("tessellation", &SolidThickness::tessellation,
                    "CAD: samples excluded as tessellation artefacts (status tessellation)")
      .def_readonly("edge_samples", &SolidThickness::edge_samples,
                    "CAD: vertices on B-rep edges, showing the smaller of their per-face samples")
      .def_readonly("exact", &SolidThickness::exact, "sampled on the exact B-rep (CAD input)")
      .def_readonly("summary", &SolidThickness::summary)
      .def("__repr__", [](const SolidThickness& s) {
        return "<pierce.SolidThickness " + std::to_string(s.geom) + " '" + s.name + "': " +
               std::to_string(s.valid) + "/" + std::to_string(s.elements) + " valid, min " +
               std::to_string(s.summary.min) + ">";
      });

  pyb::class_<ThicknessRegion>(m, "ThicknessRegion",
                                "A thin or thick wall: samples of one solid connected on its surface, both sides "
                                "of the wall (see docs/THICKNESS.md, Regions).")
      .def_readonly("solid", &ThicknessRegion::solid, "geometry id")
      .def_readonly("thickness", &ThicknessRegion::thickness,
                    "the extreme thickness: minimum of a thin region, maximum of a thick one")
      .def_readonly("thick", &ThicknessRegion::thick, "a thick region (else a thin one)")
      .def_property_readonly(
          "min_thickness", [](const ThicknessRegion& g) { return g.thick ? pyb::object(pyb::none()) : pyb::float_(g.thickness); },
          "a thin region's minimum thickness (None for a thick region)")
      .def_property_readonly(
          "max_thickness", [](const ThicknessRegion& g) { return g.thick ? pyb::object(pyb::float_(g.thickness)) : pyb::none(); },
          "a thick region's maximum thickness (None for a thin region)")
      .def_property_readonly("point", [](const ThicknessRegion& g) { return std::vector<double>{g.point.x, g.point.y, g.point.z}; },
                             "[x, y, z] of the extreme sample")
      .def_property_readonly("exit", [](const ThicknessRegion& g) { return std::vector<double>{g.exit.x, g.exit.y, g.exit.z}; },
                             "[x, y, z] where that sample's ray leaves the solid")
      .def_readonly("area", &ThicknessRegion::area, "flagged surface area, both sides of the wall")
      .def_property_readonly("area_sides", [](const ThicknessRegion&) { return "both"; })
      .def_readonly("samples", &ThicknessRegion::samples, "samples in the region")
      .def_readonly("faces", &ThicknessRegion::faces, "CAD: B-rep face indices holding its area; empty for meshes")
      .def("__repr__", [](const ThicknessRegion& g) {
        return "<pierce.ThicknessRegion solid " + std::to_string(g.solid) + " thickness " + std::to_string(g.thickness) +
               " area " + std::to_string(g.area) + " samples " + std::to_string(g.samples) + ">";
      });

  // Arrays are read-only views into the result (kept alive by them).
  pyb::class_<ThicknessResult>(m, "ThicknessResult",
                               "One entry per sampled element, solid by solid; element = vertex or triangle "
                               "index in its geometry.")
      .def_property_readonly("per", [](const ThicknessResult& r) { return std::string(enum_name(r.per)); })
      .def_readonly("completed", &ThicknessResult::completed)
      .def_readonly("solids", &ThicknessResult::solids, "per-solid statistics (SolidThickness)")
      .def("__len__", &ThicknessResult::size)
      .def_property_readonly("solid", readonly_column(&ThicknessResult::solid), "(N,) uint32 geometry id")
      .def_property_readonly("element", readonly_column(&ThicknessResult::element),
                             "(N,) uint32 vertex or triangle index")
      .def_property_readonly("point", readonly_column(&ThicknessResult::point), "(N, 3) sample points")
      .def_property_readonly("normal", readonly_column(&ThicknessResult::normal),
                             "(N, 3) unit outward normals (zero where none)")
      .def_property_readonly("thickness", readonly_column(&ThicknessResult::thickness),
                             "(N,) float64, NaN where there is none")
      .def_property_readonly("thin", [](pyb::object self) {
        const auto& r = self.cast<const ThicknessResult&>();
        static_assert(sizeof(bool) == sizeof(std::uint8_t));
        pyb::array a(pyb::dtype("bool"), {static_cast<pyb::ssize_t>(r.thin.size())}, {}, r.thin.data(), self);
        a.attr("flags").attr("writeable") = false;
        return a;
      }, "(N,) bool, thickness < min_thickness")
      .def_property_readonly("status", [](pyb::object self) {
        const auto& r = self.cast<const ThicknessResult&>();
        static_assert(sizeof(ThicknessStatus) == sizeof(std::uint8_t));
        return readonly_view(reinterpret_cast<const std::uint8_t*>(r.status.data()), r.status.size(), 0, self);
      }, "(N,) uint8: 0 ok, 1 no_exit, 2 no_normal, 3 tessellation (see THICKNESS_STATUS)")
      .def_property_readonly("region", readonly_column(&ThicknessResult::region),
                             "(N,) int32 region id, -1 for none: below len(thin_regions) an index into thin_regions, "
                             "else into thick_regions after subtracting len(thin_regions)")
      .def_readonly("thin_regions", &ThicknessResult::thin_regions,
                    "ThicknessRegion list, thinnest first (thickness strictly below min_thickness)")
      .def_readonly("thick_regions", &ThicknessResult::thick_regions,
                    "ThicknessRegion list, thickest first (thickness strictly above max_thickness)")
      .def_property_readonly("brep_faces", readonly_column(&ThicknessResult::brep_faces),
                             "(N,) uint8 CAD: B-rep faces sampled at the element (2+: a vertex on an edge, the "
                             "smallest kept); empty for meshes")
      .def("__repr__", [](const ThicknessResult& r) {
        return "<pierce.ThicknessResult " + std::to_string(r.size()) + " " +
               (r.per == SampleAt::vertex ? "vertices" : "faces") + ", " + std::to_string(r.solids.size()) +
               " solids>";
      });
  // Names from core's tables (enum_names.h), as the CLI spells them; THICKNESS_STATUS[i] is the
  // name of status code i.
  m.attr("THICKNESS_STATUS") = pyb::tuple(pyb::cast(enum_names<ThicknessStatus>()));
  m.def("thickness_methods", [] { return enum_names<ThicknessMethod>(); },
        "Names of the thickness methods (thickness(method=...)).");
  m.def(
      "default_color_range",
      [](const std::vector<double>& values, double min_thickness) {
        return default_color_range(values, min_thickness);
      },
      pyb::arg("values"), pyb::arg("min_thickness") = 0.0,
      "(lo, hi): the colour range every front end gives a thickness map by default: with a thin threshold\n"
      "min_thickness > 0, 0 to COLOR_RANGE_THIN_FACTOR x min_thickness; otherwise the COLOR_RANGE_PERCENTILES\n"
      "of the finite values. Values outside take the colour of the nearer end.");
  m.attr("COLOR_RANGE_THIN_FACTOR") = kColorRangeThinFactor;
  m.attr("COLOR_RANGE_PERCENTILES") = pyb::make_tuple(kColorRangePercentiles[0], kColorRangePercentiles[1]);
  m.def(
      "thickness_defaults",
      [] {
        const ThicknessOptions o;
        pyb::dict d;
        d["method"] = std::string(enum_name(o.method));
        d["per"] = std::string(enum_name(o.per));
        return d;
      },
      "The thickness defaults every front end uses (the CLI's --method and --per): method, per.");
  m.def("thickness_samplings", [] { return enum_names<SampleAt>(); },
        "Names of the sample locations (thickness(per=...)).");
  m.def("cone_aggregates", [] { return enum_names<ConeAggregate>(); },
        "Names of the cone method's aggregates (thickness(cone_aggregate=...)).");

  m.def(
      "thickness",
      [](PyScene& s, const std::string& method, const std::string& per, double max_distance, double min_thickness,
         double max_thickness, int cone_rays, double cone_angle, const std::string& cone_aggregate, int sphere_max_iterations,
         double tie_tolerance_rel, const std::string& kernel, std::vector<std::uint32_t> solids,
         std::optional<std::vector<double>> percentiles, int histogram_bins, const pyb::object& progress,
         CancelToken* cancel) {
        const ThicknessOptions o = make_options(s, method, per, max_distance, min_thickness, max_thickness, cone_rays, cone_angle,
                                                cone_aggregate, sphere_max_iterations, tie_tolerance_rel, kernel,
                                                std::move(solids), percentiles, histogram_bins);
        return run_analysis(s, progress, cancel, 0,
                            [&](const Progress& p) { return compute_thickness(s.accel(), o, p); });
      },
      pyb::arg("scene"), pyb::kw_only(), pyb::arg("method") = std::string(enum_name(ThicknessOptions{}.method)),
      pyb::arg("per") = std::string(enum_name(ThicknessOptions{}.per)),
      pyb::arg("max_distance") = std::numeric_limits<double>::infinity(), pyb::arg("min_thickness") = 0.0,
      pyb::arg("max_thickness") = std::numeric_limits<double>::infinity(), pyb::arg("cone_rays") = 30, pyb::arg("cone_angle") = 120.0, pyb::arg("cone_aggregate") = "shapira",
      pyb::arg("sphere_max_iterations") = 100, pyb::arg("tie_tolerance_rel") = 1e-6, pyb::arg("kernel") = default_kernel_name(),
      pyb::arg("solids") = std::vector<std::uint32_t>{}, pyb::arg("percentiles") = pyb::none(),
      pyb::arg("histogram_bins") = 20, pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Wall thickness per vertex or per face of the given solids (all when empty); the other solids take part\n"
      "as neighbours. method: ray (along the inward normal to where the ray leaves the solid), cone\n"
      "(shape-diameter function over cone_rays rays in a cone_angle-degree cone) or sphere (largest inscribed\n"
      "ball). Elements whose ray escapes (open mesh, beyond max_distance) get NaN, status no_exit.\n"
      "CAD files (add_model_files) are sampled on the exact B-rep with exits refined on it; tessellation\n"
      "artefacts get NaN, status tessellation, and are left out of the statistics (SolidThickness.tessellation).\n"
      "With min_thickness > 0 (thin: strictly below it) or a finite max_thickness (thick: strictly above it),\n"
      "flagged samples are grouped into regions (thin_regions, thick_regions, region).");

  m.def(
      "thickness_at",
      [](PyScene& s, const pyb::handle& solids, const pyb::handle& points, const pyb::object& normals,
         const std::string& method, double max_distance, double min_thickness, int cone_rays, double cone_angle,
         const std::string& cone_aggregate, int sphere_max_iterations, double tie_tolerance_rel,
         const std::string& kernel, std::optional<std::vector<double>> percentiles, int histogram_bins,
         const pyb::object& progress, CancelToken* cancel) {
        const auto pts = as_points(points, "points");
        const auto n = static_cast<std::size_t>(pts.shape(0));
        std::vector<Vec3d> p(n), nv;
        for (std::size_t i = 0; i < n; ++i) p[i] = {pts.at(i, 0), pts.at(i, 1), pts.at(i, 2)};
        if (!normals.is_none()) {
          const auto nn = as_points(normals, "normals");
          if (static_cast<std::size_t>(nn.shape(0)) != n) throw pyb::value_error("normals: one per point");
          nv.resize(n);
          for (std::size_t i = 0; i < n; ++i) nv[i] = {nn.at(i, 0), nn.at(i, 1), nn.at(i, 2)};
        }
        const std::vector<std::uint32_t> geom = geometry_ids(s, solids, n, "solids", [](std::size_t i, std::int64_t v) {
          return "thickness_at: point " + std::to_string(i) + ": solid " + std::to_string(v) + " is not in the scene";
        });
        const ThicknessOptions o = make_options(s, method, "face", max_distance, min_thickness,
                                                std::numeric_limits<double>::infinity(), cone_rays, cone_angle,
                                                cone_aggregate, sphere_max_iterations, tie_tolerance_rel, kernel, {},
                                                percentiles, histogram_bins);
        return run_analysis(s, progress, cancel, 0,
                            [&](const Progress& report) { return thickness_at(s.accel(), geom, p, nv, o, report); });
      },
      pyb::arg("scene"), pyb::arg("solids"), pyb::arg("points"), pyb::arg("normals") = pyb::none(), pyb::kw_only(),
      pyb::arg("method") = "ray", pyb::arg("max_distance") = std::numeric_limits<double>::infinity(),
      pyb::arg("min_thickness") = 0.0, pyb::arg("cone_rays") = 30, pyb::arg("cone_angle") = 120.0,
      pyb::arg("cone_aggregate") = "shapira", pyb::arg("sphere_max_iterations") = 100,
      pyb::arg("tie_tolerance_rel") = 1e-6, pyb::arg("kernel") = default_kernel_name(), pyb::arg("percentiles") = pyb::none(),
      pyb::arg("histogram_bins") = 20, pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Thickness at given points (N, 3) of solids (one id or one per point), like a caliper: each point is\n"
      "projected onto its solid's boundary (on CAD input onto the exact B-rep face) and measured there along\n"
      "the given outward normals (N, 3) or the surface's. One entry per point, in order (ThicknessResult;\n"
      "element = triangle the point was projected onto).");

  m.def(
      "thickness_along",
      [](PyScene& s, const pyb::handle& geoms, const pyb::handle& points, const pyb::handle& inward,
         double max_distance, double tie_tolerance_rel, const std::string& kernel, const pyb::object& progress,
         CancelToken* cancel) {
        // Adapter for callers that know better normals than the mesh's averaged ones (CAD faces):
        // the core's ray_exit_distance at caller-given points and inward directions.
        const KernelKind kind = kernel_from_name(kernel);
        if (!is_exact(kind)) throw pyb::value_error("thickness_along: kernel must be exact");
        const std::vector<Ray> rays = make_rays(points, inward, pyb::float_(0.0), pyb::float_(max_distance));
        const std::vector<std::uint32_t> geom =
            geometry_ids(s, geoms, rays.size(), "geoms", [](std::size_t, std::int64_t v) {
              return "geometry id " + std::to_string(v) + " is not in the scene";
            });
        const auto along = run_analysis(s, progress, cancel, rays.size(), [&](const Progress& p) {
          return thickness_along(s.accel(), geom, rays, max_distance, tie_tolerance_rel, kind, p);
        });
        return vector_array(along->thickness);
      },
      pyb::arg("scene"), pyb::arg("geoms"), pyb::arg("points"), pyb::arg("inward"), pyb::kw_only(),
      pyb::arg("max_distance") = std::numeric_limits<double>::infinity(), pyb::arg("tie_tolerance_rel") = 1e-6,
      pyb::arg("kernel") = default_kernel_name(), pyb::arg("progress") = pyb::none(), pyb::arg("cancel") = nullptr,
      "Ray thickness at given surface points of solid geoms (one id or one per point) along given inward\n"
      "directions (normalised here): distance to where the ray leaves that solid, NaN if it does not.");
}

}  // namespace pierce::py
