#pragma once
// The one parallel loop of Pierce: independent work items (rays, samples, triangles, picture
// rows) spread over the cores with TBB, each worker thread with its own state (a HitIterator,
// scratch buffers, counters), progress reported with one signature and cancellation honoured
// between chunks. Each item writes its own result slot, so results do not depend on the thread
// count or the scheduling; sums over the workers' states are for statistics that commute.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstddef>

#include "pierce/progress.h"

namespace pierce {

// Progress and cancellation of one parallel run: workers add the items they finished; once the
// callback returns false, stopped() is true and the remaining work is skipped.
class ProgressTracker {
 public:
  ProgressTracker(std::size_t total, const Progress& progress) : total_(total), progress_(progress) {}
  bool stopped() const { return cancelled_.load(std::memory_order_relaxed); }
  void add(std::size_t finished) {
    const std::size_t done = done_.fetch_add(finished, std::memory_order_relaxed) + finished;
    if (progress_ && !progress_(done, total_)) cancelled_.store(true, std::memory_order_relaxed);
  }

 private:
  std::size_t total_;
  const Progress& progress_;
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> cancelled_{false};
};

// Calls body(state, i) for every i in [0, n), in chunks of about `grain` items; `state` is the
// calling thread's element of `states`. Returns false if the progress callback cancelled.
template <class State, class Body>
bool parallel_for_items(std::size_t n, std::size_t grain, tbb::enumerable_thread_specific<State>& states,
                        const Progress& progress, Body&& body) {
  ProgressTracker tracker(n, progress);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    if (tracker.stopped()) return;
    State& state = states.local();
    for (std::size_t i = r.begin(); i != r.end(); ++i) body(state, i);
    tracker.add(r.size());
  });
  return !tracker.stopped();
}

}  // namespace pierce
