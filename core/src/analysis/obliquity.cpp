#include "pierce/analysis/obliquity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace pierce::analysis {

double obliquity_deg(Vec3d dir, const Hit& h) {
  if (!h.valid()) return std::numeric_limits<double>::quiet_NaN();
  const Vec3d n(h.ng);
  const double ln = length(n), ld = length(dir);
  if (ln == 0 || ld == 0) return std::numeric_limits<double>::quiet_NaN();
  const double c = std::min(1.0, std::abs(dot(n, dir)) / (ln * ld));
  return std::acos(c) * (180.0 / std::numbers::pi);
}

}  // namespace pierce::analysis
