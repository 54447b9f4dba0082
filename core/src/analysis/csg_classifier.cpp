// Points inside / outside / on an expression, from rays through them (csg.h, PointClassifier).
#include <algorithm>
#include <cmath>
#include <limits>

#include "pierce/analysis/bvh_query.h"
#include "pierce/analysis/csg.h"
#include "pierce/analysis/tie_distance.h"

namespace pierce::analysis {

PointClassifier::PointClassifier(const Accel& accel, const CsgExpr& expr, KernelKind kernel, double tolerance_rel)
    : accel_(&accel),
      it_(accel, kernel, KernelOptions{HitOrder{TieOrder::leave_before_enter}}),
      builder_(accel.scene().geometries().size()),
      eval_(expr, accel.scene().geometries().size()),
      tolerance_(tie_distance(accel.scene(), tolerance_rel)) {
  if (!is_exact(kernel)) throw std::invalid_argument("point classification needs an exact kernel");
  if (!(tolerance_rel >= 0)) throw std::invalid_argument("point classification tolerance must be >= 0");
}

PointClass PointClassifier::classify_along(Vec3d point, Vec3d dir, std::size_t which) {
  const Ray ray{point, dir, 0.0, std::numeric_limits<double>::infinity()};
  hits_.clear();
  collect_hits(it_, full_line_ray(ray, accel_->scene().bounds()), 0, hits_);
  builder_.build(hits_, parts_);
  snap_partitions(parts_, tolerance_);
  eval_.evaluate(parts_, intervals_);
  // dir is unit length: t is a distance.
  const double probe = std::max(tolerance_, 1e-12 * accel_->scene().scale());
  for (std::size_t side = 0; side < 2; ++side) {
    const double t = side == 0 ? -probe : probe;
    std::vector<std::uint32_t>& out = sides_[2 * which + side];
    out.clear();
    for (const Partition& p : parts_.partitions)
      if (p.t_in <= t && t <= p.t_out) {
        const auto s = parts_.solids_of(p);
        out.assign(s.begin(), s.end());
        break;
      }
  }
  for (const CsgInterval& iv : intervals_) {
    if (std::abs(iv.t_in) <= tolerance_ || std::abs(iv.t_out) <= tolerance_) return PointClass::on;
    if (iv.t_in < 0 && 0 < iv.t_out) return PointClass::inside;
  }
  return PointClass::outside;
}

PointClass PointClassifier::classify(Vec3d point) {
  // Two skew unit directions, unlikely to lie in a modelled face's plane: a ray lying in the plane
  // of a face the point is on would not see that face.
  static constexpr Vec3d kDir1{0.5345224838248488, 0.2672612419124244, 0.8017837257372732};
  static constexpr Vec3d kDir2{-0.3015113445777636, 0.9045340337332909, -0.3015113445777636};
  const PointClass a = classify_along(point, kDir1, 0);
  if (a == PointClass::on) return a;
  const PointClass b = classify_along(point, kDir2, 1);
  if (b == PointClass::on || a != b) return PointClass::on;
  if (on_grazed_surface(point)) return PointClass::on;
  return a;
}

// Both rays agree and no interval ends near the point, yet the point may lie on a vertex or edge
// of a solid that both rays touch only there (its crossings cancel, or none is reported): e.g. the
// corner two boxes share, seen by rays that leave the one and miss the other. A solid within the
// tolerance of the point that neither ray has inside it on either side of the point is such a
// grazed solid; the point is "on" when being inside it would change the expression's value next
// to the point.
bool PointClassifier::on_grazed_surface(Vec3d point) {
  const Vec3d r{tolerance_, tolerance_, tolerance_};
  BBoxd box;
  box.extend(point - r);
  box.extend(point + r);
  near_.clear();
  for_each_overlapping(accel_->wide_double(), box, stack_, [&](const Triangle<double>& t) {
    if (std::find(near_.begin(), near_.end(), t.geom) != near_.end()) return;
    const Vec3d c = closest_point_on_triangle(point, t.v0, t.v1, t.v2);
    if (length(c - point) <= tolerance_) near_.push_back(t.geom);
  });
  for (std::uint32_t g : near_) {
    const auto has = [g](const std::vector<std::uint32_t>& s) { return std::binary_search(s.begin(), s.end(), g); };
    if (std::any_of(sides_.begin(), sides_.end(), has)) continue;  // crossed or inside: the rays saw it
    for (const std::vector<std::uint32_t>& side : sides_) {
      with_ = side;
      with_.insert(std::lower_bound(with_.begin(), with_.end(), g), g);
      if (eval_.contains(with_) != eval_.contains(side)) return true;
    }
  }
  return false;
}

}  // namespace pierce::analysis
