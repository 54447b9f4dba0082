#pragma once
// Scene files for `pierce run` (docs/CSG.md, "Scene files"): a JSON document naming the model
// files, the materials and which solid is made of which, the rays (a generator spec, a CSV file or
// an orthographic camera) and the requested effects with their parameters and outputs.
//
// Relative paths (models, ray CSV files, outputs) are relative to the scene file's directory;
// outputs may be redirected (`pierce run --out-dir`).
//
// Part of the CLI, not of pierce_core: the format (and its JSON parser) is the command's, while
// what it configures, analysis::EffectsConfig, is core's.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pierce/analysis/effects.h"

namespace pierce::cli {

struct CameraSpec {
  Vec3d center;              // centre of the image plane; rays start there and run along `direction`
  Vec3d direction{0, 0, 1};  // viewing direction (need not be unit length)
  Vec3d up{0, 1, 0};         // image "up"; must not be parallel to direction
  double width = 1, height = 1;  // image plane size in model units
  int pixels_x = 64, pixels_y = 64;
};

struct EffectSceneSpec {
  std::string path;      // the scene file (for messages)
  std::string base_dir;  // its directory: relative paths resolve against it
  std::vector<std::string> models;  // resolved paths
  std::vector<analysis::Material> materials;
  // Solid name (or "#id", or "*" for every solid not named otherwise) -> index into materials, in
  // file order (inline materials are appended to `materials`).
  std::vector<std::pair<std::string, std::size_t>> assignments;
  std::string rays;                  // a ray_source.h spec (CSV paths resolved), when not a camera
  std::optional<CameraSpec> camera;
  analysis::EffectsConfig config;    // enabled effects, their parameters, kernel; materials unbound
  std::string csg;                   // classification.csg, bound in bind_effect_scene
  // Outputs, resolved against base_dir; empty = not requested.
  std::string rays_csv, intervals_csv, report_json;
  std::string xray_png, xray_vti, transparency_png;
};

// Parses a scene document. `path` names it in messages and gives base_dir. Throws InputError
// "path: where: what is wrong" (JSON syntax errors with line and column; unknown keys, wrong types
// and out-of-range values with their key path, e.g. "effects.xray.threshold").
EffectSceneSpec parse_effect_scene(std::string_view json_text, const std::string& path);
EffectSceneSpec load_effect_scene(const std::string& path);

// Outputs moved under another directory (relative output names keep their relative part).
void redirect_outputs(EffectSceneSpec& spec, const std::string& out_dir);

// Binds material assignments and the classification expression to the loaded scene: the config
// to run. Throws InputError listing unknown solid or material names.
analysis::EffectsConfig bind_effect_scene(const EffectSceneSpec& spec, const Scene& scene);

// The rays of a scene and, when they form an image (grid generator or camera), its layout:
// ray index of the pixel at column i (left to right) and row j counted from the top.
struct SceneRays {
  std::vector<Ray> rays;
  int width = 0, height = 0;  // 0: the rays do not form an image
  bool bottom_up = false;     // grid: ray row 0 is the image's bottom row
  Vec3d plane_origin, plane_spacing{1, 1, 1};  // pixel (0, bottom) centre and steps, in the image plane

  bool is_image() const { return width > 0 && height > 0; }
  std::size_t ray_of_pixel(int i, int row_from_top) const {
    const int r = bottom_up ? height - 1 - row_from_top : row_from_top;
    return std::size_t(r) * std::size_t(width) + std::size_t(i);
  }
};
SceneRays make_scene_rays(const EffectSceneSpec& spec, const Scene& scene);
std::vector<Ray> camera_rays(const CameraSpec& cam);

}  // namespace pierce::cli
