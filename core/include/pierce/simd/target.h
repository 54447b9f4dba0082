#pragma once
// The instruction-set targets of the SIMD levels (simd_level.h). The SIMD code is compiled for
// these with GCC target attributes, behind Pierce's own run-time dispatch: only code reached after
// the CPU check (simd_level()) runs it, so one binary runs on any x86-64. A function with the AVX2
// target can be inlined into one with the AVX-512 target (its instructions are a subset); the
// traversal's per-level entry points are flattened, so everything below them inlines.

#define PIERCE_AVX2_TARGET "avx2,fma,bmi,bmi2"
#define PIERCE_AVX512_TARGET "avx2,fma,avx512f,avx512vl,avx512bw,avx512dq,bmi,bmi2"

namespace pierce::simd {

// The SIMD levels, as tags for what differs between them (node_test.h, hit_output.h).
struct Avx2 {};
struct Avx512 {};

}  // namespace pierce::simd
