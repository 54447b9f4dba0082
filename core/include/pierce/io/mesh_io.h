#pragma once
// Triangle-mesh files: STL (ASCII and binary), OBJ, OFF, PLY (ASCII, binary little/big endian).
//
// Every face of a file becomes triangles at its position in the file, including degenerate and
// exactly duplicated faces (stacked coplanar duplicates are what Pierce is for), so a hit's `prim`
// is the face's index in file order. Polygons with k > 3 vertices are fan-triangulated in order
// (v0,v1,v2), (v0,v2,v3), ...: they take k-2 consecutive prim indices, and prim then counts the fan
// triangles, not the file's faces.
//
// The readers are written by hand rather than taken from OpenMesh: OpenMesh's halfedge meshes drop
// non-manifold and duplicated faces, and its STL reader may skip degenerate ones, which would shift
// every later prim. For the same reason Pierce does not use OpenMesh at all: the topology it needs
// (welded vertices, edge incidence, vertex normals; analysis/mesh_topology.h) must work on exactly
// the meshes a halfedge structure cannot hold (non-manifold edges, duplicated and degenerate faces,
// triangle soups), so it is computed on indexed triangles, and the build does not look for OpenMesh.
#include <string>
#include <vector>

#include "pierce/scene.h"

namespace pierce {

struct LoadedMesh {
  std::string name;
  std::vector<Vec3d> vertices;
  std::vector<Tri> triangles;  // file order; see above
};

// Reads one model file, chosen by extension (case-insensitive .stl .obj .off .ply). Usually returns
// one mesh, named after the file's stem (or the ASCII STL solid name); several where the file holds
// several parts:
//  - OBJ: each `o`/`g` statement starts a new mesh named after it; meshes without faces are dropped
//    (so `o A` directly followed by `g B` gives one mesh "B"); faces before the first statement form
//    a mesh named after the file. Each mesh keeps the vertices its faces use, in file order; prim is
//    the face's index among its own mesh's faces.
//  - ASCII STL: one mesh per `solid ... endsolid` block.
// STL corners with bit-identical coordinates are welded into one vertex (in order of first
// occurrence), as ParaView's STL reader does; triangles keep the file's order and corners, so
// hits and prim ids are those of the unwelded facets.
// Throws InputError "path:line: what is wrong" (binary data: byte offset or element index) for a
// missing or empty file, unknown extension, truncated data, bad numbers, out-of-range indices, faces
// with fewer than 3 vertices, non-finite or beyond-float-range coordinates, and files without faces.
std::vector<LoadedMesh> load_mesh_file(const std::string& path);

// Loads each file in order and adds its meshes to the scene: geometry ids follow argument order,
// then the order of the meshes inside each file. Geometry source = path.
void add_model_files(Scene& scene, const std::vector<std::string>& paths);

}  // namespace pierce
