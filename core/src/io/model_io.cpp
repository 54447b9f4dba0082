#include "pierce/io/model_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "pierce/error.h"
#include "pierce/io/mesh_io.h"

namespace pierce {

std::vector<LoadedFile> add_any_model(Scene& scene, const std::vector<std::string>& paths,
                                      const TessellationOptions& opts) {
  std::vector<LoadedFile> out;
  for (const std::string& path : paths) {
    LoadedFile f;
    f.path = path;
    f.first_geometry = std::uint32_t(scene.geometries().size());
    if (is_cad_file(path)) {
      CadModel m = load_cad_file(path, opts);
      for (CadSolid& s : m.solids) {
        scene.add_mesh(std::move(s.vertices), std::move(s.triangles), std::move(s.name), path);
        f.cad.push_back(std::move(s.link));
      }
      f.units = m.units;
      f.linear_deflection = m.linear_deflection;
      f.cad_times = m.times;
      f.warnings = std::move(m.warnings);
    } else {
      std::string ext = std::filesystem::path(path).extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
      if (ext != ".stl" && ext != ".obj" && ext != ".off" && ext != ".ply")
        throw InputError(path + ": unknown model format " + (ext.empty() ? std::string("(no extension)") : "'" + ext + "'") +
                         " (expected .stl, .obj, .off, .ply, .step, .stp, .iges, .igs, .brep or .brp)");
      for (LoadedMesh& m : load_mesh_file(path))
        scene.add_mesh(std::move(m.vertices), std::move(m.triangles), std::move(m.name), path);
      f.units = "model units";
    }
    f.geometry_count = std::uint32_t(scene.geometries().size()) - f.first_geometry;
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace pierce
