// Progress of long work, drawn on the terminal (stderr) only when stdout is a terminal, so
// pipes, files and CI logs stay clean. Safe to advance from many threads.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace pss {

class Progress {
 public:
  Progress(std::string label, std::int64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::int64_t n);
  static bool enabled_for_terminal();
  bool shown() const { return enabled_; }

 private:
  void draw(std::int64_t done);

  std::string label_;
  std::int64_t total_;
  std::atomic<std::int64_t> done_{0};
  bool enabled_;
  std::mutex draw_mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace pss
