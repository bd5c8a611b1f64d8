#include "pss/core/stats.hpp"

#include <algorithm>

#include "pss/io/output_file.hpp"

namespace pss {

void Stats::add_time(const std::string& phase, double seconds) {
  auto it = std::find_if(times_.begin(), times_.end(), [&](const auto& t) { return t.first == phase; });
  if (it == times_.end())
    times_.emplace_back(phase, seconds);
  else
    it->second += seconds;
}

void Stats::add_peak(const std::string& phase, std::int64_t bytes) {
  if (bytes < 0) return;
  auto it = std::find_if(peaks_.begin(), peaks_.end(), [&](const auto& p) { return p.first == phase; });
  if (it == peaks_.end())
    peaks_.emplace_back(phase, bytes);
  else
    it->second = std::max(it->second, bytes);
}

double Stats::time(const std::string& phase) const {
  auto it = std::find_if(times_.begin(), times_.end(), [&](const auto& t) { return t.first == phase; });
  return it == times_.end() ? 0.0 : it->second;
}

nlohmann::json Stats::to_json() const {
  nlohmann::json j = values_;
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [phase, s] : times_) seconds[phase] = s;
  j["seconds"] = seconds;
  // Each phase's peak resident bytes, and the whole run's so far as "total".
  nlohmann::json peak_bytes = nlohmann::json::object();
  for (const auto& [phase, bytes] : peaks_) peak_bytes[phase] = bytes;
  if (const std::int64_t total = process_peak_bytes(); total >= 0) peak_bytes["total"] = total;
  j["peak_bytes"] = peak_bytes;
  return j;
}

void Stats::write(const std::filesystem::path& path) const { write_text_file(path, to_json().dump(2) + "\n"); }

}  // namespace pss
