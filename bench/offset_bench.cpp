// pierce_bench_offsets: origin offsets (Zoet, "Accelerating ray tracing with origin offsets"),
// Tables 2-4 for Pierce. For every hemisphere set and four scenes (closed organic, a CAD part with
// concave corners, an assembly of touching parts, an axis-aligned block of touching cubes):
//  - thickness rays: from every face centre along the inward normal to where the ray leaves the
//    solid (analysis::ray_exit_distance, `queue`, as `pierce thickness --per face` traces them);
//  - AO-like rays: from random surface points, cosine-weighted about the outward normal, length
//    1/5/10/25/50 % of the scene diagonal, first hit other than the start triangle (`queue`).
// Reports visited inner nodes and leaves per ray (from an untimed pass of the kernel's counting
// variant) relative to no offset, the time ratio with/without offsets (offset queries
// included; single thread, best of --reps), memory per triangle and build time. Every offset run
// is checked against the run without: thickness values and occlusion must be identical.
// A benchmark, not a test: it reports, it never asserts a speed.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bench_main.h"
#include "bench_timing.h"
#include "pierce/analysis/thickness.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"
#include "pierce/origin_offsets.h"

namespace pierce::bench {
namespace {

struct World {
  std::string name;
  Scene scene;
  std::unique_ptr<Accel> accel;
};

// Closed surface of a voxel set (unit faces between filled and empty cells, two triangles each,
// outward winding), scaled by `scale` and moved by `offset`.
gen::Mesh voxel_surface(const std::string& name, int nx, int ny, int nz, const std::function<bool(int, int, int)>& filled,
                        Vec3d scale = {1, 1, 1}, Vec3d offset = {}) {
  gen::Mesh m;
  m.name = name;
  std::map<std::array<int, 3>, std::uint32_t> index;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, fresh] = index.emplace(p, std::uint32_t(m.vertices.size()));
    if (fresh) m.vertices.push_back({p[0] * scale.x + offset.x, p[1] * scale.y + offset.y, p[2] * scale.z + offset.z});
    return it->second;
  };
  auto in = [&](int x, int y, int z) {
    return x >= 0 && y >= 0 && z >= 0 && x < nx && y < ny && z < nz && filled(x, y, z);
  };
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z) {
        if (!in(x, y, z)) continue;
        for (int a = 0; a < 3; ++a)
          for (int s : {-1, 1}) {
            std::array<int, 3> nb{x, y, z};
            nb[a] += s;
            if (in(nb[0], nb[1], nb[2])) continue;
            std::array<int, 3> base{x, y, z};
            if (s > 0) base[a] += 1;
            const int u = (a + 1) % 3, v = (a + 2) % 3;
            std::array<int, 3> p1 = base, p2 = base, p3 = base;
            p1[u] += 1, p2[u] += 1, p2[v] += 1, p3[v] += 1;
            const std::uint32_t i0 = vertex(base), i1 = vertex(p1), i2 = vertex(p2), i3 = vertex(p3);
            if (s > 0) {
              m.triangles.push_back({i0, i1, i2}), m.triangles.push_back({i0, i2, i3});
            } else {
              m.triangles.push_back({i0, i2, i1}), m.triangles.push_back({i0, i3, i2});
            }
          }
      }
  return m;
}

