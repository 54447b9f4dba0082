#pragma once
// CSG over the named solids of a scene, evaluated per ray on its partitions (Roth 1982).
//
// Expressions (docs/CSG.md):
//   expr := name | op '(' expr (',' expr)+ ')'
//   op   := union | intersection | difference     difference(a, b, c) = a minus b minus c
//   name := a bare name (any run of characters other than blanks, ',', '(', ')' and '"'),
//           a quoted name "..." (\" and \\ escape), or #N for geometry id N.
// A name stands for every geometry carrying it (their union); a bare N that no geometry is named
// is geometry id N, as everywhere solids are named (solid_reference.h). A bare word followed by '(' is an
// operation; a solid called e.g. "union" is written as a quoted name.
//
// Evaluation: a partition is inside the expression when the expression, read as a boolean function
// of "inside solid s", is true for the partition's solid set; adjacent true partitions merge. No
// operation is a complement, so air is always outside and only partitions need evaluating. Touching
// solids (adjacent partitions) merge into one interval under union with no seam.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pierce/analysis/obliquity.h"  // obliquity_deg, declared here before
#include "pierce/analysis/ray_partitions.h"
#include "pierce/enum_names.h"
#include "pierce/kernel.h"
#include "pierce/node_stack.h"
#include "pierce/scene.h"

namespace pierce::analysis {

enum class CsgOp : std::uint8_t { leaf, union_of, intersection_of, difference_of };

struct CsgNode {
  CsgOp op = CsgOp::leaf;
  std::uint32_t arg = 0;  // leaf: index into CsgExpr::leaves; operation: number of operands
};

// A parsed and bound expression. `program` is postfix: operands before their operation.
struct CsgExpr {
  std::string text;
  std::vector<CsgNode> program;
  std::vector<std::string> leaf_names;               // as written (quotes removed)
  std::vector<std::vector<std::uint32_t>> leaves;    // geometry ids of each leaf, ascending
  std::vector<std::uint32_t> solids() const;         // every geometry referenced, ascending, unique
};

// Parses `text` and binds its names to `scene`'s geometries (csg_parser.cpp; the evaluator is in
// csg_evaluator.cpp, the point classifier in csg_classifier.cpp). Throws InputError:
//  - "csg expression, column C: <what is wrong>" followed by the expression and a caret line;
//  - "csg expression: unknown solid name(s) 'x', 'y' (known: ...)" listing every unknown name.
CsgExpr parse_csg(std::string_view text, const Scene& scene);

// Hit distances come from float arithmetic per triangle: two solids sharing a face through
// different triangles (other diagonals, T-junctions) cross it at t values a few ulps apart, which
// would read as a sliver of overlap or gap between touching solids. This drops partitions no longer
// than `tie_t`, closes gaps no longer than `tie_t` (the later partition starts where the earlier one
// ends) and merges adjacent partitions with equal solid sets. tie_t is in units of the ray's |dir|;
// tie_distance() (tie_distance.h) gives the usual length.
void snap_partitions(RayPartitions& parts, double tie_t);

// A result interval of one ray: [t_in, t_out] with the crossings that bound it (invalid where
// the interval is cut by the ray's ends).
struct CsgInterval {
  double t_in = 0, t_out = 0;
  Hit in_hit, out_hit;
};

// Evaluates one expression on partitions. Reusable across rays; not thread-safe (one per thread).
class CsgEvaluator {
 public:
  CsgEvaluator(const CsgExpr& expr, std::size_t geometry_count);
  // True when a point inside exactly `solids` (ascending geometry ids) is inside the expression.
  bool contains(std::span<const std::uint32_t> solids);
  // Clears `out` and writes the expression's intervals along the ray whose partitions are given.
  void evaluate(const RayPartitions& parts, std::vector<CsgInterval>& out);
  std::uint64_t evaluations = 0;  // contains() calls so far (work counter)

 private:
  const CsgExpr* expr_;
  std::vector<std::uint8_t> inside_;  // per geometry, scratch
  std::vector<std::uint8_t> stack_;
};

enum class PointClass : std::uint8_t { outside, inside, on };
constexpr EnumTable<PointClass, 3> enum_table(PointClass) {
  using enum PointClass;
  return {"point class", {{outside, "outside"}, {inside, "inside"}, {on, "on"}}};
}
inline std::string_view point_class_name(PointClass c);  // enum_name (its table follows the namespace)

// Inside / outside / on of points with respect to an expression, by the same machinery: rays
// through the point along two fixed skew directions, their partitions, the expression's intervals.
// "on": the point lies within `tolerance` (absolute length) of an interval's end on either ray, or
// the two rays disagree (which only happens at a boundary), or it lies within `tolerance` of a
// solid's surface that both rays only graze (a vertex or edge the rays touch at the point alone)
// and being inside that solid would change the expression's value there. Partitions are snapped
// with the same tolerance (snap_partitions). Not thread-safe (one per thread).
class PointClassifier {
 public:
  // tolerance = tie_distance(scene, tolerance_rel) (tie_distance.h). The kernel must be exact.
  PointClassifier(const Accel& accel, const CsgExpr& expr, KernelKind kernel = kDefaultKernel,
                  double tolerance_rel = 1e-6);
  PointClass classify(Vec3d point);
  double tolerance() const { return tolerance_; }

 private:
  PointClass classify_along(Vec3d point, Vec3d dir, std::size_t which);  // which: 0 or 1
  bool on_grazed_surface(Vec3d point);

  const Accel* accel_;
  HitIterator it_;
  PartitionBuilder builder_;
  CsgEvaluator eval_;
  double tolerance_;
  std::vector<Hit> hits_;
  RayPartitions parts_;
  std::vector<CsgInterval> intervals_;
  // Per ray: the solids claiming the ray just before and just after the point (t = -+probe).
  std::array<std::vector<std::uint32_t>, 4> sides_;
  std::vector<std::uint32_t> near_, with_;  // scratch for on_grazed_surface
  NodeStack<double> stack_;
};

}  // namespace pierce::analysis

inline std::string_view pierce::analysis::point_class_name(PointClass c) { return enum_name(c); }
