// The false-colour renderer behind `pierce thickness/overlaps --png`: a thickness map of two
// slabs of different thickness rendered to PNG, decoded back and checked pixel by pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "png_decode.h"
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/generators.h"
#include "pierce/render/false_colour.h"

namespace pierce {
namespace {

using csgtest::decode_png;

// Slab A [0,1]x[0,1]x[0,0.2] and slab B [1.5,2.5]x[0,1]x[0,0.6], side by side along x.
Scene two_slabs() {
  return gen::to_scene({gen::box({0, 0, 0}, {1, 1, 0.2}, "thin"), gen::box({1.5, 0, 0}, {2.5, 1, 0.6}, "thick")});
}

ElementField face_thickness(const Scene& scene, const analysis::ThicknessResult& r) {
  ElementField f;
  f.at = ElementField::At::face;
  f.values.resize(scene.geometries().size());
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
    f.values[g].assign(scene.geometry(g).triangles.size(), std::nan(""));
  for (std::size_t i = 0; i < r.size(); ++i) f.values[r.solid[i]][r.element[i]] = r.thickness[i];
  return f;
}

struct Rgb {
  double r, g, b;
};
Rgb pixel(const csgtest::DecodedPng& d, std::uint32_t x, std::uint32_t y) {
  return {d.sample(x, y, 0), d.sample(x, y, 1), d.sample(x, y, 2)};
}
bool white(Rgb c) { return c.r == 1 && c.g == 1 && c.b == 1; }
// Within two 8-bit steps: one for the PNG, one for the shade factor read back from a pixel.
void expect_colour(Rgb got, Vec3d want, const char* what) {
  EXPECT_NEAR(got.r, want.x, 2.0 / 255) << what;
  EXPECT_NEAR(got.g, want.y, 2.0 / 255) << what;
  EXPECT_NEAR(got.b, want.z, 2.0 / 255) << what;
}

TEST(FalseColour, ThicknessMapFromAboveShowsEachSlabsOwnThickness) {
  const Scene scene = two_slabs();
  const Accel accel(scene);
  analysis::ThicknessOptions topts;
  topts.per = analysis::SampleAt::face;
  const analysis::ThicknessResult r = analysis::compute_thickness(accel, topts);
  const ElementField field = face_thickness(scene, r);

  FalseColourOptions opts;
  opts.width = 240;
  opts.height = 120;
  opts.view_dir = {0, 0, -1};  // looking down: x to the right, y up
  opts.legend = false;
  const FalseColourImage img = render_false_colour(accel, field, opts);
  ASSERT_TRUE(img.completed);
  // Thickness of the faces: A's top 0.2 (its smallest), B's sides 1 (the largest).
  EXPECT_NEAR(img.range_min, 0.2, 1e-6);  // float kernels
  EXPECT_NEAR(img.range_max, 1.0, 1e-6);

  const std::string png = false_colour_png(img);
  const csgtest::DecodedPng d = decode_png(png);
  ASSERT_EQ(d.error, "");
  EXPECT_EQ(d.width, 240u);
  EXPECT_EQ(d.height, 120u);
  EXPECT_EQ(d.bits, 8);
  EXPECT_EQ(d.colour_type, 2);

  // The middle row crosses both slabs' top faces: same normal, so the same shade factor.
  const std::uint32_t row = d.height / 2;
  std::uint32_t first = d.width, last = 0, hit = 0;
  for (std::uint32_t x = 0; x < d.width; ++x)
    if (!white(pixel(d, x, row))) first = std::min(first, x), last = std::max(last, x), ++hit;
  ASSERT_LT(first, last) << "nothing drawn on the middle row";
  // A gap between the slabs (x in (1, 1.5)) stays background: 0.5 of the 2.5 span.
  EXPECT_LT(hit, (last - first + 1) * 9 / 10);
  const std::uint32_t span = last - first;
  const Rgb over_a = pixel(d, first + span / 5, row), over_b = pixel(d, last - span / 5, row);
  const double s_b = (0.6 - 0.2) / (1.0 - 0.2);
  const Vec3d want_a = colour_of(ColourMap::viridis, 0.0), want_b = colour_of(ColourMap::viridis, s_b);
  const double shade = over_b.g / want_b.y;
  EXPECT_GT(shade, 0.3);
  EXPECT_LE(shade, 1.0 + 1e-9);
  expect_colour(over_a, want_a * shade, "slab A top (thickness 0.2)");
  expect_colour(over_b, want_b * shade, "slab B top (thickness 0.6)");
  EXPECT_GT(std::abs(over_a.g - over_b.g) + std::abs(over_a.b - over_b.b), 0.2);
  // The corners of the picture are background.
  EXPECT_TRUE(white(pixel(d, 0, 0)));
  EXPECT_TRUE(white(pixel(d, d.width - 1, d.height - 1)));
}

TEST(FalseColour, NoValueIsGreyAndMarkedIsHighlighted) {
  const Scene scene = two_slabs();
  const Accel accel(scene);
  ElementField field;
  field.at = ElementField::At::vertex;
  field.values = {std::vector<double>(scene.geometry(0).vertices.size(), 1.0), {}};  // B: no values
  field.marked = {std::vector<std::uint8_t>(scene.geometry(0).vertices.size(), 1), {}};
  FalseColourOptions opts;
  opts.width = 200;
  opts.height = 100;
  opts.view_dir = {0, 0, -1};
  opts.legend = false;
  const FalseColourImage img = render_false_colour(accel, field, opts);
  const csgtest::DecodedPng d = decode_png(false_colour_png(img));
  ASSERT_EQ(d.error, "");
  const std::uint32_t row = d.height / 2;
  std::uint32_t first = d.width, last = 0;
  for (std::uint32_t x = 0; x < d.width; ++x)
    if (!white(pixel(d, x, row))) first = std::min(first, x), last = std::max(last, x);
  ASSERT_LT(first, last);
  const Rgb a = pixel(d, first + (last - first) / 5, row), b = pixel(d, last - (last - first) / 5, row);
  EXPECT_GT(a.r, a.g + 0.5) << "marked elements are drawn red";
  EXPECT_NEAR(b.r, b.g, 1e-9) << "elements without a value are grey";
  EXPECT_NEAR(b.g, b.b, 1e-9);
  EXPECT_LT(b.r, 0.9);
}

TEST(FalseColour, LegendDrawsTheColourBarOnTheRight) {
  const Scene scene = two_slabs();
  const Accel accel(scene);
  ElementField field;
  field.values = {std::vector<double>(scene.geometry(0).triangles.size(), 0.5),
                  std::vector<double>(scene.geometry(1).triangles.size(), 2.0)};
  FalseColourOptions opts;
  opts.width = 300;
  opts.height = 150;
  auto right_strip_drawn = [&](bool legend) {
    opts.legend = legend;
    const csgtest::DecodedPng d = decode_png(false_colour_png(render_false_colour(accel, field, opts)));
    std::size_t n = 0;
    for (std::uint32_t y = 0; y < d.height; ++y)
      for (std::uint32_t x = d.width - 40; x < d.width; ++x) n += !white(pixel(d, x, y));
    return n;
  };
  EXPECT_GT(right_strip_drawn(true), 100u);
  EXPECT_EQ(right_strip_drawn(false), 0u);
}

TEST(FalseColour, CancelledThroughProgress) {
  const Scene scene = two_slabs();
  const Accel accel(scene);
  const FalseColourImage img = render_false_colour(accel, {}, {}, [](std::size_t, std::size_t) { return false; });
  EXPECT_FALSE(img.completed);
}

TEST(FalseColour, BadOptionsAreRejected) {
  const Scene scene = two_slabs();
  const Accel accel(scene);
  FalseColourOptions opts;
  opts.width = 4;
  EXPECT_THROW(render_false_colour(accel, {}, opts), std::invalid_argument);
  opts = {};
  opts.view_dir = {0, 0, 0};
  EXPECT_THROW(render_false_colour(accel, {}, opts), std::invalid_argument);
  ElementField wrong;
  wrong.values = {std::vector<double>(3, 1.0)};  // slab A has 12 triangles
  EXPECT_THROW(render_false_colour(accel, wrong, {}), std::invalid_argument);
  int w = 0, h = 0;
  EXPECT_THROW(parse_picture_size("--png-size", "800", w, h), InputError);
  EXPECT_THROW(parse_picture_size("--png-size", "800x6", w, h), InputError);
  parse_picture_size("--png-size", "640x480", w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  EXPECT_THROW(parse_view_direction("--png-view", "1,2"), InputError);
  EXPECT_THROW(parse_view_direction("--png-view", "0,0,0"), InputError);
  EXPECT_EQ(parse_view_direction("--png-view", "1,-2,3.5"), (Vec3d{1, -2, 3.5}));
}

// The heat map of traversal work: each pixel's count is what the kernel's counting variant counts
// for that pixel's ray, which the picture shows on the colour map from 0 to the maximum.
TEST(CostHeatmap, PixelsShowTheCountingKernelsWorkPerRay) {
  const Scene scene = gen::to_scene(gen::stacked_plates(6));
  const Accel accel(scene);
  FalseColourOptions opts;
  opts.width = 96;
  opts.height = 64;
  opts.view_dir = {0.3, 0.2, -1};
  opts.legend = false;
  for (const auto& [kind, max_hits, metric] :
       {std::tuple{KernelKind::queue, std::size_t(0), CostMetric::prim_tests},
        std::tuple{KernelKind::restart, std::size_t(1), CostMetric::traversal_steps},
        std::tuple{KernelKind::filter, std::size_t(0), CostMetric::node_tests}}) {
    SCOPED_TRACE(std::string(kernel_name(kind)) + " " + std::string(cost_metric_name(metric)));
    HeatmapStats stats;
    const FalseColourImage img = render_cost_heatmap(accel, kind, max_hits, metric, opts, stats);
    ASSERT_TRUE(img.completed);
    const auto png = decode_png(false_colour_png(img));

    const PictureFrame fr = PictureFrame::fit(scene, opts);
    KernelOptions counting;
    counting.count = true;
    HitIterator it(accel, kind, counting);
    std::vector<Hit> hits;
    std::vector<double> cost;
    for (int y = 0; y < fr.height; ++y)
      for (int x = 0; x < fr.view_width; ++x) {
        const Counters before = it.counters();
        hits.clear();
        collect_hits(it, fr.ray(x, y), max_hits, hits);
        const Counters c = it.counters() - before;
        cost.push_back(double(metric == CostMetric::prim_tests   ? c.prim_tests
                              : metric == CostMetric::node_tests ? c.node_tests
                                                                 : c.traversal_steps));
      }
    const double max = *std::max_element(cost.begin(), cost.end());
    double sum = 0;
    std::size_t working = 0;
    for (double c : cost) sum += c, working += c > 0;
    ASSERT_GT(max, 1.0);
    EXPECT_EQ(stats.max, max);
    EXPECT_DOUBLE_EQ(stats.mean, sum / double(cost.size()));
    EXPECT_EQ(img.pixels_hit, working);
    EXPECT_EQ(img.range_max, max);
    // The frame has a margin where rays miss the scene's box: no primitive tests there, only the
    // root's node test (one step), which every ray does.
    if (metric == CostMetric::prim_tests) EXPECT_LT(working, cost.size());
    else EXPECT_EQ(working, cost.size());
    for (int y = 0; y < fr.height; ++y)
      for (int x = 0; x < fr.view_width; ++x) {
        const double c = cost[std::size_t(y * fr.view_width + x)];
        const Rgb got = pixel(png, std::uint32_t(x), std::uint32_t(y));
        if (c == 0) ASSERT_TRUE(white(got)) << x << "," << y;
        else expect_colour(got, colour_of(opts.map, c / max), "heat");
      }
  }
  // Work grows with the hits asked for.
  HeatmapStats one, all;
  render_cost_heatmap(accel, KernelKind::queue, 1, CostMetric::prim_tests, opts, one);
  render_cost_heatmap(accel, KernelKind::queue, 0, CostMetric::prim_tests, opts, all);
  EXPECT_LT(one.mean, all.mean);
  EXPECT_EQ(parse_cost_metric("steps"), CostMetric::traversal_steps);
  EXPECT_EQ(parse_cost_metric("nodes"), std::nullopt);
}

}  // namespace
}  // namespace pierce
