// libFuzzer target: the model loaders (STL ASCII/binary, OBJ, OFF, PLY) and the ray CSV reader
// on arbitrary bytes. The first byte picks the format; the rest is the file. A loader may only
// return meshes that the Scene accepts or throw InputError; anything else (crash, sanitizer
// report, other exception, hang) is a finding.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "pierce/error.h"
#include "pierce/generators.h"
#include "pierce/io/mesh_io.h"
#include "pierce/io/ray_source.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExt[] = {".stl", ".obj", ".off", ".ply", ".csv"};
  const int format = data[0] % 5;
  // The loaders read files: one scratch file per process.
  static const std::string base = "/tmp/pierce-fuzz-loader-" + std::to_string(::getpid());
  const std::string path = base + kExt[format];
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size > 1 && std::fwrite(data + 1, 1, size - 1, f) != size - 1) std::abort();
    std::fclose(f);
  }
  try {
    if (format == 4) {
      static const pierce::Scene scene = pierce::gen::to_scene({pierce::gen::box({0, 0, 0}, {1, 1, 1})});
      (void)pierce::load_rays(path, scene);
    } else {
      pierce::Scene scene;
      for (pierce::LoadedMesh& m : pierce::load_mesh_file(path))
        scene.add_mesh(std::move(m.vertices), std::move(m.triangles), m.name, path);
    }
  } catch (const pierce::InputError&) {
    // The expected outcome for bad input.
  }
  std::remove(path.c_str());
  return 0;
}
