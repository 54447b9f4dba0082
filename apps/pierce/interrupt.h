#pragma once
// Ctrl-C as a request: while an InterruptGuard lives, SIGINT only sets a flag that long loops
// poll (a second Ctrl-C terminates as usual). Lets commands stop cleanly and remove partial output.
namespace pierce::cli {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// True once SIGINT arrived under a guard. Safe from any thread.
bool interrupted();

// Exit code of a command stopped by Ctrl-C (128 + SIGINT, as shells report it).
inline constexpr int kExitCancelled = 130;

// Tells the user the command stopped ("pierce: cancelled" on stderr); returns kExitCancelled.
int cancelled();

}  // namespace pierce::cli
