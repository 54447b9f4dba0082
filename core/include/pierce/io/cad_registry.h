#pragma once
// CAD models loaded in this process, by key, so that a later stage that has only triangles tagged
// with the key can find the B-rep faces behind them. The VTK CAD reader registers each model it
// loads and tags its cells with the key; the thickness filter sees those cells after any number
// of pipeline stages (D3 and surface extraction keep cell arrays, not field data) and looks the
// faces up here (vtk_filter/PierceVTK/PierceVTKBRep.h). In pierce_core, so that every module of
// a process shares one registry.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pierce/io/cad_io.h"

namespace pierce {

// How many models the registry keeps (the most recently registered): older keys are forgotten
// and their faces released.
inline constexpr std::size_t kRegisteredCadModels = 8;

// Registers the faces of every solid of `model`, loaded by load_cad_file(path, opts), under a key
// derived from the file (its absolute path, size and modification time) and the options: the
// same key in every process (MPI rank) that loads the same file with the same options. The key
// is in [1, 2^52], so that it survives a trip through a double.
std::int64_t register_cad_model(const std::string& path, const TessellationOptions& opts, const CadModel& model);

// Per solid of the model registered under `key`, in the model's solid order, its faces
// (CadLink::faces); empty when the key is not (or no longer) registered in this process.
std::vector<std::shared_ptr<const CadFaces>> registered_cad_faces(std::int64_t key);

}  // namespace pierce
