#include "pierce/analysis/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pierce::analysis {

double percentile_sorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double pos = std::clamp(q, 0.0, 100.0) / 100.0 * double(sorted.size() - 1);
  const std::size_t lo = std::size_t(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double f = pos - double(lo);
  return sorted[lo] + (sorted[hi] - sorted[lo]) * f;
}

std::pair<double, double> default_color_range(std::vector<double> values, double min_thickness) {
  double lo = 0, hi = 1;
  if (min_thickness > 0 && std::isfinite(min_thickness)) {
    hi = kColorRangeThinFactor * min_thickness;
  } else {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
                 values.end());
    if (values.empty()) return {lo, hi};
    std::sort(values.begin(), values.end());
    lo = percentile_sorted(values, kColorRangePercentiles[0]);
    hi = percentile_sorted(values, kColorRangePercentiles[1]);
  }
  if (!(hi > lo)) hi = lo + std::max(std::abs(lo) * 1e-3, 1e-9);  // a uniform wall: one colour
  return {lo, hi};
}

Summary summarize(std::vector<double> values, const std::vector<double>& percentiles, int histogram_bins) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
               values.end());
  Summary s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.count = values.size();
  s.min = values.front();
  s.max = values.back();
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / double(values.size());
  for (double q : percentiles) s.percentiles.emplace_back(q, percentile_sorted(values, q));
  const int bins = std::max(1, histogram_bins);
  s.histogram.edges.resize(std::size_t(bins) + 1);
  s.histogram.counts.assign(std::size_t(bins), 0);
  const double width = (s.max - s.min) / bins;
  for (int i = 0; i <= bins; ++i) s.histogram.edges[std::size_t(i)] = i == bins ? s.max : s.min + width * i;
  for (double v : values) {
    std::size_t b = width > 0 ? std::size_t((v - s.min) / width) : 0;
    s.histogram.counts[std::min(b, std::size_t(bins) - 1)]++;
  }
  return s;
}

}  // namespace pierce::analysis
