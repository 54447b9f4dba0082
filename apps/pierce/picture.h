#pragma once
// Renders a picture (false-colour field: thickness, overlaps; or a traversal heat map) with a
// progress bar and writes it as PNG.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "interrupt.h"
#include "output_file.h"
#include "pierce/error.h"
#include "pierce/render/false_colour.h"
#include "progress.h"

namespace pierce::cli {

// --png-size and --png-view of the commands that render a picture (`what`: "Picture", "Heat map").
inline void add_camera_options(CLI::App* cmd, std::string& size, std::string& view, const std::string& what) {
  cmd->add_option("--png-size", size, what + " size WIDTHxHEIGHT in pixels")->capture_default_str();
  cmd->add_option("--png-view", view, "Direction the camera looks along, x,y,z (z is up)")->capture_default_str();
}

// The --png options of thickness and overlaps, checked before any long work: the picture's file
// (not replaced without --force, not the -o file) and the --png-size / --png-view specs.
inline void check_picture_options(const std::string& png, const std::string& out, bool force, const std::string& size,
                                  const std::string& view) {
  if (png.empty()) return;
  OutputFile::check_target(png, force);
  if (png == out) throw InputError("--png and -o name the same file '" + png + "'");
  int width = 0, height = 0;
  parse_picture_size("--png-size", size, width, height);
  parse_view_direction("--png-view", view);
}

// `render(progress)` returns the image; it is written to `path` unless the user cancelled (no
// file is written then, and nothing is returned).
template <class Render>
std::optional<FalseColourImage> write_picture(const std::string& path, bool force, bool progress, int rows,
                                              Render render) {
  ProgressBar bar("picture", std::size_t(rows), progress);
  FalseColourImage img = render([&](std::size_t done, std::size_t) { return bar.update(done); });
  bar.finish();
  if (!img.completed || interrupted()) return std::nullopt;
  const std::string png = false_colour_png(img);
  OutputFile out(path, force);
  if (std::fwrite(png.data(), 1, png.size(), out.stream()) != png.size()) throw std::runtime_error("write error");
  out.commit();
  return img;
}

inline std::optional<FalseColourImage> write_picture(const Accel& accel, const ElementField& field,
                                                     const FalseColourOptions& fo, const std::string& path,
                                                     bool force, bool progress) {
  return write_picture(path, force, progress, fo.height, [&](const Progress& p) {
    return render_false_colour(accel, field, fo, p);
  });
}

}  // namespace pierce::cli
