// OFF (Geomview): header `[ST][C][N]OFF`, then `nv nf [ne]`, nv vertex lines (first three numbers
// used; colours, normals and texture coordinates after them ignored), nf face lines `k i1 .. ik`
// (anything after the k indices, e.g. a colour, ignored). '#' starts a comment. Read line by line,
// as every writer emits one element per line. Binary OFF and 4D/nD variants are refused.
#include <cstdint>

#include "io_util.h"
#include "readers.h"

namespace pierce::io {

namespace {

bool valid_header_keyword(std::string_view kw) {
  if (kw.size() < 3 || kw.substr(kw.size() - 3) != "OFF") return false;
  std::string_view prefix = kw.substr(0, kw.size() - 3);
  if (prefix.substr(0, 2) == "ST") prefix.remove_prefix(2);
  if (!prefix.empty() && prefix.front() == 'C') prefix.remove_prefix(1);
  if (!prefix.empty() && prefix.front() == 'N') prefix.remove_prefix(1);
  return prefix.empty();
}

}  // namespace

std::vector<LoadedMesh> read_off(const std::string& path, std::string_view data) {
  LineCursor lines(data);
  std::string_view line;
  // Next line with content, comments removed; false at end of file.
  auto next_content = [&](Tokens& tokens) {
    while (lines.next(line)) {
      line = line.substr(0, line.find('#'));
      if (!trim(line).empty()) {
        tokens = Tokens(line);
        return true;
      }
    }
    return false;
  };

  Tokens tokens({});
  if (!next_content(tokens)) fail(path, "file is empty");
  std::string_view tok;
  tokens.next(tok);
  if (!valid_header_keyword(tok)) {
    if (tok.ends_with("OFF"))
      fail_at_line(path, lines.line(), "unsupported OFF variant " + quoted(tok) + " (only 3D [ST][C][N]OFF)");
    fail_at_line(path, lines.line(), "expected 'OFF' header, found " + quoted(tok));
  }
  if (tokens.rest().starts_with("BINARY")) fail_at_line(path, lines.line(), "binary OFF is not supported");

  // The counts follow the keyword, on the header line or the next one.
  if (tokens.rest().empty() && !next_content(tokens))
    fail_at_line(path, lines.line(), "unexpected end of file, expected vertex and face counts");
  std::int64_t counts[2];
  for (int k = 0; k < 2; ++k) {
    const char* what = k == 0 ? "vertex" : "face";
    if (!tokens.next(tok)) fail_at_line(path, lines.line(), "missing " + std::string(what) + " count");
    if (!parse_int(tok, counts[k]) || counts[k] < 0)
      fail_at_line(path, lines.line(), "bad " + std::string(what) + " count " + quoted(tok));
  }
  const std::int64_t nv = counts[0], nf = counts[1];
  if (nv >= std::int64_t(std::numeric_limits<std::uint32_t>::max()))
    fail_at_line(path, lines.line(), "too many vertices: " + std::to_string(nv));
  // Each element takes at least one byte: larger counts are a corrupt header, not a reason to
  // allocate.
  if (std::uint64_t(nv) > data.size() || std::uint64_t(nf) > data.size())
    fail_at_line(path, lines.line(), "counts (" + std::to_string(nv) + " vertices, " + std::to_string(nf) +
                                         " faces) exceed what the file can hold");

  LoadedMesh m;
  m.name = file_stem(path);
  reserve_huge(m.vertices, std::size_t(nv));
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!next_content(tokens))
      fail_at_line(path, lines.line(), "unexpected end of file: expected " + std::to_string(nv) +
                                           " vertices, found " + std::to_string(i));
    m.vertices.push_back(parse_point(tokens, path, lines.line(), "vertex"));
  }
  std::vector<std::uint32_t> poly;
  reserve_huge(m.triangles, std::size_t(nf));
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!next_content(tokens))
      fail_at_line(path, lines.line(), "unexpected end of file: expected " + std::to_string(nf) + " faces, found " +
                                           std::to_string(f));
    std::int64_t k;
    tokens.next(tok);
    if (!parse_int(tok, k) || k < 0) fail_at_line(path, lines.line(), "bad face vertex count " + quoted(tok));
    if (k < 3) fail_at_line(path, lines.line(), "face with " + std::to_string(k) + " vertices (needs at least 3)");
    poly.clear();
    for (std::int64_t j = 0; j < k; ++j) {
      std::int64_t idx;
      if (!tokens.next(tok))
        fail_at_line(path, lines.line(), "face says " + std::to_string(k) + " vertices but lists " + std::to_string(j));
      if (!parse_int(tok, idx)) fail_at_line(path, lines.line(), "bad vertex index " + quoted(tok));
      if (idx < 0 || idx >= nv)
        fail_at_line(path, lines.line(), "vertex index " + std::to_string(idx) + " out of range (the file has " +
                                             std::to_string(nv) + " vertices, indices start at 0)");
      poly.push_back(std::uint32_t(idx));
    }
    append_fan(poly.data(), poly.size(), m.triangles);
  }
  return only_mesh(std::move(m));
}

}  // namespace pierce::io
