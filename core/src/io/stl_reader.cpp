// STL: binary (80-byte header, uint32 count, 50 bytes per facet, little endian) or ASCII
// (solid/facet/outer loop/vertex/endloop/endfacet/endsolid). Facet normals are ignored: Pierce
// derives facing from the vertex order, as every STL consumer does. Corners with bit-identical
// coordinates are welded into one vertex (first occurrence order), as ParaView's reader does:
// the triangles and their order are the file's, so hits and prim ids do not change, and per-vertex
// results are one per vertex of the surface rather than three per facet. A binary file is welded
// in parallel (first_equal_keys), an ASCII one as it is parsed.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>

#include "io_util.h"
#include "pierce/position_index.h"
#include "readers.h"

namespace pierce::io {

namespace {

constexpr std::size_t kHeaderBytes = 84;
constexpr std::size_t kFacetBytes = 50;

// The lowest corner index with a problem coordinate (coordinate_problem), or `corners` if none.
template <class CornerAt>
std::size_t first_bad_corner(std::size_t corners, const CornerAt& corner) {
  std::atomic<std::size_t> bad{corners};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, corners, 1 << 15), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end() && c < bad.load(std::memory_order_relaxed); ++c) {
      const Vec3d p = corner(c);
      if (!coordinate_problem(p.x) && !coordinate_problem(p.y) && !coordinate_problem(p.z)) continue;
      std::size_t seen = bad.load(std::memory_order_relaxed);
      while (c < seen && !bad.compare_exchange_weak(seen, c, std::memory_order_relaxed)) {
      }
      return;
    }
  });
  return bad.load();
}

// The index of p among `vertices`, appended if it is new.
std::uint32_t add_welded(std::vector<Vec3d>& vertices, PositionIndex& weld, const Vec3d& p) {
  const auto i = std::uint32_t(vertices.size());
  vertices.push_back(p);
  const std::uint32_t found = weld.find_or_insert(vertices, i);
  if (found != i) vertices.pop_back();
  return found;
}

bool starts_with_solid(std::string_view data) {
  const std::string_view s = trim(std::string_view(data).substr(0, 512));
  return s.substr(0, 5) == "solid" && (s.size() == 5 || is_space(s[5]) || s[5] == '\n');
}

// A binary file may start with "solid" too; the size check tells them apart, and an ASCII file
// has no NUL or other control bytes early on.
bool looks_ascii(std::string_view data) {
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

std::vector<LoadedMesh> read_binary(const std::string& path, std::string_view data) {
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
  // Corner c is corner c % 3 of facet c / 3, its floats widened to double exactly.
  const std::size_t corners = 3 * std::size_t(n);
  if (corners >= std::size_t(0xFFFFFFFFu))
    fail(path, "binary STL with " + std::to_string(n) + " triangles: more corners than 32-bit vertex indices hold");
  const char* const facets = data.data() + kHeaderBytes;
  const auto corner_offset = [](std::size_t c) { return (c / 3) * kFacetBytes + 12 + 12 * (c % 3); };
  // Corner c's three coordinates as T (float, or its bits as std::uint32_t).
  const auto corner_as = [&]<typename T>(std::size_t c) {
    const char* p = facets + corner_offset(c);
    return std::array<T, 3>{load_scalar<T>(p, false), load_scalar<T>(p + 4, false), load_scalar<T>(p + 8, false)};
  };
  const auto corner = [&](std::size_t c) {
    const std::array<float, 3> f = corner_as.template operator()<float>(c);
    return Vec3d(f[0], f[1], f[2]);
  };
  if (const std::size_t bad = first_bad_corner(corners, corner); bad < corners) {
    const Vec3d p = corner(bad);
    const int a = coordinate_problem(p.x) ? 0 : (coordinate_problem(p.y) ? 1 : 2);
    fail(path, "triangle " + std::to_string(bad / 3) + ", vertex " + std::to_string(bad % 3) + " (byte offset " +
                   std::to_string(kHeaderBytes + corner_offset(bad) + 4 * std::size_t(a)) +
                   "): " + coordinate_problem(p[std::size_t(a)]));
  }
  // Equal floats widen to equal doubles and only they do (no NaN is left), so the raw bits are the key.
  const std::vector<std::uint32_t> first = first_equal_keys<std::array<std::uint32_t, 3>>(
      corners, [&](std::size_t c) { return corner_as.template operator()<std::uint32_t>(c); });
  // Vertices are numbered in order of first occurrence: count them per chunk, then number and
  // store them chunk by chunk in parallel.
  constexpr std::size_t kChunk = std::size_t(1) << 16;
  const std::size_t chunks = (corners + kChunk - 1) / kChunk;
  std::vector<std::uint32_t> chunk_start(chunks + 1, 0);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t k) {
    std::uint32_t count = 0;
    for (std::size_t c = k * kChunk, end = std::min(corners, c + kChunk); c < end; ++c) count += first[c] == c;
    chunk_start[k + 1] = count;
  });
  for (std::size_t k = 0; k < chunks; ++k) chunk_start[k + 1] += chunk_start[k];
  LoadedMesh m;
  m.name = file_stem(path);
  reserve_huge(m.vertices, chunk_start[chunks]);
  m.vertices.resize(chunk_start[chunks]);
  HugePageVector<std::uint32_t> vertex_of(corners);  // for first occurrences only
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t k) {
    std::uint32_t v = chunk_start[k];
    for (std::size_t c = k * kChunk, end = std::min(corners, c + kChunk); c < end; ++c) {
      if (first[c] != c) continue;
      m.vertices[v] = corner(c);
      vertex_of[c] = v++;
    }
  });
  reserve_huge(m.triangles, n);
  m.triangles.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      for (std::size_t k = 0; k < 3; ++k) m.triangles[i][k] = vertex_of[first[3 * i + k]];
  });
  return only_mesh(std::move(m));
}

std::vector<LoadedMesh> read_ascii(const std::string& path, std::string_view data) {
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

std::vector<LoadedMesh> read_stl(const std::string& path, std::string_view data) {
  return looks_ascii(data) ? read_ascii(path, data) : read_binary(path, data);
}

}  // namespace pierce::io
