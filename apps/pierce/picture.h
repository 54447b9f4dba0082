#pragma once
// Renders a per-element field as a false-colour PNG with a progress bar (thickness, overlaps).
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "interrupt.h"
#include "output_file.h"
#include "pierce/io/false_colour.h"
#include "progress.h"

namespace pierce::cli {

// The rendered image, or nothing when the user cancelled (no file is written then).
inline std::optional<FalseColourImage> write_picture(const Accel& accel, const ElementField& field,
                                                     const FalseColourOptions& fo, const std::string& path,
                                                     bool force, bool progress) {
  ProgressBar bar("picture", std::size_t(fo.height), progress);
  FalseColourImage img =
      render_false_colour(accel, field, fo, [&](std::size_t done, std::size_t) { return bar.update(done); });
  bar.finish();
  if (!img.completed || interrupted()) return std::nullopt;
  const std::string png = false_colour_png(img);
  OutputFile out(path, force);
  if (std::fwrite(png.data(), 1, png.size(), out.stream()) != png.size()) throw std::runtime_error("write error");
  out.commit();
  return img;
}

}  // namespace pierce::cli
