#pragma once
// Kernels on Embree's BVH and traversal (rtcIntersect1), all exact through Pierce's
// triangle test in a user geometry:
//  - embree-restart: closest hit after the last one in the total order, per next();
//  - embree-filter: all hits gathered by the filter (AGGW15), sorted, duplicates removed;
//  - embree-nodecull: N closest with the filter shrinking tfar once N are held (GWA16).
// And the inexact baseline on Embree's native triangles:
//  - epsilon: closest hit, then relaunch from t + epsilon.
#include <vector>

#include "pierce/embree_accel.h"
#include "pierce/kernels/embree_query.h"

namespace pierce {

// Shared ray setup: rebasing and the Embree-frame ray for a query.
class EmbreeExactBase {
 protected:
  EmbreeExactBase(const EmbreeAccel& acc, HitOrder order, EmbreeQuery::Mode mode, bool count);
  // Prepares q_ for `ray`; false if the ray cannot meet the scene.
  bool setup(const Ray& ray);
  // Runs one rtcIntersect1 over Pierce-frame range [lo, hi].
  void trace(double lo, double hi);

  const EmbreeAccel* acc_;
  RTCScene scene_;  // acc_->exact(), asked for once
  EmbreeQuery q_;
  Vec3d org_, dir_;
  bool live_ = false;
  bool count_ = false;

 public:
  Counters counters;  // kept only when constructed with count = true
};

class EmbreeRestartKernel : public EmbreeExactBase {
 public:
  explicit EmbreeRestartKernel(const EmbreeAccel& acc, HitOrder order = {}, bool count = false)
      : EmbreeExactBase(acc, order, EmbreeQuery::Mode::restart, count) {}
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);
};

class EmbreeFilterKernel : public EmbreeExactBase {
 public:
  explicit EmbreeFilterKernel(const EmbreeAccel& acc, HitOrder order = {}, bool count = false)
      : EmbreeExactBase(acc, order, EmbreeQuery::Mode::all, count) {}
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);

 private:
  std::vector<Hit> hits_;
  std::size_t pos_ = 0;
};

class EmbreeNodeCullKernel : public EmbreeExactBase {
 public:
  explicit EmbreeNodeCullKernel(const EmbreeAccel& acc, HitOrder order = {}, bool count = false)
      : EmbreeExactBase(acc, order, EmbreeQuery::Mode::closest_n, count) {}
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);

 private:
  void collect();
  std::vector<Hit> batch_;
  std::size_t pos_ = 0;
  bool exhausted_ = true;
};

// Inexact baseline: what a rendering kernel does. epsilon = epsilon_rel * scene diagonal.
class EpsilonKernel {
 public:
  explicit EpsilonKernel(const EmbreeAccel& acc, double epsilon_rel = 1e-5, bool count = false);
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);
  Counters counters;  // kept only when constructed with count = true

 private:
  RTCScene scene_;  // the accel's native(), asked for once
  double eps_;
  bool count_;
  Ray ray_;
  float tnear_ = 0;
  float last_t_ = 0;       // the last hit's t
  bool relaunch_ = false;  // a hit was returned: the next call starts beyond last_t_
  bool done_ = true;
};

// Embree's own first hit on native triangles (the speed reference; not exact).
bool embree_first_hit(const EmbreeAccel& acc, const Ray& ray, Hit& out);

}  // namespace pierce
