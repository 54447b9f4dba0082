// Wavefront OBJ: `v`, `f` (v, v/vt, v//vn, v/vt/vn; negative indices count back from the last
// vertex read), `o`/`g` start a new mesh. Texture, normal, material and smoothing statements are
// ignored; free-form geometry (curves, surfaces) is refused rather than silently dropped.
#include <algorithm>
#include <array>
#include <cstdint>

#include "io_util.h"
#include "readers.h"

namespace pierce::io {

namespace {

struct Group {
  std::string name;
  std::vector<Tri> triangles;       // global (file) vertex indices, 0-based
  std::vector<std::uint32_t> line;  // source line of each triangle, for index errors
};

bool is_free_form(std::string_view kw) {
  static constexpr std::array<std::string_view, 14> kFreeForm = {
      "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con"};
  return std::find(kFreeForm.begin(), kFreeForm.end(), kw) != kFreeForm.end();
}

// Remaps a group's global indices to the vertices it uses, kept in file order. `local` is
// scratch space of one entry per file vertex.
LoadedMesh make_mesh(Group& g, const std::vector<Vec3d>& vertices, std::vector<std::uint32_t>& local) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  LoadedMesh m;
  m.name = std::move(g.name);
  std::fill(local.begin(), local.end(), kUnused);
  for (const Tri& t : g.triangles)
    for (std::uint32_t v : t) local[v] = 0;
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (local[v] != kUnused) {
      local[v] = std::uint32_t(m.vertices.size());
      m.vertices.push_back(vertices[v]);
    }
  m.triangles.reserve(g.triangles.size());
  for (const Tri& t : g.triangles) m.triangles.push_back({local[t[0]], local[t[1]], local[t[2]]});
  return m;
}

}  // namespace

std::vector<LoadedMesh> read_obj(const std::string& path, std::string_view data) {
  std::vector<Vec3d> vertices;
  std::vector<Group> groups(1);
  groups[0].name = file_stem(path);
  std::vector<std::int64_t> poly;
  LineCursor lines(data);
  std::string_view line;
  while (lines.next(line)) {
    line = line.substr(0, line.find('#'));
    Tokens tokens(line);
    std::string_view kw;
    if (!tokens.next(kw)) continue;
    if (kw == "v") {
      vertices.push_back(parse_point(tokens, path, lines.line(), "vertex"));
      if (vertices.size() > std::size_t(std::numeric_limits<std::uint32_t>::max() - 1))
        fail_at_line(path, lines.line(), "too many vertices");
    } else if (kw == "f" || kw == "fo") {
      poly.clear();
      std::string_view tok;
      while (tokens.next(tok)) {
        const std::string_view vtok = tok.substr(0, tok.find('/'));
        std::int64_t idx;
        if (!parse_int(vtok, idx)) fail_at_line(path, lines.line(), "bad vertex index " + quoted(tok));
        if (idx == 0) fail_at_line(path, lines.line(), "vertex index 0 (OBJ indices start at 1)");
        if (idx < 0) {
          const std::int64_t abs_idx = std::int64_t(vertices.size()) + idx;
          if (abs_idx < 0)
            fail_at_line(path, lines.line(),
                         "vertex index " + std::string(vtok) + " out of range: only " +
                             std::to_string(vertices.size()) + " vertices read so far");
          poly.push_back(abs_idx);
        } else {
          // Forward references are checked once all vertices are known.
          if (idx > std::int64_t(std::numeric_limits<std::uint32_t>::max()) - 1)
            fail_at_line(path, lines.line(), "vertex index " + std::string(vtok) + " out of range");
          poly.push_back(idx - 1);
        }
      }
      if (poly.size() < 3)
        fail_at_line(path, lines.line(),
                     "face with " + std::to_string(poly.size()) + " vertices (needs at least 3)");
      Group& g = groups.back();
      append_fan(poly.data(), poly.size(), g.triangles);
      g.line.resize(g.triangles.size(), std::uint32_t(std::min<std::size_t>(lines.line(), UINT32_MAX)));
    } else if (kw == "o" || kw == "g") {
      std::string name(tokens.rest());
      if (groups.back().triangles.empty()) {
        if (!name.empty()) groups.back().name = std::move(name);
      } else {
        groups.push_back({name.empty() ? std::string("default") : std::move(name), {}, {}});
      }
    } else if (is_free_form(kw)) {
      fail_at_line(path, lines.line(), "free-form geometry (" + std::string(kw) + ") is not supported");
    }
    // vt, vn, vp, s, usemtl, mtllib, l, p and other statements do not define surfaces.
  }
  std::vector<std::uint32_t> local(vertices.size());
  std::vector<LoadedMesh> out;
  for (Group& g : groups) {
    if (g.triangles.empty()) continue;
    for (std::size_t i = 0; i < g.triangles.size(); ++i)
      for (std::uint32_t v : g.triangles[i])
        if (v >= vertices.size())
          fail_at_line(path, g.line[i],
                       "vertex index " + std::to_string(std::uint64_t(v) + 1) + " out of range: the file has " +
                           std::to_string(vertices.size()) + " vertices");
    out.push_back(make_mesh(g, vertices, local));
  }
  return out;
}

}  // namespace pierce::io
