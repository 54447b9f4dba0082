#pragma once
// One reader per format (not installed). Each gets the path (for messages) and the file's bytes,
// and returns the file's meshes in file order; see pierce/io/mesh_io.h for the rules.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pierce/io/mesh_io.h"

namespace pierce::io {

std::vector<LoadedMesh> read_stl(const std::string& path, std::string_view data);
std::vector<LoadedMesh> read_obj(const std::string& path, std::string_view data);
std::vector<LoadedMesh> read_off(const std::string& path, std::string_view data);
std::vector<LoadedMesh> read_ply(const std::string& path, std::string_view data);

// A file's only mesh, moved (a braced list would copy it: its elements are const).
inline std::vector<LoadedMesh> only_mesh(LoadedMesh&& m) {
  std::vector<LoadedMesh> out;
  out.push_back(std::move(m));
  return out;
}

// Appends the fan triangulation of polygon `poly` (k >= 3 vertex indices) to `tris`.
template <typename Index>
void append_fan(const Index* poly, std::size_t k, std::vector<Tri>& tris) {
  for (std::size_t i = 1; i + 1 < k; ++i)
    tris.push_back({std::uint32_t(poly[0]), std::uint32_t(poly[i]), std::uint32_t(poly[i + 1])});
}

}  // namespace pierce::io
