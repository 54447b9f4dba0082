#include "pierce/render/false_colour.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <tbb/enumerable_thread_specific.h>

#include "pierce/error.h"
#include "pierce/render/image_writer.h"
#include "pierce/parallel_for_items.h"

namespace pierce {

namespace {

constexpr Vec3d kBackground{1, 1, 1};
constexpr Vec3d kNoValue{0.62, 0.62, 0.62};
constexpr Vec3d kMarked{0.9, 0.1, 0.1};
constexpr Vec3d kText{0, 0, 0};

// Piecewise-linear maps through evenly spaced control colours.
constexpr std::array<Vec3d, 9> kViridis{{{0.267, 0.005, 0.329},
                                         {0.283, 0.141, 0.458},
                                         {0.254, 0.265, 0.530},
                                         {0.207, 0.372, 0.553},
                                         {0.164, 0.471, 0.558},
                                         {0.128, 0.567, 0.551},
                                         {0.135, 0.659, 0.518},
                                         {0.478, 0.821, 0.318},
                                         {0.993, 0.906, 0.144}}};
// Moreland's diverging cool-warm map.
constexpr std::array<Vec3d, 5> kCoolWarm{{{0.230, 0.299, 0.754},
                                          {0.552, 0.690, 0.996},
                                          {0.865, 0.865, 0.865},
                                          {0.958, 0.604, 0.482},
                                          {0.706, 0.016, 0.150}}};

template <std::size_t N>
Vec3d lerp_map(const std::array<Vec3d, N>& stops, double s) {
  const double x = std::clamp(std::isnan(s) ? 0.0 : s, 0.0, 1.0) * double(N - 1);
  const std::size_t i = std::min(std::size_t(x), N - 2);
  const double f = x - double(i);
  return stops[i] * (1 - f) + stops[i + 1] * f;
}

// 3 x 5 pixel glyphs for the legend's numbers, one row of 3 bits per entry, top row first.
struct Glyph {
  char c;
  std::array<std::uint8_t, 5> rows;
};
constexpr Glyph kGlyphs[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
    {'+', {0, 2, 7, 2, 0}}, {'e', {0, 7, 7, 4, 7}}, {'n', {0, 6, 5, 5, 5}}, {'a', {0, 7, 1, 7, 7}},
    {'i', {2, 0, 2, 2, 2}}, {'f', {3, 4, 7, 4, 4}},
};

struct Canvas {
  int width, height;
  std::vector<double>& rgb;

  void set(int x, int y, Vec3d c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    double* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    p[0] = c.x, p[1] = c.y, p[2] = c.z;
  }
  // Text with its top-left corner at (x, y), glyphs scaled by `scale`.
  void text(int x, int y, const std::string& s, int scale) {
    for (char ch : s) {
      for (const Glyph& g : kGlyphs) {
        if (g.c != ch) continue;
        for (int row = 0; row < 5; ++row)
          for (int col = 0; col < 3; ++col)
            if (g.rows[std::size_t(row)] & (4 >> col))
              for (int dy = 0; dy < scale; ++dy)
                for (int dx = 0; dx < scale; ++dx) set(x + col * scale + dx, y + row * scale + dy, kText);
      }
      x += 4 * scale;
    }
  }
};

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void check_field(const Scene& scene, const ElementField& field) {
  const auto& geoms = scene.geometries();
  if (field.values.size() > geoms.size() || field.marked.size() > geoms.size())
    throw std::invalid_argument("false colour: field has more geometries than the scene");
  auto expected = [&](std::size_t g) {
    return field.at == ElementField::At::vertex ? geoms[g].vertices.size() : geoms[g].triangles.size();
  };
  for (std::size_t g = 0; g < field.values.size(); ++g)
    if (!field.values[g].empty() && field.values[g].size() != expected(g))
      throw std::invalid_argument("false colour: geometry " + std::to_string(g) + " has " +
                                  std::to_string(field.values[g].size()) + " values, expected " +
                                  std::to_string(expected(g)));
  for (std::size_t g = 0; g < field.marked.size(); ++g)
    if (!field.marked[g].empty() && field.marked[g].size() != expected(g))
      throw std::invalid_argument("false colour: geometry " + std::to_string(g) + " has " +
                                  std::to_string(field.marked[g].size()) + " marks, expected " +
                                  std::to_string(expected(g)));
}

// The value (NaN if none) and mark at a hit.
std::pair<double, bool> value_at(const Scene& scene, const ElementField& field, const Hit& h) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (h.geom >= field.values.size() || field.values[h.geom].empty()) return {nan, false};
  const std::vector<double>& vals = field.values[h.geom];
  const std::vector<std::uint8_t>* marks =
      h.geom < field.marked.size() && !field.marked[h.geom].empty() ? &field.marked[h.geom] : nullptr;
  if (field.at == ElementField::At::face) return {vals[h.prim], marks && (*marks)[h.prim]};
  const Tri& tri = scene.geometry(h.geom).triangles[h.prim];
  const double w[3] = {1.0 - double(h.u) - double(h.v), double(h.u), double(h.v)};
  const int nearest = int(std::max_element(w, w + 3) - w);
  const bool mark = marks && (*marks)[tri[std::size_t(nearest)]];
  const double a = vals[tri[0]], b = vals[tri[1]], c = vals[tri[2]];
  // A corner without a value would poison the blend: take the nearest corner's value instead.
  if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c)) return {w[0] * a + w[1] * b + w[2] * c, mark};
  return {vals[tri[std::size_t(nearest)]], mark};
}

}  // namespace

