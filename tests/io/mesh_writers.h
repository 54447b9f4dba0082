#pragma once
// Minimal writers for the mesh-reader tests: a polygon mesh written in each format the readers
// take, so reading it back can be compared with what was written.
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pierce/vec3.h"

namespace pierce::test {

struct PolyMesh {
  std::vector<Vec3d> vertices;
  std::vector<std::vector<std::uint32_t>> faces;  // 0-based, >= 3 vertices each
};

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

template <typename T>
void put(std::string& out, T v, bool big_endian = false) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

inline std::ostringstream precise_stream() {
  std::ostringstream o;
  o.precision(17);
  return o;
}

inline std::string obj_text(const PolyMesh& m) {
  auto o = precise_stream();
  o << "# test mesh\n";
  for (const Vec3d& v : m.vertices) o << "v " << v.x << " " << v.y << " " << v.z << "\n";
  for (const auto& f : m.faces) {
    o << "f";
    for (std::uint32_t i : f) o << " " << i + 1;
    o << "\n";
  }
  return o.str();
}

inline std::string off_text(const PolyMesh& m) {
  auto o = precise_stream();
  o << "OFF\n# test mesh\n" << m.vertices.size() << " " << m.faces.size() << " 0\n";
  for (const Vec3d& v : m.vertices) o << v.x << " " << v.y << " " << v.z << "\n";
  for (const auto& f : m.faces) {
    o << f.size();
    for (std::uint32_t i : f) o << " " << i;
    o << "\n";
  }
  return o.str();
}

enum class PlyFormat { ascii, little, big };

// Vertices carry an extra normal and colour, faces an extra colour, and an `edge` element
// follows, so readers must skip what they do not use. Coordinates as double.
inline std::string ply_data(const PolyMesh& m, PlyFormat fmt) {
  std::string out = "ply\nformat ";
  out += fmt == PlyFormat::ascii ? "ascii" : (fmt == PlyFormat::little ? "binary_little_endian" : "binary_big_endian");
  out += " 1.0\ncomment test mesh\n";
  out += "element vertex " + std::to_string(m.vertices.size()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n";
  out += "element face " + std::to_string(m.faces.size()) + "\n";
  out += "property list uchar int vertex_indices\nproperty uchar red\n";
  out += "element edge 1\nproperty int vertex1\nproperty int vertex2\n";
  out += "end_header\n";
  const bool big = fmt == PlyFormat::big;
  if (fmt == PlyFormat::ascii) {
    auto o = precise_stream();
    for (const Vec3d& v : m.vertices) o << v.x << " " << v.y << " " << v.z << " 0 0 1 255\n";
    for (const auto& f : m.faces) {
      o << f.size();
      for (std::uint32_t i : f) o << " " << i;
      o << " 7\n";
    }
    o << "0 1\n";
    return out + o.str();
  }
  for (const Vec3d& v : m.vertices) {
    put(out, v.x, big), put(out, v.y, big), put(out, v.z, big);
    put(out, 0.f, big), put(out, 0.f, big), put(out, 1.f, big), put(out, std::uint8_t(255), big);
  }
  for (const auto& f : m.faces) {
    put(out, std::uint8_t(f.size()), big);
    for (std::uint32_t i : f) put(out, std::int32_t(i), big);
    put(out, std::uint8_t(7), big);
  }
  put(out, std::int32_t(0), big), put(out, std::int32_t(1), big);
  return out;
}

// STL holds triangles only: faces must have 3 vertices.
inline std::string stl_ascii_text(const PolyMesh& m, const std::string& solid = "test") {
  auto o = precise_stream();
  o << "solid " << solid << "\n";
  for (const auto& f : m.faces) {
    o << "  facet normal 0 0 0\n    outer loop\n";
    for (std::uint32_t i : f) o << "      vertex " << m.vertices[i].x << " " << m.vertices[i].y << " " << m.vertices[i].z << "\n";
    o << "    endloop\n  endfacet\n";
  }
  o << "endsolid " << solid << "\n";
  return o.str();
}

inline std::string stl_binary_data(const PolyMesh& m, const std::string& header = "binary test") {
  std::string out = header;
  out.resize(80, ' ');
  put(out, std::uint32_t(m.faces.size()));
  for (const auto& f : m.faces) {
    for (int k = 0; k < 3; ++k) put(out, 0.f);
    for (std::uint32_t i : f) put(out, float(m.vertices[i].x)), put(out, float(m.vertices[i].y)), put(out, float(m.vertices[i].z));
    put(out, std::uint16_t(0));
  }
  return out;
}

}  // namespace pierce::test
