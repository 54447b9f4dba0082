#pragma once
// One entry point for every model format: meshes (mesh_io.h) and CAD (cad_io.h), by extension.
#include <cstdint>
#include <string>
#include <vector>

#include "pierce/io/cad_io.h"
#include "pierce/scene.h"

namespace pierce {

struct LoadedFile {
  std::string path;
  std::uint32_t first_geometry = 0, geometry_count = 0;  // ids in the scene
  std::string units;                  // "mm" for STEP/IGES, "model units" otherwise
  double linear_deflection = 0;       // CAD: tessellation used; meshes: 0
  std::vector<std::string> warnings;  // CAD: what was skipped or repaired
  CadLoadTimes cad_times;             // CAD: where the load spent its time
  std::vector<CadLink> cad;           // CAD: per geometry of the file, its triangles' link to the
                                      // B-rep (pierce/io/cad_surfaces.h); meshes: empty
};

// Adds every file's solids to the scene in argument order (geometry source = path); throws
// InputError naming the file on the first one that fails.
std::vector<LoadedFile> add_any_model(Scene& scene, const std::vector<std::string>& paths,
                                      const TessellationOptions& opts = {});

}  // namespace pierce
