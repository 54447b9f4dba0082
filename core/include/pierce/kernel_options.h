#pragma once
// The options every kernel is constructed with.
#include "pierce/hit.h"

namespace pierce {

struct KernelOptions {
  HitOrder order;
  double epsilon_rel = 1e-5;  // epsilon kernel only: relative to the scene diagonal
  // The counting variant of the kernel: HitIterator::counters() then reports its work (node tests,
  // traversal steps, primitive tests, valid hits). Off, counting costs nothing.
  bool count = false;
};

}  // namespace pierce
