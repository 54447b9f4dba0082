#include "progress.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace pierce::py {

namespace {
constexpr auto kPollInterval = std::chrono::milliseconds(100);

// Calls the Python callback; false means "cancel". Needs the GIL.
bool call_callback(const pyb::object& callback, std::size_t done, std::size_t total) {
  if (callback.is_none()) return true;
  const pyb::object r = callback(done, total);
  return r.is_none() || PyObject_IsTrue(r.ptr()) != 0;
}
}  // namespace

void run_with_progress(const pyb::object& callback, CancelToken* token, std::size_t total,
                       const std::function<void(ProgressState&)>& work) {
  if (!callback.is_none() && !PyCallable_Check(callback.ptr()))
    throw pyb::type_error("progress must be a callable (done, total) -> bool, or None");
  ProgressState state(total);
  if (token && token->cancelled()) throw Cancelled("cancelled before start");

  std::exception_ptr work_error;    // thrown by the C++ work
  std::exception_ptr python_error;  // raised by the callback or by a signal handler
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  {
    pyb::gil_scoped_release no_gil;
    std::thread worker([&] {
      try {
        work(state);
      } catch (...) {
        work_error = std::current_exception();
      }
      {
        std::lock_guard lock(mutex);
        finished = true;
      }
      finished_cv.notify_all();
    });
    for (;;) {
      {
        std::unique_lock lock(mutex);
        if (finished_cv.wait_for(lock, kPollInterval, [&] { return finished; })) break;
      }
      if (token && token->cancelled()) state.cancel();
      if (state.cancelled() || python_error) continue;  // wait for the worker to notice
      pyb::gil_scoped_acquire gil;
      try {
        if (PyErr_CheckSignals() != 0) throw pyb::error_already_set();
        if (!call_callback(callback, state.done(), state.total())) state.cancel();
      } catch (...) {
        python_error = std::current_exception();
        state.cancel();
      }
    }
    worker.join();
  }
  if (python_error) std::rethrow_exception(python_error);
  if (token && token->cancelled()) state.cancel();
  if (state.cancelled()) throw Cancelled("cancelled");
  if (work_error) std::rethrow_exception(work_error);
  // Final report, so a progress bar reaches its end.
  call_callback(callback, state.total(), state.total());
}

}  // namespace pierce::py
