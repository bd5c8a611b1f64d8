// What a run measured: the seconds of each named phase and the values worth reporting
// (counts, parameters), written by --stats as JSON so that every image is reproducible.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace pss {

class Stats {
 public:
  void add_time(const std::string& phase, double seconds);
  double time(const std::string& phase) const;
  const std::vector<std::pair<std::string, double>>& times() const { return times_; }

  nlohmann::json& values() { return values_; }
  const nlohmann::json& values() const { return values_; }

  nlohmann::json to_json() const;
  void write(const std::filesystem::path& path) const;

 private:
  std::vector<std::pair<std::string, double>> times_;  // in the order first recorded
  nlohmann::json values_ = nlohmann::json::object();
};

// Adds the time from construction to destruction (or stop()) to a phase.
class ScopedPhase {
 public:
  ScopedPhase(Stats& stats, std::string phase)
      : stats_(&stats), phase_(std::move(phase)), start_(std::chrono::steady_clock::now()) {}
  ~ScopedPhase() { stop(); }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;
  void stop() {
    if (!stats_) return;
    stats_->add_time(phase_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    stats_ = nullptr;
  }

 private:
  Stats* stats_;
  std::string phase_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace pss
