// Progress of long work on stderr, for a person at a terminal or a log file
// (ProgressMode). A Progress counts the steps of one phase and is safe to advance from many
// threads; a phase without steps announces itself through ScopedPhase (stats.hpp).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace pss {

enum class ProgressMode : unsigned char {
  automatic,  // a bar while stderr is a terminal, else nothing: pipes and test logs stay clean
  always,     // a bar on a terminal, else lines a log can read: one when a phase begins, one
              // when it ends, and one per 10 % after its first second
  never,
};

// Process-wide; the CLI's --progress sets it, the viewer turns it off.
void set_progress_mode(ProgressMode mode);
ProgressMode progress_mode();

class Progress {
 public:
  Progress(std::string label, std::int64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::int64_t n);
  // More steps than the phase began with (a mesh's band, found wave by wave): one phase, whose
  // share done falls back; no 10 % line is written twice.
  void add_total(std::int64_t n);
  bool shown() const { return style_ != Style::none; }

  // How the current mode shows progress where stderr is now.
  enum class Style : unsigned char { none, bar, lines };
  static Style style();

  // What ScopedPhase says of a phase without steps: on a terminal its name while it runs
  // (erased when it ends), in a log a line when it begins and, if it finished, one with its time.
  static void phase_begun(const std::string& label);
  static void phase_ended(const std::string& label, double seconds, bool finished = true);

 private:
  void draw_bar(std::int64_t done);
  void write_lines(std::int64_t done);
  double elapsed() const;

  std::string label_;
  std::atomic<std::int64_t> total_;
  std::atomic<std::int64_t> done_{0};
  Style style_;
  int exceptions_at_start_;
  int deciles_written_ = 0;
  std::mutex draw_mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace pss
