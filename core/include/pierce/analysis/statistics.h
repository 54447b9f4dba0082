#pragma once
// Summary statistics of a set of values: min, max, mean, percentiles, histogram.
#include <cstddef>
#include <utility>
#include <vector>

namespace pierce::analysis {

struct Histogram {
  std::vector<double> edges;        // bins + 1 increasing edges; empty when there are no values
  std::vector<std::size_t> counts;  // counts[i]: values in [edges[i], edges[i+1]) (last bin closed)
};

struct Summary {
  std::size_t count = 0;  // values summarised (finite ones only)
  double min = 0, max = 0, mean = 0;
  std::vector<std::pair<double, double>> percentiles;  // (q in [0,100], value)
  Histogram histogram;
};

// The quantiles reported by default.
inline const std::vector<double> kDefaultPercentiles = {1, 5, 10, 25, 50, 75, 90, 95, 99};

// Non-finite values are ignored. Percentiles interpolate linearly between order statistics
// (R's type 7). With no finite value every field is 0 and the histogram empty.
Summary summarize(std::vector<double> values, const std::vector<double>& percentiles = kDefaultPercentiles,
                  int histogram_bins = 20);

// Percentile q in [0,100] of sorted finite values (linear interpolation); NaN when empty.
double percentile_sorted(const std::vector<double>& sorted, double q);

// The colour range every front end gives a thickness map by default (the CLI's PNG, FreeCAD's
// legend, ParaView's ThicknessColorRange): with a thin threshold min_thickness > 0, 0 to
// kColorRangeThinFactor x min_thickness (thin walls stand out, walls a few times thicker get the
// ramp's colours); otherwise the kColorRangePercentiles of the finite values, so that a few slivers
// or long lines of sight do not squeeze every other wall into one colour. Values outside are drawn
// in the colour of the nearer end. {0, 1} without finite values; an empty range is widened.
inline constexpr double kColorRangeThinFactor = 4.0;
inline constexpr double kColorRangePercentiles[2] = {2.0, 98.0};
std::pair<double, double> default_color_range(std::vector<double> values, double min_thickness = 0);

}  // namespace pierce::analysis
