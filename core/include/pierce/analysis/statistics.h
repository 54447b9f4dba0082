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

}  // namespace pierce::analysis
