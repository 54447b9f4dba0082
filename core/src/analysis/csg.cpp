#include "pierce/analysis/csg.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>

#include "pierce/analysis/bvh_query.h"
#include "pierce/analysis/tie_distance.h"
#include "pierce/error.h"

namespace pierce::analysis {

namespace {

// Recursive-descent parser producing postfix code with leaf names; names are bound afterwards so
// that every unknown name can be listed at once.
class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}
  bool quoted(std::size_t leaf) const { return quoted_[leaf]; }

  void parse(CsgExpr& out) {
    out_ = &out;
    skip_blanks();
    if (pos_ == text_.size()) fail("the expression is empty");
    expression(0);
    skip_blanks();
    if (pos_ != text_.size()) fail("unexpected " + found() + " after the end of the expression");
  }

 private:
  static constexpr int kMaxDepth = 200;  // nesting deeper than this is certainly a mistake

  [[noreturn]] void fail(const std::string& what) const { fail_at(pos_, what); }
  [[noreturn]] void fail_at(std::size_t pos, const std::string& what) const {
    std::string msg = "csg expression, column " + std::to_string(pos + 1) + ": " + what + "\n  ";
    for (char c : text_) msg += (c == '\n' || c == '\t' || c == '\r') ? ' ' : c;
    msg += "\n  " + std::string(pos, ' ') + "^";
    throw InputError(msg);
  }

  std::string found() const {
    if (pos_ >= text_.size()) return "end of expression";
    std::string s(3, '\'');
    s[1] = text_[pos_];
    return s;
  }

  static bool is_blank(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
  static bool is_name_char(char c) { return !is_blank(c) && c != '(' && c != ')' && c != ',' && c != '"'; }

  void skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
  }

  void expression(int depth) {
    if (depth > kMaxDepth) fail("nested more than " + std::to_string(kMaxDepth) + " levels deep");
    skip_blanks();
    if (pos_ >= text_.size()) fail("expected a solid name or an operation, found end of expression");
    const std::size_t start = pos_;
    if (text_[pos_] == '"') {
      leaf(quoted_name(), start);
      return;
    }
    if (!is_name_char(text_[pos_])) fail("expected a solid name or an operation, found " + found());
    while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
    const std::string word(text_.substr(start, pos_ - start));
    const std::size_t after_word = pos_;
    skip_blanks();
    if (pos_ >= text_.size() || text_[pos_] != '(') {
      pos_ = after_word;
      leaf(word, start);
      return;
    }
    CsgOp op;
    if (word == "union") op = CsgOp::union_of;
    else if (word == "intersection") op = CsgOp::intersection_of;
    else if (word == "difference") op = CsgOp::difference_of;
    else fail_at(start, "unknown operation '" + word + "' (expected union, intersection or difference)");
    ++pos_;  // '('
    std::uint32_t operands = 0;
    for (;;) {
      expression(depth + 1);
      ++operands;
      skip_blanks();
      if (pos_ < text_.size() && text_[pos_] == ',') {
        ++pos_;
        continue;
      }
      if (pos_ < text_.size() && text_[pos_] == ')') break;
      fail("expected ',' or ')' in " + word + "(...), found " + found());
    }
    if (operands < 2) fail_at(start, word + "(...) needs at least two operands, got one");
    ++pos_;  // ')'
    out_->program.push_back({op, operands});
  }

  std::string quoted_name() {
    const std::size_t start = pos_;
    ++pos_;
    std::string name;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) ++pos_;
      name += text_[pos_++];
    }
    if (pos_ >= text_.size()) fail_at(start, "quoted name is not closed (missing '\"')");
    ++pos_;
    if (name.empty()) fail_at(start, "empty quoted name");
    return name;
  }

  void leaf(std::string name, std::size_t pos) {
    out_->program.push_back({CsgOp::leaf, std::uint32_t(out_->leaf_names.size())});
    out_->leaf_names.push_back(std::move(name));
    quoted_.push_back(text_[pos] == '"');
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  CsgExpr* out_ = nullptr;
  std::vector<bool> quoted_;  // per leaf: written in quotes (so "#3" is a name, not an id)
};

// "#12" -> 12; anything else -> npos.
std::size_t geometry_id_reference(const std::string& name) {
  if (name.size() < 2 || name[0] != '#' || name.size() > 11) return std::string::npos;
  std::size_t id = 0;
  for (std::size_t i = 1; i < name.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return std::string::npos;
    id = id * 10 + std::size_t(name[i] - '0');
  }
  return id;
}

std::string known_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const Geometry& g : scene.geometries()) names.push_back(g.name.empty() ? "(unnamed)" : g.name);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  constexpr std::size_t kShown = 20;
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > kShown) s += ", ... (" + std::to_string(names.size() - kShown) + " more)";
  if (names.empty()) return "none: the scene is empty";
  return s + "; or #N for geometry id N < " + std::to_string(scene.geometries().size());
}

}  // namespace

std::vector<std::uint32_t> CsgExpr::solids() const {
  std::vector<std::uint32_t> all;
  for (const auto& l : leaves) all.insert(all.end(), l.begin(), l.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

CsgExpr parse_csg(std::string_view text, const Scene& scene) {
  CsgExpr expr;
  expr.text = std::string(text);
  Parser parser(text);
  parser.parse(expr);

  std::multimap<std::string, std::uint32_t> by_name;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) by_name.emplace(scene.geometry(g).name, g);
  std::vector<std::string> unknown;
  for (std::size_t i = 0; i < expr.leaf_names.size(); ++i) {
    const std::string& name = expr.leaf_names[i];
    std::vector<std::uint32_t> ids;
    const std::size_t ref = parser.quoted(i) ? std::string::npos : geometry_id_reference(name);
    if (ref != std::string::npos) {
      if (ref < scene.geometries().size()) ids.push_back(std::uint32_t(ref));
    } else {
      auto [lo, hi] = by_name.equal_range(name);
      for (auto it = lo; it != hi; ++it) ids.push_back(it->second);
    }
    if (ids.empty() && std::find(unknown.begin(), unknown.end(), name) == unknown.end()) unknown.push_back(name);
    std::sort(ids.begin(), ids.end());
    expr.leaves.push_back(std::move(ids));
  }
  if (!unknown.empty()) {
    std::string msg = "csg expression: unknown solid name";
    msg += unknown.size() > 1 ? "s " : " ";
    for (std::size_t i = 0; i < unknown.size(); ++i) msg += (i ? ", '" : "'") + unknown[i] + "'";
    msg += " (known: " + known_names(scene) + ")";
    throw InputError(msg);
  }
  return expr;
}

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

std::string_view point_class_name(PointClass c) {
  switch (c) {
    case PointClass::outside: return "outside";
    case PointClass::inside: return "inside";
    case PointClass::on: return "on";
  }
  return "?";
}

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
  for_each_overlapping(accel_->bvh_double(), box, stack_, [&](const Triangle<double>& t) {
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

double obliquity_deg(Vec3d dir, const Hit& h) {
  if (!h.valid()) return std::numeric_limits<double>::quiet_NaN();
  const Vec3d n(h.ng);
  const double ln = length(n), ld = length(dir);
  if (ln == 0 || ld == 0) return std::numeric_limits<double>::quiet_NaN();
  const double c = std::min(1.0, std::abs(dot(n, dir)) / (ln * ld));
  return std::acos(c) * (180.0 / 3.14159265358979323846);
}

}  // namespace pierce::analysis
