#pragma once
// Refinement of a CAD solid's mesh for thickness maps (TessellationOptions::max_edge_length):
// BRepMesh makes few, large triangles on flat faces, so a per-face map there has few samples.
#include <cstddef>

#include "pierce/io/cad_io.h"

namespace pierce {

// Splits the triangles of `s` until no edge is longer than `max_edge`, keeping the mesh
// conforming: an edge is split at its midpoint in every triangle that uses it (Rivara's
// longest-edge bisection: each step splits the longest edge of a triangle). The midpoint is shared
// by both sides, so a closed mesh stays closed, and flat faces stay exactly flat; on a curved
// face it lies on the chord, which the thickness analysis projects onto the face. A mesh edge
// along a curved B-rep edge (between two faces) is never split: its midpoint would lie off the
// B-rep edge, outside one of the faces; such edges are short where the edge curves (angular
// deflection), and the triangles along them are split across their other edges. Each new
// triangle keeps its parent's face and flags; its corners' (u, v) are the parent's, the
// midpoint's the mean of the edge's ends in that triangle. Stops, conforming, once the solid has
// `max_triangles` triangles; returns false then.
bool split_long_edges(CadSolid& s, double max_edge, std::size_t max_triangles);

}  // namespace pierce
