#include "PierceVTKProgress.h"

#include <vtkAlgorithm.h>

namespace pierce_vtk {

ProgressBridge::ProgressBridge(vtkAlgorithm* algorithm, double begin, double end)
    : algorithm_(algorithm), owner_(std::this_thread::get_id()), begin_(begin), end_(end) {}

bool ProgressBridge::Report(std::size_t done, std::size_t total) {
  if (std::this_thread::get_id() == owner_) {
    const double fraction = total > 0 ? double(done) / double(total) : 1.0;
    const double amount = begin_ + (end_ - begin_) * fraction;
    if (amount - last_ >= 0.01 || fraction >= 1.0) {  // observers may be slow: at most ~100 calls
      last_ = amount;
      algorithm_->UpdateProgress(amount);
    }
    CheckAbort();
  }
  return !Aborted();
}

std::function<bool(std::size_t, std::size_t)> ProgressBridge::Callback() {
  return [this](std::size_t done, std::size_t total) { return Report(done, total); };
}

std::function<bool(std::size_t)> ProgressBridge::BatchCallback(std::size_t total) {
  return [this, total](std::size_t done) { return Report(done, total); };
}

bool ProgressBridge::CheckAbort() {
  if (algorithm_->CheckAbort() || algorithm_->GetAbortExecute()) aborted_.store(true, std::memory_order_relaxed);
  return Aborted();
}

}  // namespace pierce_vtk
