#pragma once
// Exact oracle for Pierce's hit convention (docs/EXACTNESS.md). Brute force over every
// triangle, exact arithmetic throughout, no acceleration structure and no rounding in any
// decision.
//
// The kernels' tie rule (an edge function that is exactly zero is decided as if the ray
// passed through the point (eps, eps^2) of the sheared plane) is the same as moving the ray
// ORIGIN by eps * e_kx + eps^2 * e_ky, where kx, ky are the 3D axes TraversalRay::make picks
// from the direction: the shear x' = x - sx z, y' = y - sy z leaves offsets along kx and ky
// unchanged. The oracle therefore decides each triangle with exact signs of the scaled edge
// functions of the true (unrounded) sheared geometry and applies that perturbation
// symbolically. Hit distances are exact rationals, ordered exactly; ties by the HitOrder
// policy.
//
// Precision: Oracle<T> sees what a kernel in precision T sees: vertices rounded to T (as
// build_bvh<T> does) and the ray's origin, direction, tmin, tmax rounded to T (as
// TraversalRay<T>::make does). Oracle<double> on a scene with double vertices is the exact
// answer for the input geometry.
#include <cstdint>
#include <vector>

#include "exact.h"
#include "pierce/hit.h"
#include "pierce/ray.h"
#include "pierce/scene.h"

namespace pierce::oracle {

struct ExactHit {
  std::uint32_t geom = 0, prim = 0;
  bool enter = false;    // direction against (v1 - v0) x (v2 - v0)
  ExactRatio t;          // exact distance along the ray
  double t_approx = 0;   // t, rounded (display, tolerances)
  double t_tol = 0;      // bound on a kernel's rounding error in t (tolerant comparisons)
};

// A triangle whose decision a kernel in precision T might get differently from the exact
// answer because of rounding in its shear or in t (the ray passes within rounding distance of
// one of its edges or vertices, or its hit lies within rounding distance of tmin or tmax).
struct NearDecision {
  std::uint32_t geom = 0, prim = 0;
  bool hit = false;          // the exact decision
  // The kernel's sheared coordinates are exact for the vertices this decision depends on (the
  // endpoints of its near edges; all three when its t is near tmin/tmax), so the kernel must
  // get it exactly right. False: outside the exact class.
  bool shear_exact = false;
};

struct OracleResult {
  bool ray_valid = false;             // false: NaN/Inf or zero direction, no hits by definition
  std::vector<ExactHit> hits;         // every crossing, in the exact total order
  std::vector<NearDecision> near;     // decisions within rounding distance of a boundary
  std::size_t near_not_shear_exact() const {
    std::size_t n = 0;
    for (const auto& d : near) n += d.shear_exact ? 0 : 1;
    return n;
  }
};

template <typename T>
class Oracle {
 public:
  explicit Oracle(const Scene& scene);
  OracleResult trace(const Ray& ray, HitOrder order = {}) const;
  std::size_t triangle_count() const { return tris_.size(); }

 private:
  struct Vertex {
    Vec3<T> p;
    Exact x[3];
  };
  struct Tri3 {
    std::uint32_t geom, prim;
    std::uint32_t v[3];  // into verts_
  };
  std::vector<Vertex> verts_;
  std::vector<Tri3> tris_;
};

extern template class Oracle<float>;
extern template class Oracle<double>;

// ---- Comparing a kernel's hit list with the oracle ----

enum class CompareMode {
  // Every decision and every order is checked exactly (the corpus: rays in the exact class).
  strict,
  // Decisions listed in OracleResult::near are not checked, and two hits whose exact t are
  // within their rounding tolerance may come in either order (general rays).
  tolerant,
};

struct Discrepancy {
  std::size_t expected = 0;      // oracle hits
  std::size_t missed = 0;        // oracle hits the kernel did not report
  std::size_t extra = 0;         // reported hits the oracle does not have (distinct identities)
  std::size_t duplicated = 0;    // repeated reports of one (geom, prim)
  std::size_t out_of_order = 0;  // adjacent reported pairs in the wrong exact order
  std::size_t wrong_enter = 0;   // facing differs from the oracle
  std::size_t unchecked = 0;     // tolerant mode: near decisions skipped
  double max_t_error_ulps = 0;   // |kernel t - exact t| in ulps of T at the exact t

  bool exact() const { return missed == 0 && extra == 0 && duplicated == 0 && out_of_order == 0 && wrong_enter == 0; }
  Discrepancy& operator+=(const Discrepancy& o);
};

// `ulp_bits`: 24 for float kernels, 53 for double kernels (for the t error column).
Discrepancy compare(const std::vector<Hit>& kernel, const OracleResult& oracle, HitOrder order, CompareMode mode,
                    int ulp_bits);

}  // namespace pierce::oracle
