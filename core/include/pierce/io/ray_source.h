#pragma once
// Rays from a CSV file or a generator spec, as `pierce hits --rays` takes them.
#include <string>
#include <vector>

#include "pierce/ray.h"
#include "pierce/scene.h"

namespace pierce {

// `spec` is one of:
//  - a CSV file, one ray per line: `ox,oy,oz,dx,dy,dz[,tmin,tmax]` (default tmin 0, tmax inf; `inf`
//    accepted for tmax). An optional header line (first content line, not numeric), blank lines and
//    lines starting with '#' are skipped. Directions need not be unit length; t is in units of |dir|.
//  - `grid:axis=x|y|z,n=N[,dir=+|-]`: N x N rays parallel to +axis (or -axis), one through the centre
//    of each cell of an N x N grid over the scene bounds' cross-section, starting outside the
//    bounds. With (u, v) the two other axes in cyclic order (z: x, y; x: y, z; y: z, x), ray
//    j*N + i passes through cell i along u and j along v. axis defaults to z, dir to +.
//  - `random:n=N[,seed=S]`: N rays, origin uniform on the sphere around the bounds' centre with
//    1.5 x the half-diagonal as radius, aimed at a uniform point inside the bounds; unit directions.
//    Deterministic for a given seed (default 1): mt19937_64 with Pierce's own distributions, not the
//    std:: ones whose output differs between standard libraries.
// Throws InputError: "path:line: what" for CSV problems; the spec and the problem for generators
// (unknown keys, missing or non-positive n, bad numbers, an empty scene).
std::vector<Ray> load_rays(const std::string& spec, const Scene& scene);

// Upper bound on generated rays (grid n*n, random n): beyond it memory, not the kernels, fails.
inline constexpr std::size_t kMaxGeneratedRays = std::size_t(1) << 30;

}  // namespace pierce
