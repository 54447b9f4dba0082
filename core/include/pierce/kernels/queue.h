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
// small. (Until the twentieth session the breadth-first pass kept a bound too; breadth first it
// closes late, and where it never closes `queue` trailed `filter` for the same work:
// docs/BENCHMARKS-HISTORY.md, twentieth session.) The hits are the same either way: after a gathering
// pass every hit is held and no node is deferred.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

enum class QueueFirstPass { adaptive, depth_first, breadth_first };

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class QueueKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  explicit QueueKernel(const WideBvh<T>& bvh, HitOrder order = {},
                       QueueFirstPass first_pass = QueueFirstPass::adaptive)
      : Base(bvh, order), first_pass_(first_pass) {
    gathering_ = first_pass == QueueFirstPass::breadth_first;
    until_probe_ = gathering_ ? kNever : 1;
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
  // depth-first pass holds its hits for next() and returns false.
  // Inlined into HitIterator::collect() as `filter`'s is (GCC left it out of line, a call per ray
  // that `filter` does not make).
  // A gathering pass touches nothing next() reads: its hits are all in `out`, and after
  // HitIterator::collect no next() follows (begin() resets next()'s state itself).
  [[gnu::always_inline]] bool begin_into(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
    this->prepare(ray);
    // While it gathers, this count and gather()'s size test are all a ray pays over `filter`:
    // whether to probe is decided once per probe interval (descends()), not per ray. It is 1 on
    // every ray that does not gather.
    if (--until_probe_ == 0) [[unlikely]] {
      if (descends(max_hits)) return false;
    }
    // `filter`'s pass: every hit in range, nothing deferred. It runs where culling saves little,
    // and breadth first the bound would close late anyway.
    gather(max_hits, out);
    return true;
  }

  // Whether the next begin() runs its first pass breadth first: as the constructor fixed it, or
  // (adaptive) while recent depth-first passes deferred fewer than kBreadthFirstBelow subtrees per
  // node traversed, but for every probe_every_-th ray, which runs depth first to keep that average
  // current. The probes cost: where no ray closes its bound (CGAL's meshes, the shell at N = 5 and
  // 15), probing every 32nd ray kept `queue` measurably behind `filter` (docs/BENCHMARKS-HISTORY.md,
  // eighteenth session), so while the probes find nothing to cull they come less often. And a probe
  // runs only where at least one in kProbeShare of the rays gathered since the last one held as
  // many hits as the bound's depth. A ray with fewer closes no bound: depth first it defers nothing
  // and only loses the latency that the breadth-first pass hides, so where no ray holds that many
  // (blob at N = 5 and 15, CGAL's meshes at N = 15) a probe could only cost, and where more than
  // seven rays lose for each that could cull (CGAL's meshes at N = 5), culling can hardly win it
  // back. (Until the twenty-sixth session one such ray in an interval was enough for a probe.)
  bool breadth_first() const { return gathering_ && !(until_probe_ == 1 && could_cull()); }
  static constexpr std::uint64_t kProbeShare = 8;  // a probe needs one ray in 8 that could cull (above)

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
  // begin_into() at the end of a probe interval, and on every ray while first passes run depth
  // first: runs a depth-first first pass and returns true, or returns false where the ray gathers
  // after all (a probe is due, but too few gathered rays since the last one could cull). Out of
  // line and without a gathering pass of its own: begin_into() has the one copy of it, as `filter`
  // has. (Until the twenty-seventh session this function gathered itself where it skipped a probe:
  // a second copy of the pass, run by one ray in 32 where no probe ever runs, blob at N = 5 and 15.)
  [[gnu::noinline]] bool descends(std::size_t max_hits) {
    if (gathering_) {
      // A probe is due on this ray: run it, or put it one interval on.
      const bool probe = could_cull();
      cull_rays_ = 0;
      if (!probe) {
        // Too few rays could have culled: the next interval is twice as long, as after a probe
        // that found little to cull (descend_first()).
        probe_every_ = std::min(2 * probe_every_, kProbeMost);
        until_probe_ = probe_every_;
        return false;
      }
      until_probe_ = probe_every_;
    } else {
      until_probe_ = 1;  // the next ray comes here too, unless descend_first() starts gathering
    }
    descend_first(max_hits);
    return true;
  }

  // A gathering first pass into `out`. Unlike `filter`, it sorts only the max_hits hits the caller
  // wants: a ray with many more (hairball) is not sorted in full. A ray that holds max_hits hits
  // (1 without a hint) or more could have closed the bound, so culling could have paid on it
  // (cull_rays_); a ray that holds fewer pays only the size test for it.
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
    ++cull_rays_;
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
    cull_rays_ = 0;
    Descend p{*this};
    this->run(p);
    // What culling saved on this ray: subtrees deferred per node traversed (none where the bound
    // never closed). Measured on depth-first passes only, since a gathering pass defers nothing.
    // 1/32: the average follows the last few dozen of them.
    const float deferred = float(deferred_.size()) / float(steps_ > 0 ? steps_ : 1);
    deferred_per_step_ += (deferred - deferred_per_step_) * (1.0f / 32.0f);
    // While the probes say "breadth first" by a wide margin, probe half as often (down to every
    // kProbeMost-th ray); one that does not brings the interval back to kProbeLeast.
    const bool clear = deferred < kBreadthFirstBelow / 4 && deferred_per_step_ < kBreadthFirstBelow / 4;
    probe_every_ = clear ? std::min(2 * probe_every_, kProbeMost) : kProbeLeast;
    if (first_pass_ == QueueFirstPass::adaptive) {
      gathering_ = deferred_per_step_ < kBreadthFirstBelow;
      until_probe_ = gathering_ ? probe_every_ : 1;
    }
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
  QueueFirstPass first_pass_;
  // Between the bench scenes' figures, read from a temporary instrumented build (no bench prints
  // them; sixteenth session, docs/BENCHMARKS-HISTORY.md): hairball at N = 15 defers 0.03 per node traversed
  // and ran faster breadth first in pierce_bench_kernels, at N = 5 0.17 and ran faster near to
  // far; blob and shell at N = 5 and 15 hold fewer hits than N and defer none.
  static constexpr float kBreadthFirstBelow = 0.08f;
  float deferred_per_step_ = 1.0f;  // adaptive: starts near to far
  std::uint64_t steps_ = 0;         // nodes traversed in this ray's passes
  // Adaptive: a breadth-first kernel's first pass still runs depth first on every probe_every_-th ray
  // (a power of two), to measure what culling would save.
  static constexpr std::uint64_t kProbeLeast = 32, kProbeMost = 256;
  std::uint64_t probe_every_ = kProbeLeast;
  // Whether first passes gather (breadth_first: always; adaptive: while culling saves little),
  // and, while they do, the rays until an adaptive kernel's next probe, this one included (kNever:
  // no probes; 1 while first passes run depth first).
  static constexpr std::uint64_t kNever = std::uint64_t(-1);
  bool gathering_ = false;
  std::uint64_t until_probe_ = 1;
  // Gathering passes since the last probe (or the decision not to run one) that held max_hits hits
  // (1 without a hint) or more: the only rays whose bound could close, so culling could pay.
  std::uint64_t cull_rays_ = 0;
  // Whether the probe due now could find culling worth a depth-first first pass (kProbeShare).
  bool could_cull() const { return cull_rays_ * kProbeShare >= probe_every_; }
};

}  // namespace pierce
