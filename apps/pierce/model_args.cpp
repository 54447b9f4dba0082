#include "model_args.h"

#include <iostream>

namespace pierce::cli {

void add_model_args(CLI::App* cmd, ModelArgs& args, bool several) {
  const std::string formats = "STL, OBJ, OFF, PLY meshes; STEP, IGES, BREP CAD files (one solid per geometry)";
  if (several)
    cmd->add_option("models", args.models, "Model files: " + formats)->required();
  else
    cmd->add_option("models", args.models, "Model file: " + formats)->required()->expected(1);
  cmd->add_option("--deflection", args.tessellation.linear_deflection,
                  "CAD tessellation: largest surface-to-triangle distance in model units (mm for STEP/IGES); "
                  "0 = 0.1% of the model's diagonal")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--angular-deflection", args.tessellation.angular_deflection_deg,
                  "CAD tessellation: largest angle between neighbouring triangles, degrees")
      ->check(CLI::Range(0.01, 179.0))
      ->capture_default_str();
  cmd->add_option("--fold-remesh-rounds", args.tessellation.fold_remesh_rounds,
                  "CAD tessellation: a solid whose triangles fold against the B-rep is meshed again, finer, up to "
                  "this many times; 0 = only flag the folds (thickness status tessellation)")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  cmd->add_option("--max-edge", args.tessellation.max_edge_length,
                  "CAD tessellation: split triangle edges longer than this (model units) at their midpoints, for more "
                  "samples on big flat faces; 0 = no splitting")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

std::vector<LoadedFile> load_models(Scene& scene, const ModelArgs& args) {
  std::vector<LoadedFile> files = add_any_model(scene, args.models, args.tessellation);
  for (const LoadedFile& f : files)
    for (const std::string& w : f.warnings) std::cerr << "pierce: warning: " << f.path << ": " << w << "\n";
  return files;
}

const TessellationCheck* tessellation_check(const std::vector<LoadedFile>& files, std::uint32_t geom) {
  for (const LoadedFile& f : files)
    if (geom >= f.first_geometry && geom < f.first_geometry + f.geometry_count &&
        geom - f.first_geometry < f.cad.size() && !f.cad[geom - f.first_geometry].empty())
      return &f.cad[geom - f.first_geometry].check;
  return nullptr;
}

std::string solid_label(const Scene& scene, std::uint32_t id) {
  const std::string& n = scene.geometry(id).name;
  return n.empty() ? "#" + std::to_string(id) : n;
}

}  // namespace pierce::cli
