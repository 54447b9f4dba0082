// libFuzzer target: random triangle soups and rays through every exact kernel.
// Aborts when
//  - two float kernels (or two double kernels) return different hit lists, for any max-hits
//    hint (a hinted list must be a prefix of the full one);
//  - a kernel's list differs from the exact oracle's answer for the kernel's own rounded
//    sheared coordinates (docs/EXACTNESS.md), within the supported coordinate range;
//  - a hit has a non-finite t, t outside [tmin, tmax], or a (geom, prim) appears twice.
// Bad scenes (NaN/Inf/out-of-range coordinates, bad indices) must throw InputError, nothing else.
// The input bytes pick the coordinate style: coarse grids (coplanar faces, rays through shared
// edges and vertices everywhere), multi-scale dyadic values, raw floats, or raw doubles.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "oracle.h"
#include "pierce/error.h"
#include "pierce/kernel.h"

namespace {

using namespace pierce;

const Scene* g_scene = nullptr;  // for the failure report

[[noreturn]] void fail(const std::string& what, const Ray& r) {
  std::fprintf(stderr, "fuzz_kernels: %s\n  ray org (%a, %a, %a) dir (%a, %a, %a) t [%a, %a]\n", what.c_str(), r.org.x,
               r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax);
  if (g_scene)
    for (std::uint32_t g = 0; g < g_scene->geometries().size(); ++g) {
      const Geometry& geo = g_scene->geometry(g);
      for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
        std::fprintf(stderr, "  geom %u prim %u%s:", g, p, geo.degenerate[p] ? " (degenerate)" : "");
        for (auto i : geo.triangles[p]) {
          const Vec3d& v = geo.vertices[i];
          std::fprintf(stderr, " (%a, %a, %a)", v.x, v.y, v.z);
        }
        std::fprintf(stderr, "\n");
      }
    }
  std::abort();
}

std::string list(const std::vector<Hit>& h) {
  std::string s;
  char b[96];
  for (const Hit& x : h) {
    std::snprintf(b, sizeof b, " (%u,%u,%a,%d)", x.geom, x.prim, x.t, int(x.enter));
    s += b;
  }
  return s;
}

bool same_list(const std::vector<Hit>& a, const std::vector<Hit>& b, std::size_t n) {
  const std::size_t m = n == 0 ? a.size() : std::min(n, a.size());
  if (b.size() != m) return false;
  for (std::size_t i = 0; i < m; ++i)
    if (!same_hit(a[i], b[i]) || a[i].enter != b[i].enter) return false;
  return true;
}

struct Input {
  FuzzedDataProvider& fdp;
  int style = 0;
  double coord() {
    switch (style) {
      case 0: return 0.25 * fdp.ConsumeIntegralInRange<int>(-8, 8);
      case 1: return std::ldexp(double(fdp.ConsumeIntegralInRange<int>(-64, 64)), fdp.ConsumeIntegralInRange<int>(-30, 30));
      case 2: return double(fdp.ConsumeFloatingPoint<float>());
      default: return fdp.ConsumeFloatingPoint<double>();
    }
  }
  double direction_component() {
    if (style <= 1) return 0.25 * fdp.ConsumeIntegralInRange<int>(-4, 4);
    return coord();
  }
  double t_bound(double fallback) {
    switch (fdp.ConsumeIntegralInRange<int>(0, 5)) {
      case 0: return std::numeric_limits<double>::infinity();
      case 1: return -std::numeric_limits<double>::infinity();
      case 2: return std::numeric_limits<double>::quiet_NaN();
      case 3: return 0.25 * fdp.ConsumeIntegralInRange<int>(-8, 64);
      case 4: return coord();
      default: return fallback;
    }
  }
};

