// Pierce vs VTK's locators: all hits along the same segments with vtkOBBTree,
// vtkStaticCellLocator and vtkCellLocator (IntersectWithLine, multi-hit overloads, as a ParaView
// user would call them) and with Pierce's and Embree's kernels through pierce. The expected
// hits are those of Pierce's filter kernel (checked against the exact oracle in tests/oracle).
// vtkModifiedBSPTree is left out: its IntersectWithLine is broken in this VTK (wrong results,
// segfaults; see the notes on Embree and VTK).
//
// Per ray, returned hits are matched to the expected ones first by cell id, then by parameter t
// (a hit on the neighbour triangle of an expected edge hit, at the same point, counts as
// found). Counted per scene: missed (expected crossings nobody returned), duplicated (the same
// cell returned twice on a ray), doubled (one more cell at an expected crossing's point: the
// second triangle of an edge, the other triangles around a vertex) and spurious (a returned
// crossing where none is expected). Single thread for every method; VTK is single-threaded.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <vtkCellArray.h>
#include <vtkCellLocator.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkOBBTree.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>

#include "bench_scenes.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace {

using namespace pierce;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

// A segment p1 -> p2; Pierce traces it as org p1, dir p2 - p1, t in [0, 1].
struct Segment {
  Vec3d p1, p2;
};

struct Crossing {
  double t;
  std::int64_t cell;  // global triangle index (geometry offset + prim)
};
using Crossings = std::vector<Crossing>;

struct Tally {
  std::size_t rays = 0, expected = 0, returned = 0, missed = 0, duplicated = 0, doubled = 0, spurious = 0,
              rays_wrong = 0;
  double ms = 0, build_ms = 0;
};

// Matches `got` against `want` on one ray (see the file comment) and adds to the tally.
void compare(const Crossings& want, Crossings got, double t_tol, Tally& tally) {
  tally.expected += want.size();
  tally.returned += got.size();
  std::size_t dup = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (got[j].cell == got[i].cell && got[j].cell >= 0) {
        got[i].cell = -2;  // drop it from the matching
        ++dup;
        break;
      }
  std::vector<char> want_used(want.size(), 0), got_used(got.size(), 0);
  for (std::size_t i = 0; i < want.size(); ++i)
    for (std::size_t j = 0; j < got.size(); ++j)
      if (!got_used[j] && got[j].cell == want[i].cell) {
        want_used[i] = got_used[j] = 1;
        break;
      }
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (want_used[i]) continue;
    for (std::size_t j = 0; j < got.size(); ++j)
      if (!got_used[j] && got[j].cell != -2 && std::abs(got[j].t - want[i].t) <= t_tol) {
        want_used[i] = got_used[j] = 1;
        break;
      }
  }
  std::size_t missed = 0, doubled = 0, spurious = 0;
  for (char u : want_used) missed += !u;
  for (std::size_t j = 0; j < got.size(); ++j) {
    if (got_used[j] || got[j].cell == -2) continue;
    const bool at_expected = std::any_of(want.begin(), want.end(), [&](const Crossing& w) {
      return std::abs(w.t - got[j].t) <= t_tol;
    });
    (at_expected ? doubled : spurious) += 1;
  }
  tally.rays += 1;
  tally.missed += missed;
  tally.duplicated += dup;
  tally.doubled += doubled;
  tally.spurious += spurious;
  tally.rays_wrong += (missed + dup + doubled + spurious) > 0;
}

struct Case {
  std::string name, description;
  Scene scene;
  std::vector<Segment> segments;
};

std::vector<Segment> segments_of(const std::vector<Ray>& rays, const BBoxd& box) {
  const double reach = 2 * length(box.extent());
  std::vector<Segment> s;
  for (const Ray& r : rays) {
    const double len = length(r.dir);
    const double to_centre = length(r.org - box.center());
    s.push_back({r.org, r.org + r.dir * ((to_centre + reach) / len)});
  }
  return s;
}

