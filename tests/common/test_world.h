#pragma once
// A scene with its acceleration structures, for the tests of every part (kernels, analyses, CSG).
#include <memory>
#include <vector>

#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce::test {

// Accel keeps pointers into the scene and into itself: keep both in place.
struct World {
  Scene scene;
  Accel accel;
  explicit World(Scene s) : scene(std::move(s)), accel(scene) {}
  World(const World&) = delete;
  World& operator=(const World&) = delete;
};

inline std::unique_ptr<World> make_world(const std::vector<gen::Mesh>& meshes) {
  return std::make_unique<World>(gen::to_scene(meshes));
}

}  // namespace pierce::test
