#include "progress.h"

#include <unistd.h>

#include <cstdio>

#include "interrupt.h"

namespace pierce::cli {

namespace {
constexpr std::int64_t kDelayNs = 1'000'000'000;   // unforced bars wait for runs over ~1 s
constexpr std::int64_t kPeriodNs = 100'000'000;    // then redraw at most 10 times a second
constexpr int kWidth = 30;
}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total, bool force)
    : label_(std::move(label)),
      total_(total),
      enabled_(force || isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()),
      next_draw_ns_(force ? 0 : kDelayNs) {}

bool ProgressBar::update(std::size_t done) {
  if (enabled_) {
    const std::int64_t now =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
    std::int64_t due = next_draw_ns_.load(std::memory_order_relaxed);
    if (now >= due && next_draw_ns_.compare_exchange_strong(due, now + kPeriodNs)) {
      std::lock_guard lock(draw_mutex_);
      draw(done);
    }
  }
  return !interrupted();
}

void ProgressBar::draw(std::size_t done) {
  // Callbacks from several threads may arrive out of order: never move backwards.
  if (done < best_) done = best_;
  best_ = done;
  const double frac = total_ ? double(done) / double(total_) : 1.0;
  const int filled = int(frac * kWidth);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '-';
  bar[kWidth] = 0;
  std::fprintf(stderr, "\r%s [%s] %3d%% %zu/%zu rays  %.1f s", label_.c_str(), bar, int(frac * 100), done, total_,
               secs);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  std::lock_guard lock(draw_mutex_);
  if (!drawn_) return;
  if (!interrupted()) draw(total_);
  std::fputc('\n', stderr);
  drawn_ = false;
}

bool LazyProgressBar::update(const std::string& label, std::size_t done, std::size_t total) {
  ProgressBar* bar;
  {
    std::lock_guard lock(mutex_);
    if (!bar_ || label != current_) {
      if (bar_) bar_->finish();
      bar_ = std::make_unique<ProgressBar>(label, total, force_);
      current_ = label;
    }
    bar = bar_.get();
  }
  return bar->update(done);
}

void LazyProgressBar::finish() {
  std::lock_guard lock(mutex_);
  if (bar_) bar_->finish();
}

}  // namespace pierce::cli
