// What a run measured: the seconds and the peak resident memory of each named phase and the
// values worth reporting (counts, parameters), written by --stats as JSON so that every
// image is reproducible.
#pragma once

#include <chrono>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pss/core/memory.hpp"
#include "pss/core/progress.hpp"

namespace pss {

class Stats {
 public:
  void add_time(const std::string& phase, double seconds);
  double time(const std::string& phase) const;
  const std::vector<std::pair<std::string, double>>& times() const { return times_; }
  // The phase's peak resident bytes, the largest of its runs; a negative count is unknown.
  void add_peak(const std::string& phase, std::int64_t bytes);
  const std::vector<std::pair<std::string, std::int64_t>>& peaks() const { return peaks_; }

  nlohmann::json& values() { return values_; }
  const nlohmann::json& values() const { return values_; }

  nlohmann::json to_json() const;
  void write(const std::filesystem::path& path) const;

 private:
  std::vector<std::pair<std::string, double>> times_;  // in the order first recorded
  std::vector<std::pair<std::string, std::int64_t>> peaks_;
  nlohmann::json values_ = nlohmann::json::object();
};

// Adds the time from construction to destruction (or stop()) to a phase, and its peak
// resident memory over that time (memory.hpp), and shows the phase's progress
// (Progress::phase_begun); a phase whose steps a Progress counts passes announce = false.
class ScopedPhase {
 public:
  ScopedPhase(Stats& stats, std::string phase, bool announce = true)
      : stats_(&stats),
        phase_(std::move(phase)),
        announce_(announce),
        exceptions_at_start_(std::uncaught_exceptions()),
        peak_watch_(begin_peak_watch()),
        start_(std::chrono::steady_clock::now()) {
    if (announce_) Progress::phase_begun(phase_);
  }
  ~ScopedPhase() { stop(); }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;
  void stop() {
    if (!stats_) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    stats_->add_time(phase_, seconds);
    stats_->add_peak(phase_, end_peak_watch(peak_watch_));
    // While an error unwinds, the phase did not finish.
    if (announce_) Progress::phase_ended(phase_, seconds, std::uncaught_exceptions() == exceptions_at_start_);
    stats_ = nullptr;
  }

 private:
  Stats* stats_;
  std::string phase_;
  bool announce_;
  int exceptions_at_start_;
  int peak_watch_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace pss
