#include "pss/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>

namespace pss {
namespace {

std::atomic<ProgressMode> mode{ProgressMode::automatic};
constexpr double kQuietSeconds = 1.0;

// "3.8 s left" once the rate is known (a few per cent done), else nothing.
std::string time_left(double fraction, double seconds) {
  if (fraction < 0.02 || fraction >= 1 || seconds < 0.2) return "";
  char text[48];
  std::snprintf(text, sizeof text, ", %.1f s left", seconds * (1 - fraction) / fraction);
  return text;
}

}  // namespace

void set_progress_mode(ProgressMode m) { mode.store(m); }
ProgressMode progress_mode() { return mode.load(); }

Progress::Style Progress::style() {
  const ProgressMode m = mode.load();
  if (m == ProgressMode::never) return Style::none;
  if (isatty(STDERR_FILENO)) return Style::bar;
  return m == ProgressMode::always ? Style::lines : Style::none;
}

void Progress::phase_begun(const std::string& label) {
  switch (style()) {
    case Style::bar: std::fprintf(stderr, "\r%s ...\033[K", label.c_str()); break;
    case Style::lines: std::fprintf(stderr, "%s ...\n", label.c_str()); break;
    case Style::none: return;
  }
  std::fflush(stderr);
}

void Progress::phase_ended(const std::string& label, double seconds, bool finished) {
  switch (style()) {
    case Style::bar: std::fputs("\r\033[K", stderr); break;  // an error message may follow on this line
    case Style::lines:
      if (!finished) return;
      std::fprintf(stderr, "%s: done in %.2f s\n", label.c_str(), seconds);
      break;
    case Style::none: return;
  }
  std::fflush(stderr);
}

Progress::Progress(std::string label, std::int64_t total)
    : label_(std::move(label)),
      total_(total),
      style_(total > 0 ? style() : Style::none),
      exceptions_at_start_(std::uncaught_exceptions()) {
  start_ = last_draw_ = std::chrono::steady_clock::now();
  if (style_ == Style::lines) {
    std::fprintf(stderr, "%s: %lld steps ...\n", label_.c_str(), (long long)total_);
    std::fflush(stderr);
  }
}

Progress::~Progress() {
  // While an error unwinds the work did not finish: no 100 %, no "done".
  const bool finished = std::uncaught_exceptions() == exceptions_at_start_;
  if (style_ == Style::bar) {
    if (finished) draw_bar(total_);
    std::fputc('\n', stderr);
  } else if (style_ == Style::lines && finished) {
    std::fprintf(stderr, "%s: done in %.2f s\n", label_.c_str(), elapsed());
  }
  std::fflush(stderr);
}

void Progress::add_total(std::int64_t n) { total_.fetch_add(n); }

void Progress::advance(std::int64_t n) {
  const std::int64_t done = done_.fetch_add(n) + n;
  if (style_ == Style::lines) {
    // A line per 10 % crossed, in order, whichever thread crosses it.
    const std::int64_t total = total_.load();
    if (done * 10 / total == (done - n) * 10 / total) return;
    std::lock_guard lock(draw_mutex_);
    write_lines(done);
  } else if (style_ == Style::bar) {
    // Redraw at most ten times a second, by whichever thread gets the lock.
    std::unique_lock lock(draw_mutex_, std::try_to_lock);
    if (!lock) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw_bar(done);
  }
}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::write_lines(std::int64_t done) {
  // 100 % is the "done" line the destructor writes; a phase shorter than a second needs no
  // more than its first and last lines.
  const int decile = int(std::min<std::int64_t>(done * 10 / total_.load(), 9));
  const double seconds = elapsed();
  if (seconds < kQuietSeconds) {
    deciles_written_ = decile;
    return;
  }
  for (; deciles_written_ < decile; ++deciles_written_) {
    const double fraction = (deciles_written_ + 1) / 10.0;
    std::fprintf(stderr, "%s: %d%% after %.2f s%s\n", label_.c_str(), (deciles_written_ + 1) * 10, seconds,
                 time_left(fraction, seconds).c_str());
  }
  std::fflush(stderr);
}

void Progress::draw_bar(std::int64_t done) {
  const double fraction = double(done) / double(total_.load());
  const double seconds = elapsed();
  const int width = 30, filled = int(fraction * width + 0.5);
  std::fprintf(stderr, "\r%-22s [%.*s%*s] %5.1f%%  %.1f s%s\033[K", label_.c_str(), filled,
               "##############################", width - filled, "", 100.0 * fraction, seconds,
               time_left(fraction, seconds).c_str());
  std::fflush(stderr);
}

}  // namespace pss
