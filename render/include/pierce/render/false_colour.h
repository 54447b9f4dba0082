#pragma once
// False-colour pictures of per-element values (thickness, overlap count) rendered by Pierce
// itself: one orthographic primary ray per pixel, closest hit, Lambert-shaded colour-mapped
// value, white background, colour bar with the value range. No VTK, no display needed.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pierce/progress.h"
#include "pierce/enum_names.h"
#include "pierce/kernel.h"

namespace pierce {

enum class ColourMap { viridis, cool_warm };

// Values to paint, per geometry of the scene: one per vertex (interpolated across each triangle)
// or one per triangle. A geometry with no values, and NaN values, are painted grey.
struct ElementField {
  enum class At { vertex, face };
  At at = At::face;
  std::vector<std::vector<double>> values;        // [geom][vertex or triangle]
  std::vector<std::vector<std::uint8_t>> marked;  // optional, same shape: 1 = highlight (e.g. thin)
};

struct FalseColourOptions {
  int width = 800, height = 600;      // whole picture, colour bar included
  Vec3d view_dir{-1, -1, -1};         // the direction the camera looks along (z is up)
  ColourMap map = ColourMap::viridis;
  // Value range of the colour map; NaN = the finite values' min / max.
  double range_min = std::numeric_limits<double>::quiet_NaN();
  double range_max = std::numeric_limits<double>::quiet_NaN();
  bool legend = true;  // colour bar with min / max labels on the right (if the picture is wide enough)
  KernelKind kernel = kDefaultKernel;
};

// The picture's frame: an orthographic camera fitted to the scene's bounds seen along
// opts.view_dir, the image area (view_width x height pixels, from the left) and the colour bar
// strip beside it. Throws std::invalid_argument on bad sizes or view direction (as the renderers).
struct PictureFrame {
  int width = 0, height = 0, view_width = 0, legend_width = 0, glyph_scale = 1, label_width = 0;
  bool legend = false;
  Vec3d f, right, cam_up, eye, light;
  double pixel = 0;  // pixel size in scene units

  static PictureFrame fit(const Scene& scene, const FalseColourOptions& opts);
  // The primary ray of pixel (x, y), x < view_width, rows from the top.
  Ray ray(int x, int y) const;
};

struct FalseColourImage {
  int width = 0, height = 0;
  std::vector<double> rgb;  // width * height * 3 samples in [0, 1], rows from the top
  double range_min = 0, range_max = 0;
  std::size_t pixels_hit = 0;
  bool completed = true;  // false if cancelled through the progress callback
};

// Which work a traversal heat map shows per pixel (Gribble 2016, from the counting kernels).
enum class CostMetric { traversal_steps, node_tests, prim_tests };
constexpr EnumTable<CostMetric, 3> enum_table(CostMetric) {
  using enum CostMetric;
  return {"heat map count", {{traversal_steps, "steps"}, {node_tests, "node-tests"}, {prim_tests, "prim-tests"}}};
}
// The names of enum_table(CostMetric): steps, node-tests, prim-tests.
inline std::string_view cost_metric_name(CostMetric m) { return enum_name(m); }
inline std::optional<CostMetric> parse_cost_metric(std::string_view name) { return parse_enum<CostMetric>(name); }

struct HeatmapStats {
  CostMetric metric = CostMetric::traversal_steps;
  double mean = 0, max = 0;      // per pixel, over every pixel of the view
  double mean_over_scene = 0;    // per pixel whose ray met the scene's box
  std::size_t rays = 0;          // pixels traced (the view, without the colour bar)
};

// Gribble's heat map of traversal work: one ray per pixel (the camera of render_false_colour),
// traced by `kernel`'s counting variant for up to `max_hits` hits (0 = all); each pixel coloured
// by its ray's count of `metric`. Pixels whose ray does no work at all stay white. opts.kernel is
// ignored; the colour range defaults to 0 .. the maximum.
FalseColourImage render_cost_heatmap(const Accel& accel, KernelKind kernel, std::size_t max_hits, CostMetric metric,
                                     const FalseColourOptions& opts, HeatmapStats& stats,
                                     const Progress& progress = {});

// Colour of value s in [0, 1] (clamped) under the map.
Vec3d colour_of(ColourMap map, double s);

// Throws std::invalid_argument on bad sizes (below 16 or above 16384 pixels per side), a zero
// or non-finite view direction, or a field whose shape does not match the scene.
FalseColourImage render_false_colour(const Accel& accel, const ElementField& field, const FalseColourOptions& opts = {},
                                     const Progress& progress = {});

// The picture as 8-bit RGB PNG bytes.
std::string false_colour_png(const FalseColourImage& image);

// Command-line forms: "WxH" (e.g. 800x600) and "x,y,z". Throw InputError naming `option`.
void parse_picture_size(const std::string& option, const std::string& spec, int& width, int& height);
Vec3d parse_view_direction(const std::string& option, const std::string& spec);

}  // namespace pierce
