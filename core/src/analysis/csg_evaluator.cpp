// CSG evaluation on a ray's partitions: snapping float-noise slivers between touching solids, and
// the expression's intervals (csg.h).
#include <algorithm>

#include "pierce/analysis/csg.h"

namespace pierce::analysis {

void snap_partitions(RayPartitions& parts, double tie_t) {
  auto& ps = parts.partitions;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    Partition p = ps[k];
    if (p.t_out - p.t_in <= tie_t) continue;
    if (kept > 0) {
      Partition& prev = ps[kept - 1];
      if (p.t_in - prev.t_out <= tie_t) {
        p.t_in = prev.t_out;
        const auto a = parts.solids_of(prev), b = parts.solids_of(p);
        if (std::equal(a.begin(), a.end(), b.begin(), b.end())) {
          prev.t_out = p.t_out;
          prev.out_hit = p.out_hit;
          continue;
        }
      }
    }
    ps[kept++] = p;
  }
  ps.resize(kept);
}

CsgEvaluator::CsgEvaluator(const CsgExpr& expr, std::size_t geometry_count)
    : expr_(&expr), inside_(geometry_count, 0) {
  stack_.reserve(expr.program.size());
}

bool CsgEvaluator::contains(std::span<const std::uint32_t> solids) {
  ++evaluations;
  for (std::uint32_t g : solids)
    if (g < inside_.size()) inside_[g] = 1;
  stack_.clear();
  for (const CsgNode& n : expr_->program) {
    if (n.op == CsgOp::leaf) {
      std::uint8_t v = 0;
      for (std::uint32_t g : expr_->leaves[n.arg]) v |= inside_[g];
      stack_.push_back(v);
      continue;
    }
    const std::size_t first = stack_.size() - n.arg;
    std::uint8_t v = stack_[first];
    for (std::size_t k = first + 1; k < stack_.size(); ++k) {
      switch (n.op) {
        case CsgOp::union_of: v = v | stack_[k]; break;
        case CsgOp::intersection_of: v = v & stack_[k]; break;
        case CsgOp::difference_of: v = v & std::uint8_t(!stack_[k]); break;
        case CsgOp::leaf: break;
      }
    }
    stack_.resize(first);
    stack_.push_back(v);
  }
  for (std::uint32_t g : solids)
    if (g < inside_.size()) inside_[g] = 0;
  return !stack_.empty() && stack_.back() != 0;
}

void CsgEvaluator::evaluate(const RayPartitions& parts, std::vector<CsgInterval>& out) {
  out.clear();
  for (const Partition& p : parts.partitions) {
    if (!contains(parts.solids_of(p))) continue;
    if (!out.empty() && out.back().t_out == p.t_in) {
      out.back().t_out = p.t_out;
      out.back().out_hit = p.out_hit;
      continue;
    }
    out.push_back({p.t_in, p.t_out, p.in_hit, p.out_hit});
  }
}

}  // namespace pierce::analysis