// n^3 touching unit cubes (gen::cube_grid), alternating face diagonals. Half the rays pass
// through integer lattice points with small integer directions, so they run exactly through cube
// vertices and edges; a quarter run along z in the planes x = integer (through edges, inside side
// faces); a quarter along z through the diagonals of the horizontal faces.
Case cube_grid_case(int n, std::size_t count, std::uint64_t seed) {
  Case c;
  c.name = "cube grid";
  c.scene = gen::to_scene(gen::cube_grid(n));
  c.description = std::to_string(n) + "^3 touching unit cubes, rays through lattice vertices and edges";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> lattice(0, n), cell(0, n - 1), step(-1, 1);
  std::uniform_real_distribution<double> U(0.05, n - 0.05), frac(0.05, 0.95);
  const double far = 3.0 * n + 3;
  for (std::size_t i = 0; i < count; ++i) {
    Vec3d dir{0, 0, 1}, through;
    if (i % 2 == 0) {
      dir = {double(step(rng)), double(step(rng)), 1.0};
      through = {double(lattice(rng)), double(lattice(rng)), double(lattice(rng))};
    } else if (i % 4 == 1) {
      through = {double(lattice(rng)), U(rng), 0.0};
    } else {
      const double f = frac(rng);
      through = {cell(rng) + f, cell(rng) + f, 0.0};
    }
    const Vec3d p1 = through - dir * double(n + 1);
    c.segments.push_back({p1, p1 + dir * far});
  }
  return c;
}

Case from_bench(bench::BenchScene b) {
  Case c;
  c.name = b.name;
  c.description = b.description;
  c.segments = segments_of(b.rays, b.scene.bounds());
  c.scene = std::move(b.scene);
  return c;
}

vtkSmartPointer<vtkPolyData> to_polydata(const Scene& scene, std::vector<std::int64_t>& offset) {
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> cells;
  std::int64_t base = 0, tri_base = 0;
  for (const Geometry& g : scene.geometries()) {
    offset.push_back(tri_base);
    for (const Vec3d& v : g.vertices) pts->InsertNextPoint(v.x, v.y, v.z);
    for (const Tri& t : g.triangles) {
      const vtkIdType ids[3] = {base + t[0], base + t[1], base + t[2]};
      cells->InsertNextCell(3, ids);
    }
    base += std::int64_t(g.vertices.size());
    tri_base += std::int64_t(g.triangles.size());
  }
  pd->SetPoints(pts);
  pd->SetPolys(cells);
  return pd;
}

double param_of(const double x[3], const Segment& s) {
  const Vec3d d = s.p2 - s.p1;
  return dot(Vec3d{x[0], x[1], x[2]} - s.p1, d) / dot(d, d);
}

struct Row {
  std::string scene, method;
  Tally tally;
  bool is_reference = false;
};

void print_rows(const std::vector<Row>& rows) {
  std::printf("| scene | method | rays | hits expected | hits returned | missed | duplicated | doubled | spurious | "
              "rays wrong | time (ms) | us/ray | x Pierce filter | build (ms) |\n");
  std::printf("|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  double ref_ms = 0;
  for (const Row& r : rows) {
    if (r.is_reference) ref_ms = r.tally.ms;
    const Tally& t = r.tally;
    std::printf("| %s | %s | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %zu | %.1f | %.2f | %.2f | %.2f |\n",
                r.scene.c_str(), r.method.c_str(), t.rays, t.expected, t.returned, t.missed, t.duplicated, t.doubled,
                t.spurious, t.rays_wrong, t.ms,
                t.rays ? 1000.0 * t.ms / double(t.rays) : 0.0, ref_ms > 0 ? t.ms / ref_ms : 0.0, t.build_ms);
  }
}

std::vector<double> parse_list(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) v.push_back(std::stod(item));
  return v;
}