Vec3d colour_of(ColourMap map, double s) {
  return map == ColourMap::viridis ? lerp_map(kViridis, s) : lerp_map(kCoolWarm, s);
}

PictureFrame PictureFrame::fit(const Scene& scene, const FalseColourOptions& opts) {
  constexpr int kMaxSide = 16384;
  if (opts.width < 16 || opts.height < 16 || opts.width > kMaxSide || opts.height > kMaxSide)
    throw std::invalid_argument("false colour: picture size must be 16..16384 pixels per side");
  const double view_len = length(opts.view_dir);
  if (!std::isfinite(view_len) || view_len == 0)
    throw std::invalid_argument("false colour: view direction must be finite and non-zero");
  PictureFrame fr;
  fr.width = opts.width;
  fr.height = opts.height;
  // Colour bar strip on the right, wide enough for a label like "-1.23e-05".
  fr.glyph_scale = std::max(1, opts.height / 200);
  fr.label_width = 9 * 4 * fr.glyph_scale;
  fr.legend_width = opts.legend ? std::max(opts.width / 6, fr.label_width + 8) : 0;
  fr.legend = opts.legend && opts.width - fr.legend_width >= opts.width / 2;
  fr.view_width = fr.legend ? opts.width - fr.legend_width : opts.width;

  fr.f = opts.view_dir * (1.0 / view_len);
  Vec3d up{0, 0, 1};
  if (length(cross(fr.f, up)) < 1e-6) up = {0, 1, 0};
  fr.right = cross(fr.f, up);
  fr.right = fr.right * (1.0 / length(fr.right));
  fr.cam_up = cross(fr.right, fr.f);
  const BBoxd& box = scene.bounds();
  const Vec3d centre = box.empty() ? Vec3d{} : box.center();
  double half_r = 0, half_u = 0;
  if (!box.empty())
    for (int i = 0; i < 8; ++i) {
      const Vec3d corner{i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z};
      half_r = std::max(half_r, std::abs(dot(corner - centre, fr.right)));
      half_u = std::max(half_u, std::abs(dot(corner - centre, fr.cam_up)));
    }
  fr.pixel = 1.06 * std::max(2 * half_r / fr.view_width, 2 * half_u / opts.height);
  if (!(fr.pixel > 0)) fr.pixel = scene.scale() / std::min(fr.view_width, opts.height);
  fr.eye = centre - fr.f * (2 * scene.scale());
  // A light above and left of the camera: in an isometric view of a box a headlight would shade
  // all three visible faces alike.
  fr.light = fr.cam_up * 0.5 - fr.right * 0.3 - fr.f;
  fr.light = fr.light * (1.0 / length(fr.light));
  return fr;
}

