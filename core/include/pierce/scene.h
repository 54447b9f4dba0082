#pragma once
// Triangle meshes in double precision, one geometry each. Validated on entry.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pierce/bbox.h"
#include "pierce/vec3.h"

namespace pierce {

using Tri = std::array<std::uint32_t, 3>;

struct Geometry {
  std::string name;                 // solid/part name, may be empty
  std::string source;               // where it came from, for messages (file path)
  std::vector<Vec3d> vertices;
  std::vector<Tri> triangles;       // input order; a hit's prim indexes this
  std::vector<std::uint8_t> degenerate;  // 1 where the triangle (as float) has zero area: never hit
};

class Scene {
 public:
  // Adds a mesh and returns its geometry id (0, 1, ... in call order).
  // Throws InputError naming `source`/`name` and the element on NaN/Inf coordinates,
  // coordinates beyond float range, or out-of-range indices.
  std::uint32_t add_mesh(std::vector<Vec3d> vertices, std::vector<Tri> triangles,
                         std::string name = {}, std::string source = {});

  const std::vector<Geometry>& geometries() const { return geoms_; }
  const Geometry& geometry(std::uint32_t id) const { return geoms_.at(id); }
  std::size_t triangle_count() const;
  std::size_t degenerate_count() const;
  const BBoxd& bounds() const { return bounds_; }
  // Length of the bounds' diagonal; 1 for an empty scene.
  double scale() const;

 private:
  std::vector<Geometry> geoms_;
  BBoxd bounds_;
};

// True when the triangle with these (float-rounded) corners has exactly zero area.
bool is_degenerate(Vec3f a, Vec3f b, Vec3f c);
bool is_degenerate(Vec3d a, Vec3d b, Vec3d c);

}  // namespace pierce
