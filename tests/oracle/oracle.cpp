#include "oracle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "pierce/traversal_ray.h"

namespace pierce::oracle {

namespace {

// Safety factor on the rounding bound of a kernel's t (decides which hits are "near" tmin/tmax,
// and which pairs of t may swap in kernel_view comparisons; never an exact decision).
constexpr double kTolFactor = 16.0;

std::uint64_t key(std::uint32_t geom, std::uint32_t prim) { return (std::uint64_t(geom) << 32) | prim; }

// Per-ray data of one vertex. a = p - o exactly; X = a_kx d_kz - d_kx a_kz and
// Y = a_ky d_kz - d_ky a_kz are the true sheared coordinates times d_kz. kX, kY are the
// kernel's sheared coordinates, a_kx - sx a_kz with every operation rounded to T, held exactly.
struct VertexData {
  Exact akz, X, Y, kX, kY;
  double mag = 0;  // |a_kx| + |a_ky| + (|sx| + |sy|) |a_kz|: scale of the rounding in its shear
  double akz_d = 0;
};

// The kernels' tie rule: sign of the edge function e of (p, q) as if the ray passed through
// (eps, eps^2) of the sheared plane. `s` is +-1: the sign relating the coordinates given to the
// sheared ones (d_kz's sign for X/Y, +1 for the kernel's own).
int perturbed(const Exact& e, const Exact& px, const Exact& py, const Exact& qx, const Exact& qy, int s) {
  if (int r = e.sign()) return r;
  if (int r = (py - qy).sign()) return r * s;
  if (int r = (qx - px).sign()) return r * s;
  return 0;
}

}  // namespace

Discrepancy& Discrepancy::operator+=(const Discrepancy& o) {
  expected += o.expected, missed += o.missed, extra += o.extra, duplicated += o.duplicated;
  out_of_order += o.out_of_order, wrong_enter += o.wrong_enter, unchecked += o.unchecked;
  max_t_error_ulps = std::max(max_t_error_ulps, o.max_t_error_ulps);
  return *this;
}

template <typename T>
Oracle<T>::Oracle(const Scene& scene) {
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    const auto base = std::uint32_t(verts_.size());
    for (const Vec3d& p : geo.vertices) {
      Vertex v;
      v.p = Vec3<T>(p);  // the rounding build_bvh<T> applies
      for (int k = 0; k < 3; ++k) v.x[k] = Exact(double(v.p[k]));
      verts_.push_back(std::move(v));
    }
    // Every triangle, degenerate or not: a zero-area triangle has d . n == 0 for every ray,
    // so the exact test below never hits it, which is the documented convention.
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      const Tri& t = geo.triangles[p];
      tris_.push_back({g, p, {base + t[0], base + t[1], base + t[2]}});
    }
  }
}