// Magnitudes where the kernels' arithmetic cannot overflow or underflow (docs/EXACTNESS.md,
// "Range"): the exact comparisons with the oracle are made there.
bool in_supported_range(const Scene& s, const Ray& r) {
  auto ok = [](double x) { return x == 0.0 || (std::abs(x) <= 0x1p40 && std::abs(x) >= 0x1p-40); };
  for (const Geometry& g : s.geometries())
    for (const Vec3d& v : g.vertices)
      if (!ok(v.x) || !ok(v.y) || !ok(v.z)) return false;
  for (int k = 0; k < 3; ++k)
    if (!ok(r.org[k]) || !ok(r.dir[k])) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider fdp(data, size);
  Input in{fdp, fdp.ConsumeIntegralInRange<int>(0, 3)};

  // Scene: one to three geometries of up to 12 vertices and 16 triangles each.
  Scene scene;
  const int geoms = fdp.ConsumeIntegralInRange<int>(1, 3);
  std::vector<Vec3d> all_vertices;
  for (int g = 0; g < geoms; ++g) {
    const int nv = fdp.ConsumeIntegralInRange<int>(3, 12);
    std::vector<Vec3d> v;
    for (int i = 0; i < nv; ++i) {
      Vec3d p{in.coord(), in.coord(), in.coord()};
      if (!all_vertices.empty() && fdp.ConsumeBool()) p = all_vertices[fdp.ConsumeIntegralInRange<std::size_t>(0, all_vertices.size() - 1)];
      v.push_back(p);
    }
    const int nt = fdp.ConsumeIntegralInRange<int>(1, 16);
    std::vector<Tri> t;
    for (int i = 0; i < nt; ++i) {
      Tri tri;
      for (auto& x : tri) x = fdp.ConsumeIntegralInRange<std::uint32_t>(0, std::uint32_t(nv));  // nv: out of range
      t.push_back(tri);
    }
    try {
      scene.add_mesh(v, t, "g" + std::to_string(g), "fuzz");
      all_vertices.insert(all_vertices.end(), v.begin(), v.end());
    } catch (const InputError&) {
      // Rejected input: fine, as long as it is this exception.
    }
  }

  const Accel accel(scene);
  g_scene = &scene;
  std::vector<KernelKind> floats, doubles;
  for (KernelKind k : kAllKernels)
    if (is_exact(k) && unsupported_reason(accel, k).empty()) floats.push_back(k);
  for (KernelKind k : kDoubleKernels) doubles.push_back(k);
  std::unique_ptr<oracle::Oracle<float>> of;
  std::unique_ptr<oracle::Oracle<double>> od;

  const int rays = fdp.ConsumeIntegralInRange<int>(1, 6);
  for (int ri = 0; ri < rays && fdp.remaining_bytes() > 0; ++ri) {
    Ray r;
    if (!all_vertices.empty() && fdp.ConsumeBool()) {
      // Through a vertex or an edge midpoint.
      const Vec3d a = all_vertices[fdp.ConsumeIntegralInRange<std::size_t>(0, all_vertices.size() - 1)];
      const Vec3d b = all_vertices[fdp.ConsumeIntegralInRange<std::size_t>(0, all_vertices.size() - 1)];
      const Vec3d target = fdp.ConsumeBool() ? a : (a + b) * 0.5;
      r.dir = {in.direction_component(), in.direction_component(), 1.0};
      if (fdp.ConsumeBool()) std::swap(r.dir.x, r.dir.z);
      if (fdp.ConsumeBool()) r.dir = r.dir * -1.0;
      r.org = target - r.dir * 8.0;
    } else {
      r.org = {in.coord(), in.coord(), in.coord()};
      r.dir = {in.direction_component(), in.direction_component(), in.direction_component()};
    }
    r.tmin = in.t_bound(0.0);
    r.tmax = in.t_bound(std::numeric_limits<double>::infinity());
    const std::size_t hint = fdp.ConsumeIntegralInRange<std::size_t>(0, 3) == 0 ? 0 : fdp.ConsumeIntegralInRange<std::size_t>(1, 5);

    for (const auto* set : {&floats, &doubles}) {
      std::vector<Hit> ref;
      for (std::size_t i = 0; i < set->size(); ++i) {
        HitIterator it(accel, (*set)[i]);
        std::vector<Hit> got;
        collect_hits(it, r, i == 0 ? 0 : hint, got);
        // Basic sanity of every list.
        for (std::size_t j = 0; j < got.size(); ++j) {
          const Hit& h = got[j];
          if (!std::isfinite(h.t)) fail(std::string(kernel_name((*set)[i])) + ": non-finite t" + list(got), r);
          if (!(h.t >= r.tmin && h.t <= r.tmax)) fail(std::string(kernel_name((*set)[i])) + ": t outside the segment" + list(got), r);
          for (std::size_t k = 0; k < j; ++k)
            if (got[k].geom == h.geom && got[k].prim == h.prim)
              fail(std::string(kernel_name((*set)[i])) + ": duplicate" + list(got), r);
        }
        if (i == 0) {
          ref = got;
        } else if (!same_list(ref, got, hint)) {
          fail(std::string(kernel_name((*set)[0])) + " vs " + std::string(kernel_name((*set)[i])) + " (hint " +
                   std::to_string(hint) + "):\n   " + list(ref) + "\n   " + list(got),
               r);
        }
      }
      // The exact answer for the kernels' own view, inside the supported range.
      if (!in_supported_range(scene, r)) continue;
      const bool dbl = set == &doubles;
      oracle::OracleResult want;
      if (dbl) {
        if (!od) od = std::make_unique<oracle::Oracle<double>>(scene);
        want = od->trace(r);
      } else {
        if (!of) of = std::make_unique<oracle::Oracle<float>>(scene);
        want = of->trace(r);
      }
      const oracle::Discrepancy d = oracle::compare(ref, want, {}, oracle::CompareMode::kernel_view, dbl ? 53 : 24);
      if (!d.exact()) {
        std::string o;
        for (const auto& h : want.hits) o += " (" + std::to_string(h.geom) + "," + std::to_string(h.prim) + ")";
        fail(std::string(dbl ? "double" : "float") + " kernels vs oracle: missed " + std::to_string(d.missed) +
                 " extra " + std::to_string(d.extra) + " order " + std::to_string(d.out_of_order) + " facing " +
                 std::to_string(d.wrong_enter) + "\n   kernel:" + list(ref) + "\n   oracle:" + o,
             r);
      }
    }
  }
  return 0;
}
