#pragma once
// Bridges the analyses' progress callbacks, which run on TBB worker threads, to a VTK algorithm.
// Only the thread that runs RequestData calls UpdateProgress and CheckAbort (observers such as
// ParaView's progress bar are not thread-safe); the workers see an abort through an atomic flag.
// TBB lets the calling thread take part in the work, so it reports regularly.
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>

class vtkAlgorithm;

namespace pierce_vtk {

class ProgressBridge {
 public:
  // The analysis' progress [0, 1] is mapped onto [begin, end] of the algorithm's progress.
  explicit ProgressBridge(vtkAlgorithm* algorithm, double begin = 0.0, double end = 1.0);
  ProgressBridge(const ProgressBridge&) = delete;
  ProgressBridge& operator=(const ProgressBridge&) = delete;

  // Progress callback: false once the algorithm was asked to abort.
  bool Report(std::size_t done, std::size_t total);
  // Callbacks referring to this bridge, for the analyses and for trace_batch.
  std::function<bool(std::size_t, std::size_t)> Callback();
  std::function<bool(std::size_t)> BatchCallback(std::size_t total);

  // From the RequestData thread, between phases: true when an abort was requested.
  bool CheckAbort();
  bool Aborted() const { return aborted_.load(std::memory_order_relaxed); }
  void SetRange(double begin, double end) { begin_ = begin, end_ = end, last_ = -1.0; }

 private:
  vtkAlgorithm* algorithm_;
  std::thread::id owner_;
  double begin_, end_;
  double last_ = -1.0;  // last value passed to UpdateProgress (owner thread only)
  std::atomic<bool> aborted_{false};
};

}  // namespace pierce_vtk
