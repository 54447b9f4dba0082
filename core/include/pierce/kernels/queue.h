#pragma once
// `queue` (Wald et al. §4): a hit is returned once it is strictly closer than every untraversed
// node, so the caller can stop at any hit and pays only for the nodes in front of it; the state
// survives between next() calls.
//
// The paper keeps every untraversed node in a priority queue. Here the queue holds only the nodes
// that cannot matter yet: the traversal runs depth first on the stack, near child first, and a
// node entered beyond the bound is not traversed but moved onto the heap. The bound is the N-th
// nearest hit held but not yet returned, N the max_hits hint (without one, N = 1: the nearest hit,
// as in `restart`, so a caller that stops early pays for the nodes in front of that hit only).
// Every node in front of the bound must be traversed anyway, so the heap sees only the few
// deferred subtrees instead of every child of every node; a next() that needs more pops the
// nearest deferred node and runs the same depth-first pass from it.
// Why the hits come out complete and in order: when a pass ends, every node not traversed is on
// the heap; the nearest hit held is returned only while it is strictly nearer than the nearest
// node on the heap (a node entered at exactly its t may hold a hit that ranks first).
//
// The first pass may instead be `filter`'s (GatherInRange: breadth first, FifoCursor, every hit in
// range, nothing deferred, the first N sorted). Near to far pays where the bound closes early (N hits
// held), since the nodes beyond it are then deferred; where it closes late, or never (a ray with
// fewer hits than N), nearly every node in range is traversed whatever the order, and breadth
// first hides the latency of each node behind the others. Which rays are which is not known in
// advance, so by default (QueueFirstPass::adaptive) the kernel measures what culling saved on its
// recent depth-first first passes, as nodes deferred per node traversed, and gathers while that is
// small (QueueScheduler, below). The gathering pass keeps no bound: breadth first it would close
// late. The hits are the same either way: after a gathering pass every hit is held and no node is
// deferred.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

enum class QueueFirstPass { adaptive, depth_first, breadth_first };

// The knobs of `queue`'s schedule, in one place. They change only the time, never the hits.
// `pierce_bench_kernels --kernels queue,filter,restart --max-hits 5,15` shows their effect: where
// no ray closes its bound (blob, CGAL's meshes, the shell at N = 5 and 15) `queue` must tie with
// `filter`, and where culling pays (plates, hairball at N = 5) it must beat it.
struct QueueKnobs {
  // An adaptive kernel gathers while its depth-first passes defer fewer subtrees than this per
  // node traversed. Between the bench scenes: hairball at N = 15 defers 0.03 and runs faster
  // breadth first, at N = 5 0.17 and runs faster near to far.
  float breadth_first_below = 0.08f;
  // Weight of each depth-first pass in that running average: it follows the last few dozen.
  float average_weight = 1.0f / 32.0f;
  // While it gathers, every probe_every-th ray still runs depth first to keep the average current;
  // the interval (a power of two) doubles while probes find little to cull, up to probe_most, and
  // returns to probe_least when one finds more.
  std::uint64_t probe_least = 32, probe_most = 256;
  // A probe runs only where at least one in probe_share of the rays gathered since the last one
  // held as many hits as the bound's depth: a ray with fewer closes no bound, so depth first it
  // defers nothing and only loses the latency that the breadth-first pass hides.
  std::uint64_t probe_share = 8;
};
inline constexpr QueueKnobs kQueueKnobs{};

// Chooses each ray's first pass: depth first (near to far, deferring what lies beyond the bound)
// or gathering (`filter`'s pass: breadth first, every hit in range). Fixed by QueueFirstPass, or
// adaptive: measured on the recent depth-first passes, with probes while it gathers.
class QueueScheduler {
 public:
  explicit QueueScheduler(QueueFirstPass mode)
      : mode_(mode), gathering_(mode == QueueFirstPass::breadth_first), until_probe_(gathering_ ? kNever : 1) {}

  // Once per ray: true where the scheduler must be asked (decide()). While it gathers, this count
  // is all a ray pays over `filter`; while it runs depth first, it is due on every ray.
  [[gnu::always_inline]] bool due() { return --until_probe_ == 0; }

  // On a due ray: true to run it depth first (a probe, or every ray while depth first); false to
  // gather after all (a probe is due, but too few gathered rays since the last one could cull:
  // the next interval is twice as long, as after a probe that found little to cull).
  bool decide() {
    if (!gathering_) {
      until_probe_ = 1;  // the next ray comes here too, unless the pass's result starts gathering
      return true;
    }
    const bool probe = could_cull();
    cull_rays_ = 0;
    if (!probe) probe_every_ = std::min(2 * probe_every_, kQueueKnobs.probe_most);
    until_probe_ = probe_every_;
    return probe;
  }