template <typename T>
OracleResult Oracle<T>::trace(const Ray& ray, HitOrder order) const {
  OracleResult res;
  // The kernel's view of the ray: origin, direction and range rounded to T, and its choice of
  // axes (part of the convention: the tie rule's perturbation follows kx, ky).
  const TraversalRay<T> tr = TraversalRay<T>::make(ray, 0.0);
  res.ray_valid = tr.valid();
  if (!res.ray_valid) return res;
  if (std::isnan(tr.tmin) || std::isnan(tr.tmax)) return res;  // no t satisfies tmin <= t <= tmax
  // tmin = +inf or tmax = -inf: empty range.
  if ((std::isinf(tr.tmin) && tr.tmin > 0) || (std::isinf(tr.tmax) && tr.tmax < 0)) return res;
  const int kx = tr.kx, ky = tr.ky, kz = tr.kz;
  const Exact O[3] = {Exact(double(tr.org.x)), Exact(double(tr.org.y)), Exact(double(tr.org.z))};
  const Exact D[3] = {Exact(double(tr.dir.x)), Exact(double(tr.dir.y)), Exact(double(tr.dir.z))};
  const int sdz = D[kz].sign();
  const double dkz = double(tr.dir[kz]);
  const double sx = double(tr.dir[kx]) / dkz, sy = double(tr.dir[ky]) / dkz;  // approximate, for tolerances
  const double u = double(std::numeric_limits<T>::epsilon()) / 2;
  const bool has_tmin = !std::isinf(tr.tmin), has_tmax = !std::isinf(tr.tmax);
  const Exact tmin_x = has_tmin ? Exact(double(tr.tmin)) : Exact();
  const Exact tmax_x = has_tmax ? Exact(double(tr.tmax)) : Exact();
  const Exact t_limit{double(std::numeric_limits<T>::max())};

  std::vector<VertexData> vd(verts_.size());
  for (std::size_t i = 0; i < verts_.size(); ++i) {
    const Vertex& v = verts_[i];
    const Exact a[3] = {v.x[0] - O[0], v.x[1] - O[1], v.x[2] - O[2]};
    VertexData& d = vd[i];
    d.akz = a[kz];
    d.X = a[kx] * D[kz] - D[kx] * a[kz];
    d.Y = a[ky] * D[kz] - D[ky] * a[kz];
    const Vec3<T> ak = v.p - tr.org;  // the kernel's arithmetic (contraction is off here too)
    d.kX = Exact(double(ak[kx] - tr.sx * ak[kz]));
    d.kY = Exact(double(ak[ky] - tr.sy * ak[kz]));
    const double ax = a[kx].to_double(), ay = a[ky].to_double();
    d.akz_d = a[kz].to_double();
    d.mag = std::abs(ax) + std::abs(ay) + (std::abs(sx) + std::abs(sy)) * std::abs(d.akz_d);
  }

  for (const Tri3& t : tris_) {
    const VertexData &A = vd[t.v[0]], &B = vd[t.v[1]], &C = vd[t.v[2]];
    // Edge functions times d_kz^2: the same signs as the kernel's U, V, W on exact coordinates.
    const Exact U = C.X * B.Y - C.Y * B.X;
    const Exact V = A.X * C.Y - A.Y * C.X;
    const Exact W = B.X * A.Y - B.Y * A.X;
    const int su = perturbed(U, C.X, C.Y, B.X, B.Y, sdz), sv = perturbed(V, A.X, A.Y, C.X, C.Y, sdz),
              sw = perturbed(W, B.X, B.Y, A.X, A.Y, sdz);
    const bool edges_pass = su != 0 && su == sv && su == sw;
    // The same decision on the kernel's rounded sheared coordinates.
    const int ku = perturbed(C.kX * B.kY - C.kY * B.kX, C.kX, C.kY, B.kX, B.kY, 1);
    const int kv = perturbed(A.kX * C.kY - A.kY * C.kX, A.kX, A.kY, C.kX, C.kY, 1);
    const int kw = perturbed(B.kX * A.kY - B.kY * A.kX, B.kX, B.kY, A.kX, A.kY, 1);
    const bool view_pass = ku != 0 && ku == kv && ku == kw;

    ExactHit h;
    bool in_range = false, near_t = false;
    if (edges_pass || view_pass) {
      // Plane crossing: t = ((v0 - o) . n) / (d . n), n = (v1 - v0) x (v2 - v0).
      const Vertex &P0 = verts_[t.v[0]], &P1 = verts_[t.v[1]], &P2 = verts_[t.v[2]];
      const Exact e1[3] = {P1.x[0] - P0.x[0], P1.x[1] - P0.x[1], P1.x[2] - P0.x[2]};
      const Exact e2[3] = {P2.x[0] - P0.x[0], P2.x[1] - P0.x[1], P2.x[2] - P0.x[2]};
      const Exact n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0]};
      const Exact den = D[0] * n[0] + D[1] * n[1] + D[2] * n[2];
      // den == 0: the ray lies in the triangle's plane, or the triangle has zero area. The
      // perturbed signs of such a triangle can never all agree, so this only guards.
      if (!den.is_zero()) {
        const Exact num = (P0.x[0] - O[0]) * n[0] + (P0.x[1] - O[1]) * n[1] + (P0.x[2] - O[2]) * n[2];
        h.geom = t.geom;
        h.prim = t.prim;
        h.enter = den.sign() < 0;
        h.t = {num, den};
        h.t_approx = h.t.to_double();
        const double z = std::max({std::abs(A.akz_d), std::abs(B.akz_d), std::abs(C.akz_d)}) / std::abs(dkz);
        const double m2 = A.mag * B.mag + B.mag * C.mag + C.mag * A.mag;
        const double det = std::abs(ExactRatio{U + V + W, D[kz] * D[kz]}.to_double());  // no overflow
        h.t_tol = kTolFactor * u * (std::abs(h.t_approx) + z * (1.0 + (det > 0 ? m2 / det : 1e300)));
        // A distance the kernel's precision cannot represent is never reported (a tiny
        // direction can put every hit beyond T's largest finite value).
        in_range = (!has_tmin || h.t.compare_to(tmin_x) >= 0) && (!has_tmax || h.t.compare_to(tmax_x) <= 0) &&
                   h.t.compare_to(t_limit) <= 0 && h.t.compare_to(-t_limit) >= 0;
        near_t = (has_tmin && std::abs(h.t_approx - double(tr.tmin)) <= h.t_tol) ||
                 (has_tmax && std::abs(h.t_approx - double(tr.tmax)) <= h.t_tol);
        if (near_t) {
          // The kernel's t is exact where the triangle is perpendicular to an axis the ray is
          // not parallel to: it is clamped to the slab value fl((v_k - o_k) * inv_k).
          for (int k = 0; k < 3 && near_t; ++k) {
            const T vk = verts_[t.v[0]].p[k];
            if (tr.zero[k] || verts_[t.v[1]].p[k] != vk || verts_[t.v[2]].p[k] != vk) continue;
            const T slab_t = (vk - tr.org[k]) * tr.inv[k];
            if (std::isfinite(slab_t) && h.t.compare_to(Exact(double(slab_t))) == 0) near_t = false;
          }
        }
      }
    }
    const bool hit = edges_pass && in_range;
    if (edges_pass != view_pass) {
      // The kernel's answer is known unless its t, computed on the rounded geometry, may fall
      // on either side of tmin/tmax.
      res.outside.push_back({t.geom, t.prim, hit, !(view_pass && near_t), view_pass && in_range});
    } else if (edges_pass && near_t) {
      res.outside.push_back({t.geom, t.prim, hit, false, false});
    }
    if (hit) res.hits.push_back(std::move(h));
  }

  std::sort(res.hits.begin(), res.hits.end(), [&](const ExactHit& a, const ExactHit& b) {
    if (const int c = compare(a.t, b.t)) return c < 0;
    if (order.tie == TieOrder::leave_before_enter && a.enter != b.enter) return !a.enter;
    if (a.geom != b.geom) return a.geom < b.geom;
    return a.prim < b.prim;
  });
  return res;
}

