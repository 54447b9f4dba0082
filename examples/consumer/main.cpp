// Loads the bundled sample plates.obj (10 touching plates stacked along z), shoots one ray down
// through the stack with an exact kernel, and checks that it crosses all 20 surfaces in order:
// two at each of the 9 inner planes (one plate left, the next entered), one at the top and bottom.
#include <cstdio>
#include <exception>
#include <vector>

#include <pierce/hit.h>
#include <pierce/io/mesh_io.h>
#include <pierce/kernel.h>
#include <pierce/scene.h>
#include <pierce/version.h>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s plates.obj  (in /usr/share/doc/pierce/samples)\n", argv[0]);
    return 2;
  }
  try {
    pierce::Scene scene;
    pierce::add_model_files(scene, {argv[1]});
    pierce::Accel accel(scene);
    pierce::HitIterator it(accel, pierce::KernelKind::queue);  // an exact kernel

    pierce::Ray ray;
    ray.org = {0.37, 0.61, 2.0};
    ray.dir = {0.0, 0.0, -1.0};
    std::vector<pierce::Hit> hits;
    pierce::collect_hits(it, ray, 0, hits);

    int bad = 0;
    if (scene.geometries().size() != 10) ++bad;
    if (hits.size() != 20) ++bad;
    for (std::size_t i = 0; i < hits.size(); ++i) {
      // Surfaces at z = 1.0, 0.9, ..., 0.0, i.e. t = 1.0 ... 2.0; two hits at each inner plane.
      const double z = 2.0 - hits[i].t;
      const double expected_z = 1.0 - 0.1 * static_cast<double>((i + 1) / 2);
      if (z < expected_z - 1e-6 || z > expected_z + 1e-6) ++bad;
      if (i > 0 && hits[i].t < hits[i - 1].t) ++bad;
    }
    std::printf("Pierce %s: %zu geometries, %zu hits along the ray: %s\n", PIERCE_VERSION_STRING,
                scene.geometries().size(), hits.size(), bad ? "WRONG" : "as expected");
    return bad ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pierce_consumer: %s\n", e.what());
    return 2;
  }
}
