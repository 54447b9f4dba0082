#include "pierce/io/image_writer.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pierce {

namespace {

void put_u32_be(std::string& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(char((v >> s) & 0xff));
}

std::span<const std::uint8_t> bytes_of(const std::string& s, std::size_t from = 0) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()) + from, s.size() - from};
}

void chunk(std::string& png, const char* type, const std::string& data) {
  put_u32_be(png, std::uint32_t(data.size()));
  const std::size_t start = png.size();
  png.append(type, 4);
  png += data;
  put_u32_be(png, crc32(bytes_of(png, start)));
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (std::uint8_t b : bytes) crc = table[(crc ^ b) & 0xff] ^ (crc >> 8);
  return ~crc;
}

std::uint32_t adler32(std::span<const std::uint8_t> bytes) {
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t x : bytes) {
    a = (a + x) % 65521;
    b = (b + a) % 65521;
  }
  return (b << 16) | a;
}

std::string encode_png(int width, int height, int channels, int bits, std::span<const double> samples) {
  if (width < 1 || height < 1 || (channels != 1 && channels != 3 && channels != 4) || (bits != 8 && bits != 16))
    throw std::invalid_argument("encode_png: bad image format");
  const std::size_t per_row = std::size_t(width) * std::size_t(channels);
  if (samples.size() != per_row * std::size_t(height)) throw std::invalid_argument("encode_png: wrong sample count");

  // Raw scanlines: filter byte 0 (none), then big-endian samples.
  const std::size_t bytes_per_sample = std::size_t(bits / 8);
  std::string raw;
  raw.reserve(std::size_t(height) * (1 + per_row * bytes_per_sample));
  const double top = bits == 8 ? 255.0 : 65535.0;
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    for (std::size_t k = 0; k < per_row; ++k) {
      const double v = samples[std::size_t(y) * per_row + k];
      const double c = std::isnan(v) ? 0.0 : std::min(1.0, std::max(0.0, v));
      const auto q = static_cast<std::uint32_t>(std::lround(c * top));
      if (bits == 16) raw.push_back(char(q >> 8));
      raw.push_back(char(q & 0xff));
    }
  }
  // zlib stream of stored deflate blocks (at most 65535 bytes each).
  std::string z = {char(0x78), char(0x01)};
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min<std::size_t>(65535, raw.size() - pos);
    const bool last = pos + len == raw.size();
    z.push_back(char(last ? 1 : 0));
    z.push_back(char(len & 0xff));
    z.push_back(char(len >> 8));
    z.push_back(char(~len & 0xff));
    z.push_back(char((~len >> 8) & 0xff));
    z.append(raw, pos, len);
    pos += len;
  } while (pos < raw.size());
  put_u32_be(z, adler32(bytes_of(raw)));

  std::string png = "\x89PNG\r\n\x1a\n";
  std::string ihdr;
  put_u32_be(ihdr, std::uint32_t(width));
  put_u32_be(ihdr, std::uint32_t(height));
  ihdr.push_back(char(bits));
  ihdr.push_back(char(channels == 1 ? 0 : channels == 3 ? 2 : 6));  // colour type
  ihdr.push_back(0);  // deflate
  ihdr.push_back(0);  // adaptive filtering (all rows use "none")
  ihdr.push_back(0);  // no interlace
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  return png;
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