Ray PictureFrame::ray(int x, int y) const {
  Ray r;
  r.org = eye + right * ((x + 0.5 - 0.5 * view_width) * pixel) + cam_up * ((0.5 * height - y - 0.5) * pixel);
  r.dir = f;
  return r;
}

namespace {

FalseColourImage blank_image(const PictureFrame& fr) {
  FalseColourImage img;
  img.width = fr.width;
  img.height = fr.height;
  img.rgb.resize(std::size_t(img.width) * std::size_t(img.height) * 3);
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    img.rgb[i] = kBackground.x, img.rgb[i + 1] = kBackground.y, img.rgb[i + 2] = kBackground.z;
  return img;
}

void draw_legend(const PictureFrame& fr, Canvas& canvas, ColourMap map, double lo, double hi) {
  if (!fr.legend) return;
  const int g = fr.glyph_scale;
  const int margin = 6 * g;
  const int text_height = 5 * g;
  const int x0 = fr.view_width + (fr.legend_width - fr.label_width) / 2;
  const int bar_top = margin + text_height + margin, bar_bottom = fr.height - margin - text_height - margin;
  const int bar_width = std::max(8, fr.legend_width / 5);
  for (int y = bar_top; y < bar_bottom; ++y) {
    const double s = bar_bottom - 1 > bar_top ? double(bar_bottom - 1 - y) / double(bar_bottom - 1 - bar_top) : 0.5;
    for (int x = x0; x < x0 + bar_width; ++x) canvas.set(x, y, colour_of(map, s));
  }
  canvas.text(x0, margin, label(hi), g);
  canvas.text(x0, bar_bottom + margin, label(lo), g);
}

std::uint64_t cost_of(const Counters& c, CostMetric m) {
  switch (m) {
    case CostMetric::node_tests: return c.node_tests;
    case CostMetric::prim_tests: return c.prim_tests;
    case CostMetric::traversal_steps: break;
  }
  return c.traversal_steps;
}

}  // namespace

FalseColourImage render_false_colour(const Accel& accel, const ElementField& field, const FalseColourOptions& opts,
                                     const Progress& progress) {
  const Scene& scene = accel.scene();
  const PictureFrame fr = PictureFrame::fit(scene, opts);
  check_field(scene, field);
  FalseColourImage img = blank_image(fr);

  // Value range of the colour map.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& vals : field.values)
    for (double v : vals)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isnan(opts.range_min)) lo = opts.range_min;
  if (!std::isnan(opts.range_max)) hi = opts.range_max;
  if (!(lo <= hi)) lo = 0, hi = 1;
  img.range_min = lo;
  img.range_max = hi;
  auto scaled = [&](double v) { return hi > lo ? (v - lo) / (hi - lo) : 0.5; };

  struct Worker {
    HitIterator it;
    std::size_t hits = 0;
  };
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker{HitIterator(accel, opts.kernel)}; });
  Canvas canvas{img.width, img.height, img.rgb};
  // One item per row of the picture.
  img.completed = parallel_for_items(std::size_t(fr.height), 4, workers, progress, [&](Worker& w, std::size_t row) {
    const int y = int(row);
    HitIterator& it = w.it;
    for (int x = 0; x < fr.view_width; ++x) {
      it.begin(fr.ray(x, y), 1);
      Hit h;
      if (!it.next(h)) continue;
      ++w.hits;
      const auto [value, marked] = value_at(scene, field, h);
      const Vec3d base = marked ? kMarked : std::isnan(value) ? kNoValue : colour_of(opts.map, scaled(value));
      const Vec3d n{h.ng.x, h.ng.y, h.ng.z};
      const double nl = length(n);
      // Two-sided Lambert with some ambient, so faces turned from the light stay readable.
      const double lambert = nl > 0 ? std::abs(dot(n, fr.light)) / nl : 1.0;
      canvas.set(x, y, base * (0.3 + 0.7 * lambert));
    }
  });
  for (const Worker& w : workers) img.pixels_hit += w.hits;
  draw_legend(fr, canvas, opts.map, lo, hi);
  return img;
}