template class Oracle<float>;
template class Oracle<double>;

Discrepancy compare(const std::vector<Hit>& kernel, const OracleResult& oracle, HitOrder /*order*/,
                    CompareMode mode, int ulp_bits) {
  Discrepancy d;
  std::unordered_map<std::uint64_t, std::size_t> rank;  // exact hits by identity
  for (std::size_t i = 0; i < oracle.hits.size(); ++i) rank[key(oracle.hits[i].geom, oracle.hits[i].prim)] = i;
  // Expected presence of every identity whose answer differs from "absent".
  std::unordered_map<std::uint64_t, bool> expect;
  for (const ExactHit& h : oracle.hits) expect[key(h.geom, h.prim)] = true;
  std::unordered_set<std::uint64_t> skip;
  for (const OutsideDecision& o : oracle.outside) {
    const std::uint64_t k = key(o.geom, o.prim);
    if (mode == CompareMode::kernel_view && o.view_known) {
      expect[k] = o.view_hit;
    } else {
      skip.insert(k);
    }
  }
  d.unchecked = skip.size();
  for (const auto& [k, present] : expect) d.expected += present && !skip.count(k);

  std::unordered_map<std::uint64_t, std::size_t> seen;
  std::size_t prev = std::numeric_limits<std::size_t>::max();
  for (const Hit& h : kernel) {
    const std::uint64_t k = key(h.geom, h.prim);
    if (seen[k]++ > 0) {
      ++d.duplicated;
      continue;
    }
    if (skip.count(k)) continue;
    const auto e = expect.find(k);
    if (e == expect.end() || !e->second) {
      ++d.extra;
      continue;
    }
    const auto it = rank.find(k);
    if (it == rank.end()) continue;  // present only in the kernel's view: no exact t to check
    const ExactHit& x = oracle.hits[it->second];
    if (h.enter != x.enter) ++d.wrong_enter;
    // t error, exactly: |t_k - num/den| in ulps of T at the exact t.
    const mpq_class err = abs((Exact(h.t) * x.t.den - x.t.num).to_mpq() / x.t.den.to_mpq());
    const double at = std::max(std::abs(x.t_approx), std::numeric_limits<double>::min());
    const double ulp = std::ldexp(1.0, std::ilogb(at) - (ulp_bits - 1));
    d.max_t_error_ulps = std::max(d.max_t_error_ulps, err.get_d() / ulp);
    if (prev != std::numeric_limits<std::size_t>::max() && it->second < prev) {
      const ExactHit& p = oracle.hits[prev];
      const bool tied = std::abs(p.t_approx - x.t_approx) <= p.t_tol + x.t_tol;
      if (mode == CompareMode::strict || !tied) ++d.out_of_order;
    }
    prev = it->second;
  }
  for (const auto& [k, present] : expect)
    if (present && !seen.count(k) && !skip.count(k)) ++d.missed;
  return d;
}

}  // namespace pierce::oracle
