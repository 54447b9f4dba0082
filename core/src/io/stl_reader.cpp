// STL: binary (80-byte header, uint32 count, 50 bytes per facet, little endian) or ASCII
// (solid/facet/outer loop/vertex/endloop/endfacet/endsolid). Facet normals are ignored: Pierce
// derives facing from the vertex order, as every STL consumer does. Corners with bit-identical
// coordinates are welded into one vertex (first occurrence order), as ParaView's reader does:
// the triangles and their order are the file's, so hits and prim ids do not change, and per-vertex
// results are one per vertex of the surface rather than three per facet.
#include <algorithm>
#include <cstdint>

#include "io_util.h"
#include "pierce/position_index.h"
#include "readers.h"

namespace pierce::io {

namespace {

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kFacetBytes = 50;

// The index of p among `vertices`, appended if it is new.
std::uint32_t add_welded(std::vector<Vec3d>& vertices, PositionIndex& weld, const Vec3d& p) {
  const auto i = std::uint32_t(vertices.size());
  vertices.push_back(p);
  const std::uint32_t found = weld.find_or_insert(vertices, i);
  if (found != i) vertices.pop_back();
  return found;
}

bool starts_with_solid(const std::string& data) {
  const std::string_view s = trim(std::string_view(data).substr(0, 512));
  return s.substr(0, 5) == "solid" && (s.size() == 5 || is_space(s[5]) || s[5] == '\n');
}

// A binary file may start with "solid" too; the size check tells them apart, and an ASCII file
// has no NUL or other control bytes early on.
bool looks_ascii(const std::string& data) {
  if (!starts_with_solid(data)) return false;
  if (data.size() >= kHeaderBytes) {
    const std::uint32_t n = load_scalar<std::uint32_t>(data.data() + 80, false);
    if (kHeaderBytes + std::uint64_t(n) * kFacetBytes == data.size()) return false;
  }
  const std::size_t probe = std::min<std::size_t>(data.size(), 1024);
  for (std::size_t i = 0; i < probe; ++i) {
    const auto c = static_cast<unsigned char>(data[i]);
    if (c < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') return false;
  }
  return true;
}

std::vector<LoadedMesh> read_binary(const std::string& path, const std::string& data) {
  if (data.size() < kHeaderBytes)
    fail(path, "truncated binary STL: " + std::to_string(data.size()) + " bytes, the header alone needs 84");
  const std::uint32_t n = load_scalar<std::uint32_t>(data.data() + 80, false);
  const std::uint64_t needed = kHeaderBytes + std::uint64_t(n) * kFacetBytes;
  if (data.size() < needed) {
    const std::uint64_t complete = (data.size() - kHeaderBytes) / kFacetBytes;
    fail(path, "truncated binary STL: header says " + std::to_string(n) + " triangles (" + std::to_string(needed) +
                   " bytes) but the file has " + std::to_string(data.size()) + " bytes; triangle " +
                   std::to_string(complete) + " at byte offset " +
                   std::to_string(kHeaderBytes + complete * kFacetBytes) + " is incomplete");
  }
  LoadedMesh m;
  m.name = file_stem(path);
  // A closed triangle mesh has about half as many vertices as triangles.
  m.vertices.reserve(std::size_t(n) / 2 + 3);
  m.triangles.reserve(n);
  PositionIndex weld(std::size_t(n) / 2 + 3);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::size_t base = kHeaderBytes + std::size_t(i) * kFacetBytes;
    Tri tri;
    for (int k = 0; k < 3; ++k) {
      double c[3];
      for (int a = 0; a < 3; ++a) {
        const std::size_t off = base + 12 + 12 * k + 4 * a;
        c[a] = load_scalar<float>(data.data() + off, false);
        if (const char* p = coordinate_problem(c[a]))
          fail(path, "triangle " + std::to_string(i) + ", vertex " + std::to_string(k) + " (byte offset " +
                         std::to_string(off) + "): " + p);
      }
      tri[std::size_t(k)] = add_welded(m.vertices, weld, {c[0], c[1], c[2]});
    }
    m.triangles.push_back(tri);
  }
  return {std::move(m)};
}

std::vector<LoadedMesh> read_ascii(const std::string& path, const std::string& data) {
  TokenStream ts(data);
  std::string_view tok;
  auto expect = [&](std::string_view word) {
    if (!ts.next(tok)) fail_at_line(path, ts.line(), "unexpected end of file, expected '" + std::string(word) + "'");
    if (tok != word) fail_at_line(path, ts.line(), "expected '" + std::string(word) + "', found " + quoted(tok));
  };
  std::vector<LoadedMesh> out;
  while (ts.next(tok)) {
    if (tok != "solid") fail_at_line(path, ts.line(), "expected 'solid', found " + quoted(tok));
    LoadedMesh m;
    m.name = std::string(ts.rest_of_line());
    if (m.name.empty()) m.name = file_stem(path);
    PositionIndex weld(1024);
    std::vector<std::uint32_t> poly;
    for (;;) {
      if (!ts.next(tok)) fail_at_line(path, ts.line(), "unexpected end of file, expected 'facet' or 'endsolid'");
      if (tok == "endsolid") {
        ts.rest_of_line();
        break;
      }
      if (tok != "facet") fail_at_line(path, ts.line(), "expected 'facet' or 'endsolid', found " + quoted(tok));
      expect("normal");
      for (int a = 0; a < 3; ++a) {
        double ignored;
        if (!ts.next(tok)) fail_at_line(path, ts.line(), "unexpected end of file in facet normal");
        if (!parse_double(tok, ignored)) fail_at_line(path, ts.line(), "bad number " + quoted(tok));
      }
      expect("outer");
      expect("loop");
      poly.clear();
      for (;;) {
        if (!ts.next(tok)) fail_at_line(path, ts.line(), "unexpected end of file, expected 'vertex' or 'endloop'");
        if (tok == "endloop") break;
        if (tok != "vertex") fail_at_line(path, ts.line(), "expected 'vertex' or 'endloop', found " + quoted(tok));
        double c[3];
        for (int a = 0; a < 3; ++a) {
          if (!ts.next(tok)) fail_at_line(path, ts.line(), "unexpected end of file in vertex");
          if (!parse_double(tok, c[a])) fail_at_line(path, ts.line(), "bad number " + quoted(tok));
          if (const char* p = coordinate_problem(c[a]))
            fail_at_line(path, ts.line(), std::string(p) + " " + quoted(tok));
        }
        poly.push_back(add_welded(m.vertices, weld, {c[0], c[1], c[2]}));
      }
      if (poly.size() < 3)
        fail_at_line(path, ts.line(), "facet with " + std::to_string(poly.size()) + " vertices (needs at least 3)");
      append_fan(poly.data(), poly.size(), m.triangles);
      expect("endfacet");
    }
    if (!m.triangles.empty()) out.push_back(std::move(m));  // as OBJ: parts without faces are dropped
  }
  return out;
}

}  // namespace

std::vector<LoadedMesh> read_stl(const std::string& path, const std::string& data) {
  return looks_ascii(data) ? read_ascii(path, data) : read_binary(path, data);
}

}  // namespace pierce::io