  // A gathered ray that held max_hits hits (1 without a hint) or more: its bound could have closed.
  void cullable_ray() { ++cull_rays_; }

  // After a depth-first first pass that deferred `deferred` subtrees over `steps` nodes traversed.
  void depth_first_done(std::size_t deferred, std::uint64_t steps) {
    cull_rays_ = 0;
    const float per_step = float(deferred) / float(steps > 0 ? steps : 1);
    deferred_per_step_ += (per_step - deferred_per_step_) * kQueueKnobs.average_weight;
    // While probes say "gather" by a wide margin, probe half as often; one that does not brings
    // the interval back to probe_least.
    const float clear_below = kQueueKnobs.breadth_first_below / 4;
    const bool clear = per_step < clear_below && deferred_per_step_ < clear_below;
    probe_every_ = clear ? std::min(2 * probe_every_, kQueueKnobs.probe_most) : kQueueKnobs.probe_least;
    if (mode_ == QueueFirstPass::adaptive) {
      gathering_ = deferred_per_step_ < kQueueKnobs.breadth_first_below;
      until_probe_ = gathering_ ? probe_every_ : 1;
    }
  }

  // Whether the next ray's first pass gathers.
  bool gathers_next() const { return gathering_ && !(until_probe_ == 1 && could_cull()); }

 private:
  static constexpr std::uint64_t kNever = std::uint64_t(-1);  // no probes (breadth_first mode)
  bool could_cull() const { return cull_rays_ * kQueueKnobs.probe_share >= probe_every_; }

  QueueFirstPass mode_;
  bool gathering_;
  // Rays until the next decide(), this one included (1 while first passes run depth first).
  std::uint64_t until_probe_;
  std::uint64_t probe_every_ = kQueueKnobs.probe_least;
  std::uint64_t cull_rays_ = 0;      // gathered rays since the last decision that could cull
  float deferred_per_step_ = 1.0f;   // adaptive: starts near to far
};

