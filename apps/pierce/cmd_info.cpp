// `pierce info MODEL...`: per solid, size, closed or open, non-manifold and flipped edges,
// degenerate and duplicated triangles, bounds, area, volume and units.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "command.h"
#include "json_text.h"
#include "model_args.h"
#include "pierce/analysis/mesh_report.h"

namespace pierce::cli {

namespace {

struct InfoOptions {
  ModelArgs model;
  bool json = false;
};

int run_info(const InfoOptions& o) {
  Scene scene;
  const std::vector<LoadedFile> files = load_models(scene, o.model);
  const auto report = analysis::mesh_report(scene);
  auto units_of = [&](std::uint32_t g) {
    for (const LoadedFile& f : files)
      if (g >= f.first_geometry && g < f.first_geometry + f.geometry_count) return f.units;
    return std::string();
  };
  // CAD solids: the check of their tessellation against the B-rep (null for meshes).
  auto check_of = [&](std::uint32_t g) { return tessellation_check(files, g); };
  if (o.json) {
    nlohmann::ordered_json j;
    for (const LoadedFile& f : files) {
      nlohmann::ordered_json jf{{"path", f.path}, {"units", f.units}, {"solids", f.geometry_count}};
      if (f.linear_deflection > 0) jf["linear_deflection"] = f.linear_deflection;
      jf["warnings"] = f.warnings;
      j["files"].push_back(jf);
    }
    j["solids"] = nlohmann::ordered_json::array();
    for (const auto& r : report) {
      j["solids"].push_back({{"id", r.geom},
                             {"name", r.name},
                             {"source", r.source},
                             {"units", units_of(r.geom)},
                             {"triangles", r.triangles},
                             {"vertices", r.vertices},
                             {"welded_vertices", r.welded_vertices},
                             {"closed", r.closed},
                             {"consistently_oriented", r.consistently_oriented},
                             {"boundary_edges", r.boundary_edges},
                             {"non_manifold_edges", r.non_manifold_edges},
                             {"inconsistent_edges", r.inconsistent_edges},
                             {"degenerate_triangles", r.degenerate},
                             {"duplicate_triangles", r.duplicates},
                             {"bounds_min", json_point(r.bounds.lo)},
                             {"bounds_max", json_point(r.bounds.hi)},
                             {"area", r.area},
                             {"volume", r.volume}});
      if (const TessellationCheck* c = check_of(r.geom))
        j["solids"].back()["tessellation"] = {{"brep_faces", c->faces},
                                              {"folded_triangles", c->folded},
                                              {"sliver_triangles", c->slivers},
                                              {"folded_found", c->folded_found},
                                              {"faces_folded", c->faces_folded},
                                              {"faces_remeshed", c->faces_remeshed},
                                              {"remesh_rounds", c->remesh_rounds},
                                              {"deflection", c->final_deflection}};
    }
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  for (const LoadedFile& f : files) {
    std::printf("%s: %u solid(s), units %s", f.path.c_str(), f.geometry_count, f.units.c_str());
    if (f.linear_deflection > 0) std::printf(", tessellated with deflection %g", f.linear_deflection);
    std::printf("\n");
  }
  for (const auto& r : report) {
    std::printf("\nsolid %u: %s\n", r.geom, r.name.empty() ? "(unnamed)" : r.name.c_str());
    std::printf("  triangles %zu, vertices %zu (%zu distinct positions)\n", r.triangles, r.vertices, r.welded_vertices);
    std::printf("  %s%s: %zu boundary edges, %zu non-manifold edges, %zu inconsistently oriented edges\n",
                r.closed ? "closed" : "open", r.closed ? (r.consistently_oriented ? ", oriented" : ", NOT oriented") : "",
                r.boundary_edges, r.non_manifold_edges, r.inconsistent_edges);
    std::printf("  degenerate triangles %zu, duplicated triangles %zu\n", r.degenerate, r.duplicates);
    std::printf("  bounds [%g, %g, %g] .. [%g, %g, %g] %s\n", r.bounds.lo.x, r.bounds.lo.y, r.bounds.lo.z, r.bounds.hi.x,
                r.bounds.hi.y, r.bounds.hi.z, units_of(r.geom).c_str());
    std::printf("  area %g", r.area);
    if (r.closed) std::printf(", volume %g%s", r.volume, r.volume < 0 ? " (inward-facing winding)" : "");
    std::printf("\n");
    if (const TessellationCheck* c = check_of(r.geom)) {
      std::printf("  tessellation against the B-rep (%zu faces): %zu folded triangles, %zu sliver triangles", c->faces,
                  c->folded, c->slivers);
      if (c->folded_found > 0)
        std::printf("; first mesh had %zu folded triangles on %zu faces, %zu faces remeshed (%d rounds, deflection %g)",
                    c->folded_found, c->faces_folded, c->faces_remeshed, c->remesh_rounds, c->final_deflection);
      std::printf("\n");
    }
  }
  return 0;
}

}  // namespace

std::function<int()> register_info(CLI::App& app) {
  const auto [opts, cmd] = add_model_command<InfoOptions>(
      app, "info",
      "Per solid: triangles, closed or open, non-manifold edges, degenerate triangles, bounding box, units");
  cmd->add_flag("--json", opts->json, "Print the report as JSON");
  return [opts] { return run_info(*opts); };
}

}  // namespace pierce::cli
