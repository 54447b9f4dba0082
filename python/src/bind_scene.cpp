// pierce.Scene: meshes from numpy arrays, read back as zero-copy views; synthetic meshes.
#include <pybind11/stl.h>

#include <cstring>
#include <limits>
#include <sstream>

#include "common.h"
#include "pierce/analysis/mesh_report.h"
#include "pierce/error.h"
#include "pierce/generators.h"

namespace pierce::py {

static_assert(sizeof(Vec3d) == 3 * sizeof(double), "Vec3d must be three packed doubles");
static_assert(sizeof(Tri) == 3 * sizeof(std::uint32_t), "Tri must be three packed uint32");

namespace {

std::string shape_string(const pyb::array& a) {
  std::ostringstream s;
  s << '(';
  for (pyb::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

void require_rows_of_3(const pyb::array& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw pyb::value_error(std::string(what) + " must have shape (N, 3), got " + shape_string(a));
}

// A geometry of a scene, read through zero-copy views that keep the scene alive.
struct GeometryRef {
  pyb::object scene_obj;  // the Python Scene
  std::uint32_t id;
  const Geometry& geom() const { return scene_obj.cast<PyScene&>().scene.geometry(id); }
};

pyb::array_t<double> mesh_vertices(const gen::Mesh& m) {
  pyb::array_t<double> a({static_cast<pyb::ssize_t>(m.vertices.size()), pyb::ssize_t{3}});
  if (!m.vertices.empty()) std::memcpy(a.mutable_data(), m.vertices.data(), m.vertices.size() * sizeof(Vec3d));
  return a;
}
pyb::array_t<std::uint32_t> mesh_triangles(const gen::Mesh& m) {
  pyb::array_t<std::uint32_t> a({static_cast<pyb::ssize_t>(m.triangles.size()), pyb::ssize_t{3}});
  if (!m.triangles.empty()) std::memcpy(a.mutable_data(), m.triangles.data(), m.triangles.size() * sizeof(Tri));
  return a;
}

Vec3d to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

pyb::array_t<double> bounds_array(const BBoxd& b) {
  pyb::array_t<double> out({2, 3});
  auto r = out.mutable_unchecked<2>();
  for (int k = 0; k < 3; ++k) {
    r(0, k) = b.lo[k];
    r(1, k) = b.hi[k];
  }
  return out;
}

const Accel& PyScene::accel() {
  std::lock_guard lock(accel_mutex_);
  if (!accel_) accel_ = std::make_unique<Accel>(scene);
  return *accel_;
}

pyb::array_t<double, pyb::array::c_style> as_points(const pyb::handle& obj, const char* what) {
  if (obj.is_none()) throw pyb::type_error(std::string(what) + " must be an (N, 3) array, got None");
  auto a = pyb::array_t<double, pyb::array::c_style | pyb::array::forcecast>::ensure(obj);
  if (!a) {
    PyErr_Clear();
    throw pyb::type_error(std::string(what) + " must be convertible to an (N, 3) float array");
  }
  require_rows_of_3(a, what);
  return a;
}

pyb::array as_point_rows(const pyb::handle& obj, const char* what) {
  if (!pyb::isinstance<pyb::array_t<double>>(obj)) return as_points(obj, what);
  auto a = pyb::reinterpret_borrow<pyb::array>(obj);
  require_rows_of_3(a, what);
  return a;
}

std::vector<Vec3d> to_vec3d(const pyb::array_t<double, pyb::array::c_style>& a) {
  std::vector<Vec3d> out(static_cast<std::size_t>(a.shape(0)));
  if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), a.data(), out.size() * sizeof(Vec3d));
  return out;
}

std::vector<Tri> to_triangles(const pyb::handle& obj, const char* what) {
  pyb::array raw = pyb::array::ensure(obj);
  if (!raw) {
    PyErr_Clear();
    throw pyb::type_error(std::string(what) + " must be an (M, 3) integer array");
  }
  if (raw.size() > 0 && raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u')
    throw pyb::type_error(std::string(what) + " must hold integers, got dtype " +
                          std::string(pyb::str(raw.dtype())));
  if (raw.size() == 0 && raw.ndim() == 1) return {};  // [] is an empty triangle list
  require_rows_of_3(raw, what);
  std::vector<Tri> out(static_cast<std::size_t>(raw.shape(0)));
  if (out.empty()) return out;
  // Fast path: already packed uint32 rows.
  if (raw.dtype().is(pyb::dtype::of<std::uint32_t>()) && (raw.flags() & pyb::array::c_style)) {
    std::memcpy(out.data(), raw.data(), out.size() * sizeof(Tri));
    return out;
  }
  auto idx = pyb::array_t<std::int64_t, pyb::array::c_style | pyb::array::forcecast>::ensure(raw);
  if (raw.dtype().kind() == 'u' && raw.dtype().itemsize() == 8) {
    // uint64 beyond int64 range would wrap: check before the cast.
    auto u = pyb::array_t<std::uint64_t, pyb::array::c_style | pyb::array::forcecast>::ensure(raw);
    const std::uint64_t* p = u.data();
    for (pyb::ssize_t i = 0; i < u.size(); ++i)
      if (p[i] > std::numeric_limits<std::uint32_t>::max())
        throw InputError(std::string(what) + ": triangle " + std::to_string(i / 3) + " has index " +
                         std::to_string(p[i]) + ", beyond the 32-bit range");
  }
  const std::int64_t* p = idx.data();
  for (std::size_t t = 0; t < out.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = p[3 * t + k];
      if (v < 0 || v > std::int64_t{std::numeric_limits<std::uint32_t>::max()})
        throw InputError(std::string(what) + ": triangle " + std::to_string(t) + " has index " +
                         std::to_string(v) + (v < 0 ? " (negative)" : ", beyond the 32-bit range"));
      out[t][k] = static_cast<std::uint32_t>(v);
    }
  return out;
}

void bind_scene(pyb::module_& m) {
  pyb::class_<GeometryRef>(m, "Geometry", "One mesh of a Scene (read-only views into the scene's memory).")
      .def_property_readonly("id", [](const GeometryRef& g) { return g.id; })
      .def_property_readonly("name", [](const GeometryRef& g) { return g.geom().name; })
      .def_property_readonly("source", [](const GeometryRef& g) { return g.geom().source; })
      .def_property_readonly(
          "vertices",
          [](const GeometryRef& g) {
            const auto& v = g.geom().vertices;
            return readonly_view(&v.data()->x, v.size(), 3, g.scene_obj);
          },
          "(N, 3) float64, read-only view")
      .def_property_readonly(
          "triangles",
          [](const GeometryRef& g) {
            const auto& t = g.geom().triangles;
            return readonly_view(t.empty() ? nullptr : t.data()->data(), t.size(), 3, g.scene_obj);
          },
          "(M, 3) uint32, read-only view; a hit's prim indexes these rows")
      .def_property_readonly(
          "degenerate",
          [](const GeometryRef& g) {
            const auto& d = g.geom().degenerate;
            return readonly_view(d.data(), d.size(), 0, g.scene_obj);
          },
          "(M,) uint8, 1 where the triangle has zero area in float and is never hit")
      .def("__repr__", [](const GeometryRef& g) {
        const Geometry& x = g.geom();
        return "<pierce.Geometry " + std::to_string(g.id) + " '" + x.name + "': " +
               std::to_string(x.vertices.size()) + " vertices, " + std::to_string(x.triangles.size()) +
               " triangles>";
      });

  pyb::class_<PyScene>(m, "Scene", pyb::dynamic_attr(),
                       "Triangle meshes (one geometry per solid). Geometry ids are 0, 1, ... in the order added.")
      .def(pyb::init<>())
      .def(
          "add_mesh",
          [](PyScene& s, const pyb::handle& vertices, const pyb::handle& triangles, const std::string& name,
             const std::string& source) {
            if (s.in_use()) throw std::runtime_error("Scene.add_mesh: the scene is in use by a running call");
            std::vector<Vec3d> v = to_vec3d(as_points(vertices, "vertices"));
            std::vector<Tri> t = to_triangles(triangles, "triangles");
            const std::uint32_t id = s.scene.add_mesh(std::move(v), std::move(t), name, source);
            s.invalidate_accel();
            return id;
          },
          pyb::arg("vertices"), pyb::arg("triangles"), pyb::arg("name") = "", pyb::arg("source") = "",
          "Adds a mesh from an (N, 3) float array and an (M, 3) integer array (outward = counter-clockwise);\n"
          "returns its geometry id. Raises pierce.InputError on NaN/Inf coordinates or bad indices.")
      .def(
          "add",
          [](PyScene& s, const gen::Mesh& mesh, const std::string& source) {
            if (s.in_use()) throw std::runtime_error("Scene.add: the scene is in use by a running call");
            const std::uint32_t id = s.scene.add_mesh(mesh.vertices, mesh.triangles, mesh.name, source);
            s.invalidate_accel();
            return id;
          },
          pyb::arg("mesh"), pyb::arg("source") = "generated", "Adds a pierce.gen.Mesh; returns its geometry id.")
      .def("__len__", [](const PyScene& s) { return s.scene.geometries().size(); })
      .def_property_readonly("geometry_count", [](const PyScene& s) { return s.scene.geometries().size(); })
      .def_property_readonly("triangle_count", [](const PyScene& s) { return s.scene.triangle_count(); })
      .def_property_readonly("degenerate_count", [](const PyScene& s) { return s.scene.degenerate_count(); })
      .def_property_readonly("bounds", [](const PyScene& s) { return bounds_array(s.scene.bounds()); },
                             "(2, 3) array: min corner, max corner")
      .def_property_readonly("scale", [](const PyScene& s) { return s.scene.scale(); },
                             "length of the bounds' diagonal (1 for an empty scene)")
      .def_property_readonly("names", [](const PyScene& s) {
        std::vector<std::string> n;
        for (const auto& g : s.scene.geometries()) n.push_back(g.name);
        return n;
      })
      .def(
          "geometry",
          [](pyb::object self, long long id) {
            const auto& s = self.cast<PyScene&>();
            const auto n = static_cast<long long>(s.scene.geometries().size());
            if (id < 0) id += n;
            if (id < 0 || id >= n)
              throw pyb::index_error("geometry id " + std::to_string(id) + " out of range (scene has " +
                                     std::to_string(n) + ")");
            return GeometryRef{self, static_cast<std::uint32_t>(id)};
          },
          pyb::arg("id"))
      .def(
          "__getitem__",
          [](pyb::object self, long long id) { return self.attr("geometry")(id); }, pyb::arg("id"))
      .def(
          "build",
          [](PyScene& s) {
            PyScene::Use use(s);
            pyb::gil_scoped_release no_gil;
            s.accel();
          },
          "Builds the acceleration structures now (otherwise done by the first call that needs them).")
      .def("__repr__", [](const PyScene& s) {
        return "<pierce.Scene: " + std::to_string(s.scene.geometries().size()) + " geometries, " +
               std::to_string(s.scene.triangle_count()) + " triangles>";
      });

  using analysis::SolidReport;
  pyb::class_<SolidReport>(m, "SolidReport", "Mesh diagnostics of one geometry (pierce.mesh_report).")
      .def_readonly("geom", &SolidReport::geom)
      .def_readonly("name", &SolidReport::name)
      .def_readonly("source", &SolidReport::source)
      .def_readonly("vertices", &SolidReport::vertices)
      .def_readonly("welded_vertices", &SolidReport::welded_vertices)
      .def_readonly("triangles", &SolidReport::triangles)
      .def_readonly("degenerate", &SolidReport::degenerate)
      .def_readonly("duplicates", &SolidReport::duplicates)
      .def_readonly("edges", &SolidReport::edges)
      .def_readonly("boundary_edges", &SolidReport::boundary_edges)
      .def_readonly("non_manifold_edges", &SolidReport::non_manifold_edges)
      .def_readonly("inconsistent_edges", &SolidReport::inconsistent_edges)
      .def_readonly("closed", &SolidReport::closed)
      .def_readonly("consistently_oriented", &SolidReport::consistently_oriented)
      .def_property_readonly("bounds", [](const SolidReport& r) { return bounds_array(r.bounds); })
      .def_readonly("area", &SolidReport::area)
      .def_readonly("volume", &SolidReport::volume, "signed; < 0 means inward-facing winding (closed meshes)")
      .def("__repr__", [](const SolidReport& r) {
        return "<pierce.SolidReport " + std::to_string(r.geom) + " '" + r.name + "': " +
               std::to_string(r.triangles) + " triangles, " + (r.closed ? "closed" : "open") + ">";
      });
  m.def(
      "mesh_report", [](const PyScene& s) { return analysis::mesh_report(s.scene); }, pyb::arg("scene"),
      "Per-geometry diagnostics: closed/open, non-manifold, degenerate and duplicate triangles, bounds, area, volume.");

  // Synthetic meshes with known answers (pierce::gen).
  auto g = m.def_submodule("gen", "Synthetic meshes with known answers (closed ones wound outward).");
  pyb::class_<gen::Mesh>(g, "Mesh")
      .def(pyb::init([](const pyb::handle& vertices, const pyb::handle& triangles, const std::string& name) {
             return gen::Mesh{name, to_vec3d(as_points(vertices, "vertices")), to_triangles(triangles, "triangles")};
           }),
           pyb::arg("vertices"), pyb::arg("triangles"), pyb::arg("name") = "")
      .def_readwrite("name", &gen::Mesh::name)
      .def_property_readonly("vertices", &mesh_vertices, "(N, 3) float64 copy")
      .def_property_readonly("triangles", &mesh_triangles, "(M, 3) uint32 copy")
      .def("__repr__", [](const gen::Mesh& x) {
        return "<pierce.gen.Mesh '" + x.name + "': " + std::to_string(x.vertices.size()) + " vertices, " +
               std::to_string(x.triangles.size()) + " triangles>";
      });
  g.def(
      "box",
      [](std::array<double, 3> lo, std::array<double, 3> hi, std::string name) {
        return gen::box(to_vec(lo), to_vec(hi), std::move(name));
      },
      pyb::arg("lo"), pyb::arg("hi"), pyb::arg("name") = "box", "Closed axis-aligned box, 12 triangles.");
  g.def("stacked_plates", &gen::stacked_plates, pyb::arg("layers"), pyb::arg("size") = 1.0,
        pyb::arg("thickness") = 0.1, "Closed plates stacked along z sharing faces exactly.");
  g.def("cube_grid", &gen::cube_grid, pyb::arg("n"), "n^3 touching unit cubes, one geometry each.");
  g.def("voxel_block", &gen::voxel_block, pyb::arg("n"));
  g.def("blob", &gen::blob, pyb::arg("subdivisions"), pyb::arg("seed") = 7, pyb::arg("bumpiness") = 0.25);
  g.def("duplicated", &gen::duplicated, pyb::arg("mesh"), pyb::arg("copies"), pyb::arg("alternate_winding"));
  g.def(
      "translated", [](gen::Mesh mesh, std::array<double, 3> d) { return gen::translated(std::move(mesh), to_vec(d)); },
      pyb::arg("mesh"), pyb::arg("offset"));
  g.def("scaled", &gen::scaled, pyb::arg("mesh"), pyb::arg("factor"));
}

}  // namespace pierce::py
