#include "pierce/analysis/mesh_report.h"

#include <algorithm>

#include "pierce/analysis/mesh_topology.h"

namespace pierce::analysis {

std::vector<SolidReport> mesh_report(const Scene& scene) {
  std::vector<SolidReport> out;
  for (std::uint32_t id = 0; id < scene.geometries().size(); ++id) {
    const Geometry& g = scene.geometry(id);
    SolidReport r;
    r.geom = id;
    r.name = g.name;
    r.source = g.source;
    r.vertices = g.vertices.size();
    r.triangles = g.triangles.size();
    for (auto d : g.degenerate) r.degenerate += d;
    const auto weld = weld_by_position(g.vertices);
    for (std::size_t v = 0; v < weld.size(); ++v) r.welded_vertices += weld[v] == v;
    r.duplicates = duplicate_triangles(g, weld);
    const EdgeStats e = edge_stats(g, weld);
    r.edges = e.edges;
    r.boundary_edges = e.boundary;
    r.non_manifold_edges = e.non_manifold;
    r.inconsistent_edges = e.inconsistent;
    r.closed = !g.triangles.empty() && e.boundary == 0 && e.non_manifold == 0;
    r.consistently_oriented = r.closed && e.inconsistent == 0;
    for (const Tri& t : g.triangles)
      for (auto v : t) r.bounds.extend(g.vertices[v]);
    double area = 0, volume = 0;
    for (const Tri& t : g.triangles) {
      const Vec3d a = g.vertices[t[0]], b = g.vertices[t[1]], c = g.vertices[t[2]];
      area += 0.5 * length(cross(b - a, c - a));
      // Relative to the bounds' centre, which keeps the sum well conditioned far from the origin.
      const Vec3d o = r.bounds.center();
      volume += dot(a - o, cross(b - o, c - o)) / 6.0;
    }
    r.area = area;
    r.volume = volume;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace pierce::analysis
