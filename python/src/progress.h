#pragma once
// Long C++ calls run on a worker thread without the GIL; the calling thread wakes a few times
// a second to report progress to Python (with the GIL, on the caller's own thread, so GUI
// callbacks are safe), to honour cancellation and Ctrl-C.
#include <pybind11/pybind11.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <stdexcept>

namespace pierce::py {

namespace pyb = pybind11;

// Raised in Python as pierce.Cancelled when a progress callback returned False or a
// CancelToken was set.
struct Cancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Thread-safe flag Python code can set from anywhere (another thread, a GUI button).
class CancelToken {
 public:
  void cancel() { flag_.store(true); }
  void reset() { flag_.store(false); }
  bool cancelled() const { return flag_.load(); }

 private:
  std::atomic<bool> flag_{false};
};

// What the worker sees: report(done) records progress and returns false once cancelled.
class ProgressState {
 public:
  explicit ProgressState(std::size_t total) : total_(total) {}
  bool report(std::size_t done) {
    done_.store(done, std::memory_order_relaxed);
    return !cancel_.load(std::memory_order_relaxed);
  }
  // For work whose size is known only once it runs (the analyses' Progress callbacks).
  bool report(std::size_t done, std::size_t total) {
    total_.store(total, std::memory_order_relaxed);
    return report(done);
  }
  bool cancelled() const { return cancel_.load(std::memory_order_relaxed); }
  void cancel() { cancel_.store(true); }
  std::size_t done() const { return done_.load(std::memory_order_relaxed); }
  std::size_t total() const { return total_.load(std::memory_order_relaxed); }

 private:
  std::atomic<std::size_t> total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> cancel_{false};
};

// Runs work(state) on a worker thread. Must be called with the GIL held. `callback` (None or a
// callable (done, total) -> bool|None) is called on this thread; returning False cancels, and an
// exception it raises cancels and propagates. Throws Cancelled when cancelled (by callback,
// token or Ctrl-C: KeyboardInterrupt propagates as itself), else rethrows what work threw.
// `total` is the initial total (0 when unknown; the work may update it through report()).
void run_with_progress(const pyb::object& callback, CancelToken* token, std::size_t total,
                       const std::function<void(ProgressState&)>& work);

}  // namespace pierce::py
