#pragma once
// The SIMD layer of the wide-BVH traversal, by role:
//  - target.h: the instruction-set targets of the levels (simd_level.h picks one at run time);
//  - ray_setup.h: SimdRay, what the tests take from the ray, and prepare_simd_ray;
//  - node_test.h: the slab test of a node's eight child boxes, with its containment argument;
//  - leaf_test.h: the triangle test of a leaf block's eight lanes, bit for bit the scalar one;
//  - hit_output.h: storing the children that pass for the traversal;
//  - level_ops.h: ScalarOps, Avx2Ops and Avx512Ops, what traverse.h calls.
#include "pierce/simd/level_ops.h"
