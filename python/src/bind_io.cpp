// Loading models and ray sets from files.
#include <pybind11/stl.h>

#include "common.h"
#include "pierce/generators.h"
#include "pierce/io/cad_io.h"  // TessellationOptions: the defaults every front end shares
#include "pierce/io/mesh_io.h"
#ifdef PIERCE_PY_WITH_CAD
#include "pierce/io/cad_surfaces.h"
#include "pierce/io/model_io.h"
#endif
#include "pierce/io/ray_source.h"

namespace pierce::py {

void bind_io(pyb::module_& m) {
  const TessellationOptions tess;  // defaults of the CLI, Python, ParaView and FreeCAD
  m.def(
      "tessellation_defaults",
      [] {
        const TessellationOptions t;
        pyb::dict d;
        d["linear_deflection"] = t.linear_deflection;
        d["angular_deflection"] = t.angular_deflection_deg;
        d["fold_remesh_rounds"] = t.fold_remesh_rounds;
        d["max_edge"] = t.max_edge_length;
        return d;
      },
      "The CAD tessellation defaults every front end uses (the CLI's --deflection, --angular-deflection,\n"
      "--fold-remesh-rounds and --max-edge): linear_deflection (0 = 0.1% of the model's diagonal),\n"
      "angular_deflection (degrees), fold_remesh_rounds and max_edge (0 = long edges are not split).");
  m.def(
      "load_mesh",
      [](const std::string& path) {
        std::vector<LoadedMesh> loaded;
        {
          pyb::gil_scoped_release no_gil;
          loaded = load_mesh_file(path);
        }
        std::vector<gen::Mesh> out;
        for (auto& l : loaded) out.push_back({std::move(l.name), std::move(l.vertices), std::move(l.triangles)});
        return out;
      },
      pyb::arg("path"),
      "Meshes of one STL/OBJ/OFF/PLY file (several where the file holds several parts), as pierce.gen.Mesh.\n"
      "Raises pierce.InputError 'path:line: problem' on a bad file.");

  m.def(
      "add_model_files",
      [](PyScene& s, const std::vector<std::string>& paths, double linear_deflection, double angular_deflection,
         int fold_remesh_rounds, double max_edge) {
        if (s.in_use()) throw std::runtime_error("add_model_files: the scene is in use by a running call");
        // Everything is read into a scratch scene first: a bad file leaves the scene as it was.
        Scene scratch;
        pyb::list info;
#ifdef PIERCE_PY_WITH_CAD
        std::vector<LoadedFile> files;
        {
          pyb::gil_scoped_release no_gil;
          TessellationOptions t;
          t.linear_deflection = linear_deflection;
          t.angular_deflection_deg = angular_deflection;
          t.fold_remesh_rounds = fold_remesh_rounds;
          t.max_edge_length = max_edge;
          files = add_any_model(scratch, paths, t);
        }
        const auto first = static_cast<std::uint32_t>(s.scene.geometries().size());
        for (const LoadedFile& f : files) {
          pyb::dict d;
          d["path"] = f.path;
          d["geometries"] = pyb::make_tuple(first + f.first_geometry, f.geometry_count);
          d["units"] = f.units;
          d["linear_deflection"] = f.linear_deflection;
          d["warnings"] = f.warnings;
          pyb::list checks;  // per solid of a CAD file: its tessellation checked against the B-rep
          for (const CadLink& l : f.cad) {
            pyb::dict c;
            c["brep_faces"] = l.check.faces;
            c["folded"] = l.check.folded;
            c["slivers"] = l.check.slivers;
            c["folded_found"] = l.check.folded_found;
            c["faces_folded"] = l.check.faces_folded;
            c["faces_remeshed"] = l.check.faces_remeshed;
            c["remesh_rounds"] = l.check.remesh_rounds;
            c["deflection"] = l.check.final_deflection;
            checks.append(c);
          }
          d["tessellation"] = checks;
          info.append(d);
        }
#else
        (void)linear_deflection, (void)angular_deflection, (void)fold_remesh_rounds, (void)max_edge;
        {
          pyb::gil_scoped_release no_gil;
          add_model_files(scratch, paths);
        }
#endif
        for (const Geometry& g : scratch.geometries()) s.scene.add_mesh(g.vertices, g.triangles, g.name, g.source);
#ifdef PIERCE_PY_WITH_CAD
        bool any_cad = false;
        s.cad.resize(first);
        for (const LoadedFile& f : files)
          for (std::uint32_t k = 0; k < f.geometry_count; ++k) {
            s.cad.push_back(k < f.cad.size() ? f.cad[k] : CadLink{});
            any_cad = any_cad || !s.cad.back().empty();
          }
        for (const CadLink& l : s.cad) any_cad = any_cad || !l.empty();
        if (any_cad) s.exact = std::make_shared<CadSurfaces>(s.cad);
#endif
        s.invalidate_accel();
        return info;
      },
      pyb::arg("scene"), pyb::arg("paths"), pyb::kw_only(), pyb::arg("linear_deflection") = tess.linear_deflection,
      pyb::arg("angular_deflection") = tess.angular_deflection_deg, pyb::arg("fold_remesh_rounds") = tess.fold_remesh_rounds,
      pyb::arg("max_edge") = tess.max_edge_length,
      "Adds every solid of the files (STL/OBJ/OFF/PLY, and STEP/IGES/BREP when built with OpenCASCADE;\n"
      "geometry source = path). CAD files are tessellated with linear_deflection (model units, 0 = 0.1% of\n"
      "the diagonal) and angular_deflection (degrees); a solid whose mesh folds against the B-rep is meshed\n"
      "again, finer, up to fold_remesh_rounds times (0: folds are only flagged); then triangle edges longer\n"
      "than max_edge (model units; 0: none) are split at their midpoints, for more samples on big flat\n"
      "faces (the mesh stays closed; the triangles stay linked to their faces). Returns per-file info (CAD\n"
      "builds: path, geometries, units, linear_deflection, warnings, and per solid 'tessellation': the check\n"
      "against the B-rep) or []. Thickness maps of CAD solids are sampled on the exact B-rep.");

  m.attr("HAS_CAD") =
#ifdef PIERCE_PY_WITH_CAD
      true;
#else
      false;
#endif

  m.def(
      "load_rays",
      [](const std::string& spec, const PyScene& s) { return rays_to_arrays(load_rays(spec, s.scene)); },
      pyb::arg("spec"), pyb::arg("scene"),
      "Rays from a CSV file (ox,oy,oz,dx,dy,dz[,tmin,tmax]) or a generator ('grid:axis=z,n=64',\n"
      "'random:n=1000,seed=1'): (origins, directions, tmin, tmax).");
}

}  // namespace pierce::py
