#pragma once
// Renders a picture (false-colour field: thickness, overlaps; or a traversal heat map) with a
// progress bar and writes it as PNG.
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "interrupt.h"
#include "output_file.h"
#include "pierce/io/false_colour.h"
#include "progress.h"

namespace pierce::cli {

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
  return write_picture(path, force, progress, fo.height, [&](const analysis::Progress& p) {
    return render_false_colour(accel, field, fo, p);
  });
}

}  // namespace pierce::cli