std::string tol_text(double tol) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", tol);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Pierce vs VTK locators: all hits along the same segments, misses, duplicates, time"};
  std::size_t ray_count = 2000;
  std::uint64_t seed = 42;
  int plate_layers = 16, grid_n = 4, blob_subdivisions = 4;
  std::string tolerances = "0,1e-6";
  std::size_t warmup = 100;
  app.add_option("--rays", ray_count, "Rays per scene")->capture_default_str();
  app.add_option("--seed", seed)->capture_default_str();
  app.add_option("--warmup", warmup, "Untimed rays traced first by every method")->capture_default_str();
  app.add_option("--plates", plate_layers, "Touching plates in the stack")->capture_default_str();
  app.add_option("--grid", grid_n, "Cubes per side of the cube grid")->capture_default_str();
  app.add_option("--blob", blob_subdivisions, "Blob subdivisions (20 * 4^s triangles)")->capture_default_str();
  app.add_option("--tol", tolerances,
                 "Tolerances passed to vtkStaticCellLocator / vtkCellLocator IntersectWithLine (comma list); "
                 "vtkOBBTree keeps its default")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const std::vector<double> tols = parse_list(tolerances);

  std::vector<Case> cases;
  cases.push_back(from_bench(bench::plates_scene(plate_layers, ray_count, seed)));
  cases.push_back(cube_grid_case(grid_n, ray_count, seed + 1));
  cases.push_back(from_bench(bench::blob_scene(blob_subdivisions, ray_count, seed + 2)));

  const KernelKind pierce_kernels[] = {KernelKind::filter,         KernelKind::queue,           KernelKind::embree_filter,
                                       KernelKind::embree_restart, KernelKind::embree_nodecull, KernelKind::epsilon};
  std::vector<Row> rows;
  for (const Case& c : cases) {
    std::printf("%s: %s; %zu triangles, %zu segments\n", c.name.c_str(), c.description.c_str(),
                c.scene.triangle_count(), c.segments.size());
    std::fflush(stdout);
    std::vector<std::int64_t> offset;
    const vtkSmartPointer<vtkPolyData> pd = to_polydata(c.scene, offset);
    const double t_tol = 1e-6;  // segment parameter: a hit on a neighbour triangle at the same point

    auto t0 = Clock::now();
    const Accel accel(c.scene);
    const double accel_ms = ms_since(t0);

    // Pierce's filter kernel first: the expected crossings of every segment.
    std::vector<Crossings> expected(c.segments.size());
    for (KernelKind kind : pierce_kernels) {
      Row row{c.name, "pierce " + std::string(kernel_name(kind)), {}, kind == KernelKind::filter};
      HitIterator it(accel, kind);
      std::vector<Crossings> got(c.segments.size());
      auto trace = [&](std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
          got[i].clear();
          Ray ray{c.segments[i].p1, c.segments[i].p2 - c.segments[i].p1, 0.0, 1.0};
          it.begin(ray);
          for (Hit h; it.next(h);) got[i].push_back({h.t, offset[h.geom] + std::int64_t(h.prim)});
        }
      };
      trace(std::min(warmup, c.segments.size()));  // untimed: caches, lazily grown buffers
      t0 = Clock::now();
      trace(c.segments.size());
      row.tally.ms = ms_since(t0);
      row.tally.build_ms = accel_ms;
      if (kind == KernelKind::filter) expected = got;
      for (std::size_t i = 0; i < c.segments.size(); ++i) compare(expected[i], std::move(got[i]), t_tol, row.tally);
      rows.push_back(std::move(row));
    }

    auto run_vtk = [&](const std::string& method, vtkAbstractCellLocator* loc, double tol, bool obb) {
      Row row{c.name, method, {}, false};
      loc->SetDataSet(pd);
      t0 = Clock::now();
      loc->BuildLocator();
      row.tally.build_ms = ms_since(t0);
      vtkNew<vtkPoints> points;
      vtkNew<vtkIdList> ids;
      vtkNew<vtkGenericCell> cell;
      std::vector<Crossings> got(c.segments.size());
      auto trace = [&](std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
          got[i].clear();
          const double p1[3] = {c.segments[i].p1.x, c.segments[i].p1.y, c.segments[i].p1.z};
          const double p2[3] = {c.segments[i].p2.x, c.segments[i].p2.y, c.segments[i].p2.z};
          points->Reset();
          ids->Reset();
          if (obb)
            loc->IntersectWithLine(p1, p2, points, ids);
          else
            loc->IntersectWithLine(p1, p2, tol, points, ids, cell);
          for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
            double x[3];
            points->GetPoint(k, x);
            got[i].push_back({param_of(x, c.segments[i]), std::int64_t(ids->GetId(k))});
          }
        }
      };
      trace(std::min(warmup, c.segments.size()));
      t0 = Clock::now();
      trace(c.segments.size());
      row.tally.ms = ms_since(t0);
      for (std::size_t i = 0; i < c.segments.size(); ++i) compare(expected[i], std::move(got[i]), t_tol, row.tally);
      rows.push_back(std::move(row));
      std::fflush(stdout);
    };
    {
      vtkNew<vtkOBBTree> obb;
      run_vtk("vtkOBBTree (default tol " + tol_text(obb->GetTolerance()) + ")", obb, 0, true);
    }
    for (double tol : tols) {
      vtkNew<vtkStaticCellLocator> loc;
      run_vtk("vtkStaticCellLocator tol " + tol_text(tol), loc, tol, false);
    }
    for (double tol : tols) {
      vtkNew<vtkCellLocator> loc;
      run_vtk("vtkCellLocator tol " + tol_text(tol), loc, tol, false);
    }
  }
  std::printf("\n");
  print_rows(rows);
  return 0;
}
