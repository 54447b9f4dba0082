#pragma once
// Shared by the file readers (not installed): whole-file reading, line and token scanning with
// line numbers, strict number parsing, endian-aware binary reads, and error messages in the
// "path:line: what" form.
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include "pierce/error.h"
#include "pierce/huge_page_allocator.h"
#include "pierce/vec3.h"

namespace pierce::io {

// Throws InputError unless `path` names an existing regular file.
void require_regular_file(const std::string& path);

// A file's bytes, in a buffer advised for huge pages and not zero-filled before the read: a model
// of a few hundred megabytes is otherwise paged in twice, once by the fill and once by the read.
using FileBytes = HugePageVector<char>;

// Whole file as bytes. Throws InputError if it cannot be opened or is not a regular file.
FileBytes read_file(const std::string& path);

// File name without directory and extension ("dir/plates.obj" -> "plates").
std::string file_stem(const std::string& path);

[[noreturn]] void fail_at_line(const std::string& path, std::size_t line, const std::string& what);
[[noreturn]] void fail(const std::string& path, const std::string& what);

// Token quoted for a message, shortened if long.
std::string quoted(std::string_view token);

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

inline std::string_view trim(std::string_view s) {
  while (!s.empty() && (is_space(s.front()) || s.front() == '\n')) s.remove_prefix(1);
  while (!s.empty() && (is_space(s.back()) || s.back() == '\n')) s.remove_suffix(1);
  return s;
}

// Splits text into lines ('\n', with a trailing '\r' removed), counting from 1.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(pos_, stop - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_;
    return true;
  }
  std::size_t line() const { return line_; }
  std::size_t offset() const { return pos_; }  // byte offset of the next line

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

// Whitespace-separated tokens of one line.
class Tokens {
 public:
  explicit Tokens(std::string_view s) : rest_(s) {}
  bool next(std::string_view& tok) {
    std::size_t i = 0;
    while (i < rest_.size() && is_space(rest_[i])) ++i;
    if (i == rest_.size()) {
      rest_ = {};
      return false;
    }
    std::size_t j = i;
    while (j < rest_.size() && !is_space(rest_[j])) ++j;
    tok = rest_.substr(i, j - i);
    rest_ = rest_.substr(j);
    return true;
  }
  std::string_view rest() const { return trim(rest_); }

 private:
  std::string_view rest_;
};

// Tokens across lines, remembering the line of the last token. `comment` starts a comment that
// runs to the end of the line (0: none).
class TokenStream {
 public:
  TokenStream(std::string_view text, char comment = 0) : lines_(text), tokens_({}), comment_(comment) {}
  bool next(std::string_view& tok) {
    while (!tokens_.next(tok)) {
      std::string_view line;
      if (!lines_.next(line)) return false;
      if (comment_) line = line.substr(0, line.find(comment_));
      tokens_ = Tokens(line);
    }
    return true;
  }
  // What is left of the current line (and moves on to the next line).
  std::string_view rest_of_line() {
    const std::string_view r = tokens_.rest();
    tokens_ = Tokens({});
    return r;
  }
  std::size_t line() const { return lines_.line(); }
  std::size_t offset() const { return lines_.offset(); }

 private:
  LineCursor lines_;
  Tokens tokens_;
  char comment_;
};

// Strict parses: the whole token must be the number. Accepts a leading '+'; doubles accept nan/inf
// (callers decide whether those are allowed).
inline bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

inline bool parse_int(std::string_view s, std::int64_t& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

// A coordinate the scene accepts: finite and within single-precision range.
// Returns nullptr if fine, otherwise what is wrong.
inline const char* coordinate_problem(double x) {
  if (std::isnan(x)) return "NaN coordinate";
  if (!std::isfinite(x)) return "infinite coordinate";
  if (std::abs(x) > double(std::numeric_limits<float>::max())) return "coordinate beyond single-precision range";
  return nullptr;
}

// Parses three coordinates from `tokens` (text formats); errors name path:line.
inline Vec3d parse_point(Tokens& tokens, const std::string& path, std::size_t line, const char* what) {
  double c[3];
  for (int k = 0; k < 3; ++k) {
    std::string_view tok;
    if (!tokens.next(tok))
      fail_at_line(path, line, std::string(what) + " needs 3 coordinates, found " + std::to_string(k));
    if (!parse_double(tok, c[k])) fail_at_line(path, line, "bad number " + quoted(tok));
    if (const char* p = coordinate_problem(c[k])) fail_at_line(path, line, std::string(p) + " " + quoted(tok));
  }
  return {c[0], c[1], c[2]};
}

// Binary reads of a fixed-size scalar at a byte offset, in the file's byte order.
template <typename T>
T load_scalar(const char* p, bool big_endian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

}  // namespace pierce::io