// An L-bracket with bolt holes and a slot, voxelised at k cells per unit, turned 15 degrees about
// x and 10 about z (a CAD part in a general orientation).
gen::Mesh bracket(int k) {
  const int n = 4 * k;
  auto filled = [&](int x, int y, int z) {
    const bool base = z < k, flange = y < k;
    if (!(base || flange)) return false;
    auto hole = [&](double cx, double cy, double r) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      return dx * dx + dy * dy < r * r;
    };
    if (base && !flange && (hole(1.0 * k, 2.8 * k, 0.45 * k) || hole(3.0 * k, 2.8 * k, 0.45 * k))) return false;
    if (flange && !base && x >= 1.6 * k && x < 2.4 * k && z >= 1.5 * k && z < 3.2 * k) return false;  // slot
    return true;
  };
  gen::Mesh m = voxel_surface("bracket", n, n, n, filled, {1.0 / k, 1.0 / k, 1.0 / k});
  const double a = 15 * std::numbers::pi / 180, b = 10 * std::numbers::pi / 180;
  for (Vec3d& p : m.vertices) {
    const Vec3d q{p.x, p.y * std::cos(a) - p.z * std::sin(a), p.y * std::sin(a) + p.z * std::cos(a)};
    p = {q.x * std::cos(b) - q.y * std::sin(b), q.x * std::sin(b) + q.y * std::cos(b), q.z};
  }
  return m;
}

// The layout of samples/plate_assembly.step, finely tessellated: a 10 x 10 x 2 plate with three
// 2-unit blocks standing on it (faces touching the plate's top) and a fourth block sunk into it.
std::vector<gen::Mesh> assembly(int k) {
  auto all = [](int, int, int) { return true; };
  std::vector<gen::Mesh> parts;
  parts.push_back(voxel_surface("plate", 10 * k, 10 * k, 2 * k, all, {1.0 / k, 1.0 / k, 1.0 / k}));
  const Vec3d at[] = {{1, 1, 2}, {6, 1, 2}, {3, 6, 2}, {7, 6, 1.5}};
  for (int i = 0; i < 4; ++i)
    parts.push_back(voxel_surface("block" + std::to_string(i), 2 * k, 2 * k, 2 * k, all, {1.0 / k, 1.0 / k, 1.0 / k}, at[i]));
  return parts;
}

struct SurfaceRay {
  std::uint32_t geom, prim;
  Vec3d origin, dir;
};

Vec3d unit(Vec3d v) { return v * (1.0 / length(v)); }

Vec3d face_normal(const Geometry& g, std::uint32_t p) {
  const Tri& t = g.triangles[p];
  return cross(g.vertices[t[1]] - g.vertices[t[0]], g.vertices[t[2]] - g.vertices[t[0]]);
}

// Thickness rays: every face centre (at most `limit`, evenly strided), inward normal.
std::vector<SurfaceRay> thickness_rays(const Scene& s, std::size_t limit) {
  std::vector<SurfaceRay> all;
  for (std::uint32_t g = 0; g < s.geometries().size(); ++g) {
    const Geometry& geo = s.geometry(g);
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      if (geo.degenerate[p]) continue;
      const Tri& t = geo.triangles[p];
      const Vec3d c = (geo.vertices[t[0]] + geo.vertices[t[1]] + geo.vertices[t[2]]) * (1.0 / 3.0);
      all.push_back({g, p, c, unit(face_normal(geo, p)) * -1.0});
    }
  }
  if (all.size() <= limit) return all;
  std::vector<SurfaceRay> out;
  for (std::size_t i = 0; i < limit; ++i) out.push_back(all[i * all.size() / limit]);
  return out;
}

// AO rays: area-weighted random surface points, cosine-weighted directions about the outward normal.
std::vector<SurfaceRay> ao_rays(const Scene& s, std::size_t count, std::uint64_t seed) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ids;
  std::vector<double> cum;
  double total = 0;
  for (std::uint32_t g = 0; g < s.geometries().size(); ++g)
    for (std::uint32_t p = 0; p < s.geometry(g).triangles.size(); ++p) {
      if (s.geometry(g).degenerate[p]) continue;
      total += 0.5 * length(face_normal(s.geometry(g), p));
      ids.emplace_back(g, p);
      cum.push_back(total);
    }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<SurfaceRay> out;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t k = std::size_t(std::lower_bound(cum.begin(), cum.end(), u01(rng) * total) - cum.begin());
    const auto [g, p] = ids[std::min(k, ids.size() - 1)];
    const Geometry& geo = s.geometry(g);
    const Tri& t = geo.triangles[p];
    double a = u01(rng), b = u01(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec3d v0 = geo.vertices[t[0]];
    const Vec3d o = v0 + (geo.vertices[t[1]] - v0) * a + (geo.vertices[t[2]] - v0) * b;
    const Vec3d n = unit(face_normal(geo, p));
    const Vec3d helper = std::abs(n.x) < 0.6 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    const Vec3d u = unit(cross(n, helper)), w = cross(n, u);
    const double r = std::sqrt(u01(rng)), phi = 2 * std::numbers::pi * u01(rng);
    const Vec3d d = u * (r * std::cos(phi)) + w * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - r * r));
    out.push_back({g, p, o, d});
  }
  return out;
}

