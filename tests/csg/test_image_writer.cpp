// PNG and VTI encoders: the PNG is decoded back by libspng (chunk CRCs, Adler-32) and compared
// sample by sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "png_decode.h"
#include "pierce/render/image_writer.h"

namespace pierce {
namespace {

using csgtest::decode_png;
using csgtest::DecodedPng;

DecodedPng decode(const std::string& png) {
  DecodedPng d = decode_png(png);
  EXPECT_EQ(d.error, "");
  return d;
}

TEST(ImageWriter, Grey16RoundTrips) {
  const int w = 300, h = 250;  // > 64 KiB of samples: more than one zlib buffer
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
  ASSERT_EQ(d.pixels.size(), std::size_t(h) * 2 * w);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t at = std::size_t(y) * 2 * w + 2 * std::size_t(x);
      const int q = std::uint8_t(d.pixels[at]) * 256 + std::uint8_t(d.pixels[at + 1]);
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
  EXPECT_EQ(d.pixels, std::string("\xff\0\0\xff\0\xff\0\x80", 8));
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