template <typename T, class C = NoCounters>
class QueueKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  explicit QueueKernel(const WideBvh<T>& bvh, HitOrder order = {},
                       QueueFirstPass first_pass = QueueFirstPass::adaptive)
      : Base(bvh, order), schedule_(first_pass) {
    hits_.reserve(16);
    deferred_.reserve(4 * bvh.stack_capacity());
  }

  void begin(const Ray& ray, std::size_t max_hits = 0) {
    // next()'s state, which begin_into() leaves alone on a gathering pass (descend_first() resets it).
    hits_.clear();
    pos_ = 0;
    deferred_.clear();
    // A gathering pass sorts only the first max_hits of hits_: next() sorts the rest if it gets there.
    const bool gathered = begin_into(ray, max_hits, hits_);
    unsorted_from_ = gathered && max_hits != 0 ? max_hits : kAllSorted;
  }

  // begin(). A gathering first pass appends every hit to `out` and returns true (for
  // HitIterator::collect: no copy through next()): the first max_hits of them in order (all
  // without a hint), the rest after them in no order, since the caller asked for max_hits. A
  // depth-first pass holds its hits for next() and returns false. A gathering pass touches nothing
  // next() reads (begin() resets next()'s state itself). Always inlined, as `filter`'s pass is
  // into HitIterator::collect(), so that a gathered ray costs what a `filter` ray does.
  [[gnu::always_inline]] bool begin_into(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
    this->prepare(ray);
    if (schedule_.due()) [[unlikely]] {
      if (descends(max_hits)) return false;
    }
    gather(max_hits, out);
    return true;
  }

  // Whether the next begin() runs its first pass breadth first.
  bool breadth_first() const { return schedule_.gathers_next(); }
  static constexpr std::uint64_t kProbeShare = kQueueKnobs.probe_share;

  bool next(Hit& out) {
    // Nothing deferred (always after a gathering pass): every hit left is held, in order, and no
    // pass will run again, so the bound no longer matters.
    if (deferred_.empty()) {
      if (pos_ == unsorted_from_) {
        sort_hits(hits_.begin() + std::ptrdiff_t(pos_), hits_.end(), this->order_);
        unsorted_from_ = kAllSorted;
      }
      if (pos_ >= hits_.size()) return false;
      out = hits_[pos_++];
      return true;
    }
    for (;;) {
      if (pos_ < hits_.size() && (deferred_.empty() || hits_[pos_].t < double(deferred_.next_tn()))) {
        out = hits_[pos_++];
        update_bound();
        return true;
      }
      if (deferred_.empty()) return false;
      this->pending_.clear();
      this->pending_.push(deferred_.pop());
      Descend p{*this};
      this->run(p);  // depth first from the nearest deferred node, deferring what lies beyond the bound
    }
  }

 private:
  // A ray on which the schedule is due: runs a depth-first first pass and returns true, or
  // returns false where the ray gathers after all. Out of line, so that begin_into() holds the one
  // copy of the gathering pass, laid out as `filter`'s.
  [[gnu::noinline]] bool descends(std::size_t max_hits) {
    if (!schedule_.decide()) return false;
    descend_first(max_hits);
    return true;
  }

  // A gathering first pass into `out`. Unlike `filter`, it sorts only the max_hits hits the caller
  // wants: a ray with many more (hairball) is not sorted in full. A ray that holds max_hits hits
  // (1 without a hint) or more could have closed the bound, so culling could have paid on it
  // (QueueScheduler::cullable_ray); a ray that holds fewer pays only the size test for it.
  [[gnu::always_inline]] void gather(std::size_t max_hits, std::vector<Hit>& out) {
    const std::size_t first = out.size();
    this->gather_in_range(out);
    const auto from = out.begin() + std::ptrdiff_t(first);
    if (out.end() - from < std::ptrdiff_t(std::max<std::size_t>(max_hits, 1))) [[likely]] {
      sort_hits(from, out.end(), this->order_);
      return;
    }
    sort_first(from, out.end(), max_hits);
  }
  // gather() on a ray that holds max_hits hits or more: out of line, so that the path of the rays
  // that hold fewer is laid out as `filter`'s.
  [[gnu::noinline]] void sort_first(std::vector<Hit>::iterator first, std::vector<Hit>::iterator last,
                                    std::size_t max_hits) {
    schedule_.cullable_ray();
    sort_first_hits(first, last, max_hits, this->order_);
  }

  // A depth-first first pass. The bound (depth_, bound_) is set here: after a gathering pass
  // nothing is deferred, so next() never reads it.
  void descend_first(std::size_t max_hits) {
    hits_.clear();
    pos_ = 0;
    deferred_.clear();
    depth_ = max_hits == 0 ? 1 : max_hits;
    bound_ = this->ray_.tmax;
    // The first pass, from the root (what the first next() would do, without the heap).
    this->seed_root(this->ray_.tmin, this->ray_.tmax);
    steps_ = 0;
    Descend p{*this};
    this->run(p);
    // What culling saved on this ray: subtrees deferred per node traversed (none where the bound
    // never closed). Measured on depth-first passes only: a gathering pass defers nothing.
    schedule_.depth_first_done(deferred_.size(), steps_);
  }

  // Every hit is held in order; a node entered beyond the depth_-th held hit not yet returned is
  // deferred. Children are pushed onto the stack unchecked (the fast SIMD push) and checked when
  // popped.
  struct Descend : TraversalPolicy<T> {
    QueueKernel& k;
    explicit Descend(QueueKernel& kernel) : k(kernel) {}
    void node(NodeRef /*ref*/, T /*tn*/) { ++k.steps_; }
    T lo() const { return k.ray_.tmin; }
    T hi() const { return k.ray_.tmax; }
    T cull_bound() const { return k.bound_; }
    void culled(NodeEntry<T> node) { k.deferred_.push(node); }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) { k.hold(make_hit(b, l, h)); }
  };
  // Inserted in order; the depth-first pass meets hits roughly near to far, so from the back:
  // the held hits that rank after h move up one.
  void hold(const Hit& h) {
    hits_.push_back(h);
    std::size_t i = hits_.size() - 1;
    while (i > pos_ && this->order_.less(h, hits_[i - 1])) {
      hits_[i] = hits_[i - 1];
      --i;
    }
    hits_[i] = h;
    update_bound();
  }
  void update_bound() {
    bound_ = hits_.size() - pos_ >= depth_ ? T(hits_[pos_ + depth_ - 1].t) : this->ray_.tmax;
  }

  std::vector<Hit> hits_;  // held hits in hit order; those before pos_ were returned
  std::size_t pos_ = 0;
  // hits_ from here on are in no order (a gathering pass sorted only the first max_hits).
  static constexpr std::size_t kAllSorted = std::size_t(-1);
  std::size_t unsorted_from_ = kAllSorted;
  std::size_t depth_ = 1;  // the bound is the depth_-th held hit not yet returned
  T bound_ = 0;            // its t (tmax while fewer are held)
  NodeHeap<T> deferred_;   // nodes entered beyond the bound, nearest first
  std::uint64_t steps_ = 0;  // nodes traversed in this ray's passes
  QueueScheduler schedule_;
};

}  // namespace pierce
