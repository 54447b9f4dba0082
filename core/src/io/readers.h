#pragma once
// One reader per format (not installed). Each gets the path (for messages) and the file's bytes,
// and returns the file's meshes in file order; see pierce/io/mesh_io.h for the rules.
#include <string>
#include <vector>

#include "pierce/io/mesh_io.h"

namespace pierce::io {

std::vector<LoadedMesh> read_stl(const std::string& path, const std::string& data);
std::vector<LoadedMesh> read_obj(const std::string& path, const std::string& data);
std::vector<LoadedMesh> read_off(const std::string& path, const std::string& data);
std::vector<LoadedMesh> read_ply(const std::string& path, const std::string& data);

// Appends the fan triangulation of polygon `poly` (k >= 3 vertex indices) to `tris`.
template <typename Index>
void append_fan(const Index* poly, std::size_t k, std::vector<Tri>& tris) {
  for (std::size_t i = 1; i + 1 < k; ++i)
    tris.push_back({std::uint32_t(poly[0]), std::uint32_t(poly[i]), std::uint32_t(poly[i + 1])});
}

}  // namespace pierce::io
