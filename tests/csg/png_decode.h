#pragma once
// Decoder for the PNGs encode_png writes (stored deflate blocks only), checking every checksum:
// enough to read our own images back in tests.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pierce/io/image_writer.h"

namespace pierce::csgtest {

struct DecodedPng {
  std::uint32_t width = 0, height = 0;
  int bits = 0, colour_type = 0;
  std::string raw;    // inflated scanlines, each with its filter byte
  std::string error;  // empty when the file is well formed

  // Sample c of pixel (x, y), y from the top, scaled to [0, 1] (filter byte 0 assumed).
  double sample(std::uint32_t x, std::uint32_t y, int c = 0) const {
    const int channels = colour_type == 0 ? 1 : colour_type == 2 ? 3 : 4;
    const std::size_t bps = std::size_t(bits / 8);
    const std::size_t row = 1 + std::size_t(width) * std::size_t(channels) * bps;
    const std::size_t at = std::size_t(y) * row + 1 + (std::size_t(x) * std::size_t(channels) + std::size_t(c)) * bps;
    if (bits == 8) return std::uint8_t(raw[at]) / 255.0;
    return (std::uint8_t(raw[at]) * 256 + std::uint8_t(raw[at + 1])) / 65535.0;
  }
};

inline std::uint32_t png_be32(const std::string& s, std::size_t at) {
  return (std::uint32_t(std::uint8_t(s[at])) << 24) | (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

inline std::span<const std::uint8_t> png_bytes(const std::string& s, std::size_t from, std::size_t n) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()) + from, n};
}

inline DecodedPng decode_png(const std::string& png) {
  DecodedPng d;
  if (png.size() < 8 || png.substr(0, 8) != std::string("\x89PNG\r\n\x1a\n", 8)) {
    d.error = "bad signature";
    return d;
  }
  std::string idat;
  for (std::size_t pos = 8; pos + 12 <= png.size();) {
    const std::uint32_t len = png_be32(png, pos);
    if (pos + 12 + len > png.size()) {
      d.error = "truncated chunk";
      return d;
    }
    const std::string type = png.substr(pos + 4, 4);
    if (crc32(png_bytes(png, pos + 4, 4 + len)) != png_be32(png, pos + 8 + len)) {
      d.error = "bad CRC in " + type;
      return d;
    }
    if (type == "IHDR") {
      d.width = png_be32(png, pos + 8);
      d.height = png_be32(png, pos + 12);
      d.bits = std::uint8_t(png[pos + 16]);
      d.colour_type = std::uint8_t(png[pos + 17]);
    } else if (type == "IDAT") {
      idat += png.substr(pos + 8, len);
    }
    pos += 12 + len;
  }
  if (idat.size() < 6 || std::uint8_t(idat[0]) != 0x78 || (std::uint8_t(idat[0]) * 256 + std::uint8_t(idat[1])) % 31) {
    d.error = "bad zlib header";
    return d;
  }
  std::size_t p = 2;
  for (bool last = false; !last;) {
    if (p + 5 > idat.size()) {
      d.error = "truncated deflate block";
      return d;
    }
    last = idat[p] & 1;
    if (((idat[p] >> 1) & 3) != 0) {
      d.error = "not a stored block";
      return d;
    }
    const std::size_t len = std::uint8_t(idat[p + 1]) | (std::size_t(std::uint8_t(idat[p + 2])) << 8);
    const std::size_t nlen = std::uint8_t(idat[p + 3]) | (std::size_t(std::uint8_t(idat[p + 4])) << 8);
    if ((len ^ 0xffff) != nlen || p + 5 + len > idat.size()) {
      d.error = "bad stored block length";
      return d;
    }
    d.raw += idat.substr(p + 5, len);
    p += 5 + len;
  }
  if (p + 4 > idat.size() || adler32(png_bytes(d.raw, 0, d.raw.size())) != png_be32(idat, p)) d.error = "bad Adler-32";
  return d;
}

}  // namespace pierce::csgtest
