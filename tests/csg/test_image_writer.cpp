// PNG and VTI encoders: the PNG is decoded back (chunk CRCs, stored deflate blocks, Adler-32) and
// compared sample by sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "png_decode.h"
#include "pierce/io/image_writer.h"

namespace pierce {
namespace {

using csgtest::decode_png;
using csgtest::DecodedPng;

std::span<const std::uint8_t> bytes(const std::string& s, std::size_t from, std::size_t n) {
  return csgtest::png_bytes(s, from, n);
}

DecodedPng decode(const std::string& png) {
  DecodedPng d = decode_png(png);
  EXPECT_EQ(d.error, "");
  return d;
}

TEST(ImageWriter, ChecksumsMatchKnownValues) {
  const std::string abc = "123456789";
  EXPECT_EQ(crc32(bytes(abc, 0, abc.size())), 0xCBF43926u);  // the standard CRC-32 check value
  const std::string wiki = "Wikipedia";
  EXPECT_EQ(adler32(bytes(wiki, 0, wiki.size())), 0x11E60398u);
}

TEST(ImageWriter, Grey16RoundTrips) {
  const int w = 300, h = 250;  // > 65535 raw bytes: several stored blocks
  std::vector<double> v(std::size_t(w) * h);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::fmod(i * 0.001234, 1.0);
  v[5] = -1;
  v[6] = 7;
  v[7] = std::nan("");
  const DecodedPng d = decode(encode_png(w, h, 1, 16, v));
  EXPECT_EQ(d.width, std::uint32_t(w));
  EXPECT_EQ(d.height, std::uint32_t(h));
  EXPECT_EQ(d.bits, 16);
  EXPECT_EQ(d.colour_type, 0);
  ASSERT_EQ(d.raw.size(), std::size_t(h) * (1 + 2 * w));
  for (int y = 0; y < h; ++y) {
    EXPECT_EQ(d.raw[std::size_t(y) * (1 + 2 * w)], 0);
    for (int x = 0; x < w; ++x) {
      const std::size_t at = std::size_t(y) * (1 + 2 * w) + 1 + 2 * std::size_t(x);
      const int q = std::uint8_t(d.raw[at]) * 256 + std::uint8_t(d.raw[at + 1]);
      double expect = v[std::size_t(y) * w + x];
      expect = std::isnan(expect) ? 0 : std::clamp(expect, 0.0, 1.0);
      EXPECT_EQ(q, int(std::lround(expect * 65535))) << x << "," << y;
    }
  }
}

TEST(ImageWriter, Rgba8HasColourType6) {
  const std::vector<double> v = {1, 0, 0, 1, 0, 1, 0, 0.5};
  const DecodedPng d = decode(encode_png(2, 1, 4, 8, v));
  EXPECT_EQ(d.colour_type, 6);
  EXPECT_EQ(d.raw, std::string("\0\xff\0\0\xff\0\xff\0\x80", 9));
  std::string corrupt = encode_png(2, 1, 4, 8, v);
  corrupt[corrupt.size() / 2] ^= 0x10;  // the decoder's checks do catch damage
  EXPECT_NE(decode_png(corrupt).error, "");
  EXPECT_THROW(encode_png(2, 2, 4, 8, v), std::invalid_argument);
  EXPECT_THROW(encode_png(2, 1, 2, 8, v), std::invalid_argument);
}

TEST(ImageWriter, VtiHasExtentSpacingAndValues) {
  const std::string s = encode_vti(3, 2, {1, 2, 0}, {0.5, 0.25, 1}, {{"T", {0, 0.5, 1, 0.25, 0.125, 2}}});
  EXPECT_NE(s.find("WholeExtent=\"0 2 0 1 0 0\""), std::string::npos);
  EXPECT_NE(s.find("Origin=\"1 2 0\" Spacing=\"0.5 0.25 1\""), std::string::npos);
  EXPECT_NE(s.find("Name=\"T\""), std::string::npos);
  EXPECT_NE(s.find(" 0 0.5 1 0.25 0.125 2"), std::string::npos);
  EXPECT_THROW(encode_vti(3, 2, {}, {1, 1, 1}, {{"T", {1}}}), std::invalid_argument);
}

}  // namespace
}  // namespace pierce
