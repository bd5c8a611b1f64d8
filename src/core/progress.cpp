#include "pss/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace pss {

bool Progress::enabled_for_terminal() { return isatty(STDOUT_FILENO) && isatty(STDERR_FILENO); }

Progress::Progress(std::string label, std::int64_t total)
    : label_(std::move(label)), total_(total), enabled_(enabled_for_terminal() && total > 0) {
  start_ = last_draw_ = std::chrono::steady_clock::now();
}

Progress::~Progress() {
  if (!enabled_) return;
  draw(total_);
  std::fputc('\n', stderr);
}

void Progress::advance(std::int64_t n) {
  const std::int64_t done = done_.fetch_add(n) + n;
  if (!enabled_) return;
  // Redraw at most ten times a second, by whichever thread gets the lock.
  std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (!lock) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  draw(done);
}

void Progress::draw(std::int64_t done) {
  const double fraction = total_ > 0 ? double(done) / double(total_) : 1.0;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int width = 30, filled = int(fraction * width + 0.5);
  std::fprintf(stderr, "\r%-22s [%.*s%*s] %5.1f%%  %.1fs", label_.c_str(), filled,
               "##############################", width - filled, "", 100.0 * fraction, seconds);
  std::fflush(stderr);
}

}  // namespace pss