FalseColourImage render_cost_heatmap(const Accel& accel, KernelKind kernel, std::size_t max_hits, CostMetric metric,
                                     const FalseColourOptions& opts, HeatmapStats& stats,
                                     const Progress& progress) {
  const PictureFrame fr = PictureFrame::fit(accel.scene(), opts);
  // First the counts (the colour range needs their maximum), then the picture.
  std::vector<std::uint64_t> cost(std::size_t(fr.view_width) * std::size_t(fr.height), 0);
  KernelOptions ko;
  ko.count = true;
  struct Worker {
    HitIterator it;
    std::vector<Hit> hits;
  };
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker{HitIterator(accel, kernel, ko), {}}; });
  FalseColourImage img = blank_image(fr);
  Canvas canvas{img.width, img.height, img.rgb};
  const bool completed = parallel_for_items(std::size_t(fr.height), 4, workers, progress, [&](Worker& w, std::size_t row) {
    const int y = int(row);
    HitIterator& it = w.it;
    std::vector<Hit>& hits = w.hits;
    for (int x = 0; x < fr.view_width; ++x) {
      const Counters before = it.counters();
      hits.clear();
      collect_hits(it, fr.ray(x, y), max_hits, hits);
      cost[std::size_t(y) * std::size_t(fr.view_width) + std::size_t(x)] = cost_of(it.counters() - before, metric);
    }
  });
  stats = {};
  stats.metric = metric;
  stats.rays = cost.size();
  std::size_t working = 0;
  double sum = 0;
  for (const std::uint64_t c : cost) {
    sum += double(c), working += c > 0;
    stats.max = std::max(stats.max, double(c));
  }
  stats.mean = cost.empty() ? 0 : sum / double(cost.size());
  stats.mean_over_scene = working ? sum / double(working) : 0;

  const double lo = std::isnan(opts.range_min) ? 0.0 : opts.range_min;
  double hi = std::isnan(opts.range_max) ? stats.max : opts.range_max;
  if (!(hi > lo)) hi = lo + 1;
  img.range_min = lo;
  img.range_max = hi;
  for (int y = 0; y < fr.height; ++y)
    for (int x = 0; x < fr.view_width; ++x) {
      const std::uint64_t c = cost[std::size_t(y) * std::size_t(fr.view_width) + std::size_t(x)];
      if (c == 0) continue;
      ++img.pixels_hit;
      canvas.set(x, y, colour_of(opts.map, (double(c) - lo) / (hi - lo)));
    }
  img.completed = completed;
  draw_legend(fr, canvas, opts.map, lo, hi);
  return img;
}

std::string false_colour_png(const FalseColourImage& image) {
  return encode_png(image.width, image.height, 3, 8, image.rgb);
}

void parse_picture_size(const std::string& option, const std::string& spec, int& width, int& height) {
  int w = 0, h = 0, used = 0;
  if (std::sscanf(spec.c_str(), "%dx%d%n", &w, &h, &used) != 2 || used != int(spec.size()) || w < 16 || h < 16 ||
      w > 16384 || h > 16384)
    throw InputError(option + " '" + spec + "': expected WIDTHxHEIGHT, each 16..16384 pixels (e.g. 800x600)");
  width = w, height = h;
}

Vec3d parse_view_direction(const std::string& option, const std::string& spec) {
  Vec3d d;
  int used = 0;
  if (std::sscanf(spec.c_str(), "%lf,%lf,%lf%n", &d.x, &d.y, &d.z, &used) != 3 || used != int(spec.size()) ||
      !all_finite(d) || length(d) == 0)
    throw InputError(option + " '" + spec + "': expected a non-zero direction x,y,z (e.g. -1,-1,-1)");
  return d;
}

}  // namespace pierce
