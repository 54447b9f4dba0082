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

// A triangle where the exact answer for the true geometry and the exact answer for the
// kernel's own view of it (its sheared vertex coordinates as rounded in precision T, which is
// what the kernels promise to decide exactly) may differ: the ray passes within rounding
// distance of an edge or vertex and the shear's rounding moved it across, or the hit lies within
// rounding distance of tmin/tmax where the kernel's t is not exact. These decisions are outside
// the exact class of docs/EXACTNESS.md.
struct OutsideDecision {
  std::uint32_t geom = 0, prim = 0;
  bool hit = false;         // exact answer, true geometry
  bool view_known = false;  // the kernel's answer is known exactly (false: t-range case)
  bool view_hit = false;    // exact answer on the kernel's rounded sheared coordinates
};

struct OracleResult {
  bool ray_valid = false;               // false: NaN/Inf or zero direction, no hits by definition
  std::vector<ExactHit> hits;           // every crossing, in the exact total order
  std::vector<OutsideDecision> outside; // decisions outside the exact class
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
  // Against the true geometry, every order exact; decisions outside the exact class are not
  // checked and are counted in `unchecked` (the corpus is built to have none).
  strict,
  // Against the exact answer for the kernel's own rounded sheared coordinates (any ray): hit
  // sets exact except hits within rounding distance of tmin/tmax; two hits whose exact t are
  // within rounding tolerance may come in either order.
  kernel_view,
};

struct Discrepancy {
  std::size_t expected = 0;      // oracle hits
  std::size_t missed = 0;        // oracle hits the kernel did not report
  std::size_t extra = 0;         // reported hits the oracle does not have (distinct identities)
  std::size_t duplicated = 0;    // repeated reports of one (geom, prim)
  std::size_t out_of_order = 0;  // adjacent reported pairs in the wrong exact order
  std::size_t wrong_enter = 0;   // facing differs from the oracle
  std::size_t unchecked = 0;     // decisions not checked (outside the exact class)
  double max_t_error_ulps = 0;   // |kernel t - exact t| in ulps of T at the exact t

  bool exact() const { return missed == 0 && extra == 0 && duplicated == 0 && out_of_order == 0 && wrong_enter == 0; }
  Discrepancy& operator+=(const Discrepancy& o);
};

// `ulp_bits`: 24 for float kernels, 53 for double kernels (for the t error column).
Discrepancy compare(const std::vector<Hit>& kernel, const OracleResult& oracle, HitOrder order, CompareMode mode,
                    int ulp_bits);

}  // namespace pierce::oracle
