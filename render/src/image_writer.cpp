#include "pierce/render/image_writer.h"

#include <spng.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

namespace pierce {

namespace {

struct SpngContextDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};

void check_spng(int status, const char* what) {
  if (status != 0) throw std::runtime_error(std::string("encode_png: ") + what + ": " + spng_strerror(status));
}

}  // namespace

std::string encode_png(int width, int height, int channels, int bits, std::span<const double> samples) {
  if (width < 1 || height < 1 || (channels != 1 && channels != 3 && channels != 4) || (bits != 8 && bits != 16))
    throw std::invalid_argument("encode_png: bad image format");
  const std::size_t per_row = std::size_t(width) * std::size_t(channels);
  if (samples.size() != per_row * std::size_t(height)) throw std::invalid_argument("encode_png: wrong sample count");

  // Quantised samples, big-endian as PNG stores them (SPNG_FMT_RAW takes them as they are, so the
  // byte order does not depend on the host).
  const std::size_t bytes_per_sample = std::size_t(bits / 8);
  std::vector<std::uint8_t> pixels;
  pixels.reserve(samples.size() * bytes_per_sample);
  const double top = bits == 8 ? 255.0 : 65535.0;
  for (const double v : samples) {
    const double c = std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0);
    const auto q = static_cast<std::uint32_t>(std::lround(c * top));
    if (bits == 16) pixels.push_back(std::uint8_t(q >> 8));
    pixels.push_back(std::uint8_t(q & 0xff));
  }

  const std::unique_ptr<spng_ctx, SpngContextDeleter> ctx(spng_ctx_new(SPNG_CTX_ENCODER));
  if (!ctx) throw std::runtime_error("encode_png: libspng could not create an encoder");
  check_spng(spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1), "buffer output");
  spng_ihdr ihdr{};
  ihdr.width = std::uint32_t(width);
  ihdr.height = std::uint32_t(height);
  ihdr.bit_depth = std::uint8_t(bits);
  ihdr.color_type = std::uint8_t(channels == 1 ? SPNG_COLOR_TYPE_GRAYSCALE
                                 : channels == 3 ? SPNG_COLOR_TYPE_TRUECOLOR
                                                 : SPNG_COLOR_TYPE_TRUECOLOR_ALPHA);
  check_spng(spng_set_ihdr(ctx.get(), &ihdr), "header");
  check_spng(spng_encode_image(ctx.get(), pixels.data(), pixels.size(), SPNG_FMT_RAW, SPNG_ENCODE_FINALIZE), "image");
  std::size_t size = 0;
  int status = 0;
  void* buffer = spng_get_png_buffer(ctx.get(), &size, &status);
  check_spng(status, "output");
  const std::unique_ptr<void, decltype(&std::free)> owned(buffer, &std::free);  // spng hands the buffer over
  return std::string(static_cast<const char*>(buffer), size);
}

std::string encode_vti(int width, int height, Vec3d origin, Vec3d spacing, const std::vector<VtiArray>& arrays) {
  const std::size_t n = std::size_t(width) * std::size_t(height);
  for (const VtiArray& a : arrays)
    if (a.values.size() != n) throw std::invalid_argument("encode_vti: array '" + a.name + "' has the wrong size");
  char buf[256];
  std::string s = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n";
  std::snprintf(buf, sizeof buf, "0 %d 0 %d 0 0", width - 1, height - 1);
  const std::string extent = buf;
  s += "  <ImageData WholeExtent=\"" + extent + "\"";
  std::snprintf(buf, sizeof buf, " Origin=\"%.17g %.17g %.17g\" Spacing=\"%.17g %.17g %.17g\">\n", origin.x, origin.y,
                origin.z, spacing.x, spacing.y, spacing.z);
  s += buf;
  s += "    <Piece Extent=\"" + extent + "\">\n      <PointData";
  if (!arrays.empty()) s += " Scalars=\"" + arrays.front().name + "\"";
  s += ">\n";
  for (const VtiArray& a : arrays) {
    s += "        <DataArray type=\"Float64\" Name=\"" + a.name + "\" format=\"ascii\">\n         ";
    for (std::size_t i = 0; i < n; ++i) {
      std::snprintf(buf, sizeof buf, " %.17g", std::isnan(a.values[i]) ? 0.0 : a.values[i]);
      s += buf;
      if (i % 8 == 7 && i + 1 < n) s += "\n         ";
    }
    s += "\n        </DataArray>\n";
  }
  s += "      </PointData>\n      <CellData>\n      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
  return s;
}

}  // namespace pierce
