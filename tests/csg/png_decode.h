#pragma once
// Reads the PNGs the encoders write back for tests, through libspng with every check it makes
// (signature, chunk CRCs, zlib Adler-32, sizes): any damage shows as a non-empty `error`.
#include <spng.h>

#include <cstdint>
#include <memory>
#include <string>

namespace pierce::csgtest {

struct DecodedPng {
  std::uint32_t width = 0, height = 0;
  int bits = 0, colour_type = 0;
  std::string pixels;  // samples as stored (16-bit ones big-endian), rows from the top, no filter bytes
  std::string error;   // empty when the file is well formed

  int channels() const { return colour_type == 0 ? 1 : colour_type == 2 ? 3 : 4; }

  // Sample c of pixel (x, y), y from the top, scaled to [0, 1].
  double sample(std::uint32_t x, std::uint32_t y, int c = 0) const {
    const std::size_t bps = std::size_t(bits / 8);
    const std::size_t row = std::size_t(width) * std::size_t(channels()) * bps;
    const std::size_t at = std::size_t(y) * row + (std::size_t(x) * std::size_t(channels()) + std::size_t(c)) * bps;
    if (bits == 8) return std::uint8_t(pixels[at]) / 255.0;
    return (std::uint8_t(pixels[at]) * 256 + std::uint8_t(pixels[at + 1])) / 65535.0;
  }
};

inline DecodedPng decode_png(const std::string& png) {
  DecodedPng d;
  const std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)> ctx(spng_ctx_new(0), &spng_ctx_free);
  const auto failed = [&](int status) {
    if (status != 0) d.error = spng_strerror(status);
    return status != 0;
  };
  if (failed(spng_set_png_buffer(ctx.get(), png.data(), png.size()))) return d;
  spng_ihdr ihdr{};
  if (failed(spng_get_ihdr(ctx.get(), &ihdr))) return d;
  d.width = ihdr.width;
  d.height = ihdr.height;
  d.bits = ihdr.bit_depth;
  d.colour_type = ihdr.color_type;
  std::size_t size = 0;
  if (failed(spng_decoded_image_size(ctx.get(), SPNG_FMT_RAW, &size))) return d;
  d.pixels.assign(size, '\0');
  if (failed(spng_decode_image(ctx.get(), d.pixels.data(), size, SPNG_FMT_RAW, 0))) return d;
  // Reads the chunks after the image data up to IEND, so that their CRCs are checked too.
  if (failed(spng_decode_chunks(ctx.get()))) return d;
  return d;
}

}  // namespace pierce::csgtest
