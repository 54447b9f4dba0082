#pragma once
// Convex polygon clipping and area in 2D, for overlap areas of coplanar triangles.
#include <vector>

#include "pierce/exact_predicates.h"

namespace pierce::analysis {

inline double signed_area(const std::vector<Vec2d>& p) {
  double a = 0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2d& u = p[i];
    const Vec2d& v = p[(i + 1) % n];
    a += u.x * v.y - u.y * v.x;
  }
  return 0.5 * a;
}

// Sutherland-Hodgman: the part of `subject` inside the counter-clockwise convex polygon `clip`.
inline std::vector<Vec2d> clip_convex(std::vector<Vec2d> subject, const std::vector<Vec2d>& clip) {
  for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Vec2d p = clip[e], q = clip[(e + 1) % clip.size()];
    auto side = [&](Vec2d s) { return (q.x - p.x) * (s.y - p.y) - (q.y - p.y) * (s.x - p.x); };
    std::vector<Vec2d> out;
    for (std::size_t i = 0; i < subject.size(); ++i) {
      const Vec2d a = subject[i], b = subject[(i + 1) % subject.size()];
      const double sa = side(a), sb = side(b);
      if (sa >= 0) out.push_back(a);
      if ((sa >= 0) != (sb >= 0)) {
        const double f = sa / (sa - sb);
        out.push_back({a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f});
      }
    }
    subject = std::move(out);
  }
  return subject;
}

}  // namespace pierce::analysis
