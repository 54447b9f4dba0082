#pragma once
// Model arguments shared by the analysis subcommands: MODEL files of any format (meshes and CAD)
// and the tessellation options for CAD files.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "pierce/io/model_io.h"

namespace pierce::cli {

struct ModelArgs {
  std::vector<std::string> models;
  TessellationOptions tessellation;
};

// Adds the positional MODEL argument(s) and --deflection / --angular-deflection.
void add_model_args(CLI::App* cmd, ModelArgs& args, bool several);

// Loads every model into the scene; CAD warnings (skipped entities, repairs) go to stderr.
std::vector<LoadedFile> load_models(Scene& scene, const ModelArgs& args);

// The check of CAD solid `geom`'s tessellation against its B-rep (cad_io.h), or null for a mesh.
const TessellationCheck* tessellation_check(const std::vector<LoadedFile>& files, std::uint32_t geom);

// "name" or "#id" when unnamed, for messages and tables.
std::string solid_label(const Scene& scene, std::uint32_t id);

}  // namespace pierce::cli
