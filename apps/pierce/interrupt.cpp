#include "interrupt.h"

#include <atomic>
#include <csignal>
#include <cstdio>

namespace pierce::cli {

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
struct sigaction g_previous;

extern "C" void on_sigint(int) {
  g_interrupted.store(true, std::memory_order_relaxed);
  // The next Ctrl-C kills the process, for when a stage cannot be interrupted.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(SIGINT, &dfl, nullptr);
}

}  // namespace

InterruptGuard::InterruptGuard() {
  g_interrupted = false;
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_previous);
}

InterruptGuard::~InterruptGuard() { sigaction(SIGINT, &g_previous, nullptr); }

bool interrupted() { return g_interrupted.load(std::memory_order_relaxed); }

int cancelled() {
  std::fputs("pierce: cancelled\n", stderr);
  return kExitCancelled;
}

}  // namespace pierce::cli