struct Run {
  Counters work;
  double seconds = 0;
  std::size_t rays = 0, offset_rays = 0, beyond = 0;  // offset > 0; offset beyond the ray's end
  std::vector<double> answers;                         // thickness, or 1/0 occluded
};

// One pass over the rays, with or without offsets; `count`: with the kernel's counting variant.
Run run_pass(const World& w, const std::vector<SurfaceRay>& rays, const OriginOffsets* oo, double length, double tie,
             bool count) {
  KernelOptions kopts;
  kopts.order.tie = TieOrder::leave_before_enter;
  kopts.count = count;
  HitIterator it(*w.accel, KernelKind::queue, kopts);
  Run run;
  run.rays = rays.size();
  run.answers.reserve(rays.size());
  const Counters before = it.counters();
  const double t0 = thread_seconds();
  for (const SurfaceRay& r : rays) {
    const double off = oo ? safe_offset(*oo, r.geom, r.prim, r.origin, r.dir) : 0.0;
    run.offset_rays += off > 0;
    if (length > 0) {  // AO: first hit other than the start triangle within `length`
      run.beyond += off >= length;
      it.begin(Ray{r.origin, r.dir, off, length});
      Hit h;
      bool occluded = false;
      while (it.next(h)) {
        if (h.geom == r.geom && h.prim == r.prim) continue;
        occluded = true;
        break;
      }
      run.answers.push_back(occluded);
    } else {
      run.answers.push_back(analysis::ray_exit_distance(it, r.geom, r.origin, r.dir,
                                                        std::numeric_limits<double>::infinity(), tie, off));
    }
  }
  run.seconds = thread_seconds() - t0;
  const Counters after = it.counters();
  run.work.traversal_steps = after.traversal_steps - before.traversal_steps;
  run.work.leaf_visits = after.leaf_visits - before.leaf_visits;
  run.work.prim_tests = after.prim_tests - before.prim_tests;
  return run;
}

// Every configuration (no offsets first, then each set): one counting pass for the work and the
// answers, then `reps` timed passes of the plain kernel, interleaved so that all see the same
// machine load; each keeps its best time.
std::vector<Run> best_of(int reps, const World& w, const std::vector<SurfaceRay>& rays,
                         const std::vector<const OriginOffsets*>& configs, double length, double tie) {
  std::vector<Run> runs;
  for (const OriginOffsets* oo : configs) {
    runs.push_back(run_pass(w, rays, oo, length, tie, true));
    runs.back().seconds = std::numeric_limits<double>::infinity();
  }
  for (int i = 0; i < reps; ++i)
    for (std::size_t c = 0; c < configs.size(); ++c)
      runs[c].seconds = std::min(runs[c].seconds, run_pass(w, rays, configs[c], length, tie, false).seconds);
  return runs;
}

std::size_t mismatches(const Run& a, const Run& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.answers.size(); ++i) {
    const double x = a.answers[i], y = b.answers[i];
    n += !(x == y || (std::isnan(x) && std::isnan(y)));
  }
  return n;
}

