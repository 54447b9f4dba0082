#pragma once
// Scene families with rays and what their construction says about each ray's hits.
#include <functional>
#include <string>
#include <vector>

#include "test_util.h"

namespace pierce::test {

// What the construction says about one ray's crossings (independent of any kernel).
struct Expect {
  int count = -1;          // exact number of crossings; -1: not known
  bool closed = false;     // every geometry is closed, consistently wound, and the origin is outside it
  bool alternate = false;  // ... and the ray is generic: per geometry enter, leave, enter, ... in order
};

struct Probe {
  Ray ray;
  Expect expect;
};

struct Case {
  std::vector<gen::Mesh> meshes;
  std::vector<Probe> probes;
};

// Similarity applied to a whole case: scale about the origin, then translate.
struct Xform {
  std::string name;
  double scale = 1.0;
  Vec3d offset{0, 0, 0};
};

enum class Family {
  soup,
  blob,
  plates,
  plates_reversed,
  plates_thickness,
  duplicated_same,
  duplicated_alternate,
  overlapping,
  cube_grid,
  voxel_block,
  deep_plates,
};

std::string family_name(Family f);
Case build_case(Family f, const Xform& x);

}  // namespace pierce::test
