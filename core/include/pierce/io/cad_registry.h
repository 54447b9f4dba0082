#pragma once
// CAD models loaded in this process, by key, so that a later stage that has only triangles tagged
// with the key can find the B-rep faces behind them, and check that its triangles are still the
// ones loaded (not moved, cut or remeshed since: a hash per triangle). The VTK CAD reader registers each model it
// loads and tags its cells with the key; the thickness filter sees those cells after any number
// of pipeline stages (D3 and surface extraction keep cell arrays, not field data) and looks the
// faces up here (vtk_filter/PierceVTK/PierceVTKBRep.h). In pierce_core, so that every module of
// a process shares one registry.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pierce/io/cad_io.h"

namespace pierce {

// How many models the registry keeps (the most recently registered): older keys are forgotten
// and their faces released.
inline constexpr std::size_t kRegisteredCadModels = 8;

// A triangle as loaded: its corners (in order), its face and the (u, v) of its corners there.
// Two triangles hash alike only when all of these are bit for bit the same (up to collisions of
// a 64-bit hash).
std::uint64_t cad_triangle_hash(const std::array<Vec3d, 3>& corners, std::uint32_t face,
                                const std::array<double, 6>& uv);

struct RegisteredCadModel {
  struct Solid {
    std::shared_ptr<const CadFaces> faces;     // CadLink::faces
    std::vector<std::uint64_t> triangle_hash;  // per triangle of the solid, cad_triangle_hash
  };
  std::vector<Solid> solids;  // in the model's solid order
};

// Registers the faces and triangle hashes of every solid of `model`, loaded by
// load_cad_file(path, opts), under a key
// derived from the file (its absolute path, size and modification time) and the options: the
// same key in every process (MPI rank) that loads the same file with the same options. The key
// is in [1, 2^52], so that it survives a trip through a double.
std::int64_t register_cad_model(const std::string& path, const TessellationOptions& opts, const CadModel& model);

// The model registered under `key`; null when the key is not (or no longer) registered here.
std::shared_ptr<const RegisteredCadModel> registered_cad_model(std::int64_t key);

}  // namespace pierce