std::string pct(double with, double without) {
  if (without == 0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.0f%%", 100.0 * (with / without - 1.0));
  return buf;
}

std::string num(double v, const char* fmt = "%.1f") {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

int run(int argc, char** argv) {
  CLI::App app{"Origin offsets (Zoet): traversal work and time with each hemisphere set"};
  std::size_t rays = 20000, thickness_limit = 20000;
  int reps = 3, blob_level = 5, grid_n = 10, k = 8;
  bool quick = false;
  std::string sets_arg = "center,vertex,median,median+center,polygon,random";
  app.add_option("--rays", rays, "AO rays per scene and length")->capture_default_str();
  app.add_option("--thickness-rays", thickness_limit, "Thickness rays per scene (face centres, strided)")->capture_default_str();
  app.add_option("--reps", reps, "Timing repetitions (best is kept)")->capture_default_str();
  app.add_option("--blob", blob_level, "gen::blob subdivision level")->capture_default_str();
  app.add_option("--grid", grid_n, "gen::cube_grid size n (n^3 cubes)")->capture_default_str();
  app.add_option("--voxels", k, "Voxels per unit of the bracket and the assembly")->capture_default_str();
  app.add_option("--sets", sets_arg, "Comma-separated hemisphere sets")->capture_default_str();
  app.add_flag("--quick", quick, "Tiny sizes (smoke run)");
  CLI11_PARSE(app, argc, argv);
  if (quick) rays = 300, thickness_limit = 300, reps = 1, blob_level = 2, grid_n = 3, k = 2;
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);

  std::vector<HemisphereSet> sets;
  for (std::size_t pos = 0; pos <= sets_arg.size();) {
    const std::size_t end = std::min(sets_arg.find(',', pos), sets_arg.size());
    const auto s = parse_hemisphere_set(sets_arg.substr(pos, end - pos));
    if (!s) {
      std::fprintf(stderr, "unknown hemisphere set '%s'\n", sets_arg.substr(pos, end - pos).c_str());
      return 2;
    }
    sets.push_back(*s);
    pos = end + 1;
  }

  std::vector<std::unique_ptr<World>> worlds;
  auto add = [&](std::string name, std::vector<gen::Mesh> meshes) {
    auto w = std::make_unique<World>();
    w->name = std::move(name);
    w->scene = gen::to_scene(meshes);
    w->accel = std::make_unique<Accel>(w->scene);
    worlds.push_back(std::move(w));
  };
  add("blob (organic)", {gen::blob(blob_level)});
  add("bracket (CAD, rotated)", {bracket(k)});
  add("assembly (touching)", assembly(k));
  add("cube grid (axis-aligned)", gen::cube_grid(grid_n));

  const double lengths[] = {0.01, 0.05, 0.10, 0.25, 0.50};
  std::printf("# pierce_bench_offsets\n\nqueue kernel, 1 thread, thread CPU time, best of %d interleaved (node counts from "
              "an untimed pass of the counting variant); AO rays %zu per length, thickness rays up to %zu per scene\n\n",
              reps, rays, thickness_limit);

  std::printf("## Scenes and sets: memory, build time, hemispheres with r > 0\n\n");
  std::printf("| scene | triangles | BVH B/tri | set | B/tri | build s | r > 0 |\n|---|---:|---:|---|---:|---:|---:|\n");
  std::vector<std::vector<OriginOffsets>> built(worlds.size());
  for (std::size_t wi = 0; wi < worlds.size(); ++wi) {
    const World& w = *worlds[wi];
    const double tris = double(w.scene.triangle_count());
    for (HemisphereSet s : sets) {
      const auto t0 = Clock::now();
      built[wi].push_back(build_origin_offsets(w.scene, w.accel->wide(), s));
      const double secs = seconds_since(t0);
      const OriginOffsets& oo = built[wi].back();
      std::size_t positive = 0, all = 0;
      for (std::uint32_t g = 0; g < w.scene.geometries().size(); ++g)
        for (std::uint32_t p = 0; p < w.scene.geometry(g).triangles.size(); ++p)
          for (int side = 0; side < 2; ++side)
            for (const Hemisphere& h : oo.hemispheres(g, p, side)) positive += h.radius > 0, ++all;
      std::printf("| %s | %.0f | %.0f | %s | %.0f | %.2f | %.0f%% |\n", w.name.c_str(), tris,
                  double(w.accel->wide().memory_bytes()) / tris, std::string(hemisphere_set_name(s)).c_str(),
                  double(oo.memory_bytes()) / tris, secs, 100.0 * double(positive) / double(std::max<std::size_t>(all, 1)));
    }
  }

  std::size_t total_mismatch = 0;
  auto table = [&](const char* title, bool ao) {
    std::printf("\n## %s\n\nbaseline: inner nodes / leaves per ray without offsets, time of all rays; per set: change of inner nodes / "
                "leaves, time ratio with/without (offset queries included), rays moved (offset > 0)\n\n",
                title);
    std::printf("| scene |%s baseline |", ao ? " length |" : "");
    for (HemisphereSet s : sets) std::printf(" %s |", std::string(hemisphere_set_name(s)).c_str());
    std::printf("\n|---|%s---:|", ao ? "---:|" : "");
    for (std::size_t i = 0; i < sets.size(); ++i) std::printf("---:|");
    std::printf("\n");
    for (std::size_t wi = 0; wi < worlds.size(); ++wi) {
      const World& w = *worlds[wi];
      const double tie = analysis::tie_distance(w.scene, 1e-6);
      const std::vector<SurfaceRay> rs = ao ? ao_rays(w.scene, rays, 1 + wi) : thickness_rays(w.scene, thickness_limit);
      for (double frac : ao ? std::vector<double>(std::begin(lengths), std::end(lengths)) : std::vector<double>{0.0}) {
        const double len = frac * w.scene.scale();
        std::vector<const OriginOffsets*> configs{nullptr};
        for (const OriginOffsets& oo : built[wi]) configs.push_back(&oo);
        const std::vector<Run> runs = best_of(reps, w, rs, configs, len, tie);
        const Run& base = runs[0];
        const double n = double(std::max<std::size_t>(base.rays, 1));
        const double b_inner = double(base.work.traversal_steps - base.work.leaf_visits) / n;
        const double b_leaf = double(base.work.leaf_visits) / n;
        std::printf("| %s |", w.name.c_str());
        if (ao) std::printf(" %.0f%% |", 100 * frac);
        std::printf(" %s / %s, %.1f ms |", num(b_inner).c_str(), num(b_leaf).c_str(), 1e3 * base.seconds);
        for (std::size_t si = 0; si < sets.size(); ++si) {
          const Run& r = runs[si + 1];
          const std::size_t bad = mismatches(base, r);
          total_mismatch += bad;
          const double inner = double(r.work.traversal_steps - r.work.leaf_visits) / n;
          const double leaf = double(r.work.leaf_visits) / n;
          const std::string past = ao ? ", " + num(100.0 * double(r.beyond) / n, "%.0f") + "% past end" : "";
          std::printf(" %s / %s, x%.2f, %.0f%% moved%s%s |", pct(inner, b_inner).c_str(), pct(leaf, b_leaf).c_str(),
                      r.seconds / std::max(base.seconds, 1e-12), 100.0 * double(r.offset_rays) / n, past.c_str(),
                      bad ? (" MISMATCH " + std::to_string(bad)).c_str() : "");
        }
        std::printf("\n");
        std::fflush(stdout);
      }
    }
  };
  table("Thickness rays (face centres, inward normal, to the exit)", false);
  table("AO-like rays (cosine-weighted, first hit other than the start triangle)", true);
  std::printf("\nresult mismatches with/without offsets: %zu\n", total_mismatch);
  return total_mismatch == 0 ? 0 : 1;
}

}  // namespace
}  // namespace pierce::bench

int main(int argc, char** argv) { return pierce::bench::guarded_main(argc, argv, pierce::bench::run); }
