// CSG expressions: the parser (text to postfix code) and the binding of its names to a scene's
// geometries (csg.h).
#include <algorithm>
#include <cctype>
#include <optional>

#include "pierce/analysis/csg.h"
#include "pierce/error.h"
#include "pierce/solid_reference.h"

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

  // Names bind as everywhere else (solid_reference.h), except that an unquoted #N is always an id.
  std::vector<std::string> unknown;
  for (std::size_t i = 0; i < expr.leaf_names.size(); ++i) {
    const std::string& name = expr.leaf_names[i];
    std::vector<std::uint32_t> ids;
    if (parser.quoted(i)) {
      for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
        if (scene.geometry(g).name == name) ids.push_back(g);
    } else if (name.front() == '#') {
      if (const std::optional<std::uint32_t> id = parse_solid_id(name); id && *id < scene.geometries().size())
        ids.push_back(*id);
      else if (!id)
        ids = find_solids(scene, name);  // "#x": not an id, so a name
    } else {
      ids = find_solids(scene, name);
    }
    if (ids.empty() && std::find(unknown.begin(), unknown.end(), name) == unknown.end()) unknown.push_back(name);
    expr.leaves.push_back(std::move(ids));
  }
  if (!unknown.empty()) {
    std::string msg = "csg expression: unknown solid name";
    msg += unknown.size() > 1 ? "s " : " ";
    for (std::size_t i = 0; i < unknown.size(); ++i) msg += (i ? ", '" : "'") + unknown[i] + "'";
    msg += " (known: " + known_solid_names(scene) + ")";
    throw InputError(msg);
  }
  return expr;
}

}  // namespace pierce::analysis
