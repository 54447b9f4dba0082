#pragma once
// A progress bar on stderr for long runs: drawn once a run passes ~1 s when stderr is a terminal,
// or from the start when forced (--progress). update() may be called from any thread.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>

namespace pierce::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total, bool force);
  ~ProgressBar() { finish(); }
  // Records `done` units; returns false once the user pressed Ctrl-C (see interrupt.h), which is
  // what trace_batch's progress callback needs to cancel.
  bool update(std::size_t done);
  // Ends the bar's line if it was drawn.
  void finish();

 private:
  void draw(std::size_t done);

  std::string label_;
  std::size_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<std::int64_t> next_draw_ns_;  // since start_
  std::mutex draw_mutex_;
  bool drawn_ = false;
  std::size_t best_ = 0;
};

// A bar for work whose size the analysis reports with its first progress call, as the analyses'
// `(done, total)` callbacks do: started on that call (from whichever thread makes it), restarted
// when the label changes (one bar per pass). operator() is such a callback.
class LazyProgressBar {
 public:
  LazyProgressBar(std::string label, bool force) : label_(std::move(label)), force_(force) {}
  bool operator()(std::size_t done, std::size_t total) { return update(label_, done, total); }
  bool update(const std::string& label, std::size_t done, std::size_t total);
  void finish();

 private:
  std::string label_, current_;
  bool force_;
  std::mutex mutex_;
  std::unique_ptr<ProgressBar> bar_;
};

}  // namespace pierce::cli
