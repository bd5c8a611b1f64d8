#include "pss/core/stats.hpp"

#include <algorithm>

#include "pss/io/output_file.hpp"

namespace pss {

namespace {

// The value of `phase` in `entries`, in the order first recorded: `value` when it has none,
// else `combine(old, value)`.
template <class T, class Combine>
void record(std::vector<std::pair<std::string, T>>& entries, const std::string& phase, T value, Combine combine) {
  auto it = std::find_if(entries.begin(), entries.end(), [&](const auto& e) { return e.first == phase; });
  if (it == entries.end())
    entries.emplace_back(phase, value);
  else
    it->second = combine(it->second, value);
}

}  // namespace

void Stats::add_time(const std::string& phase, double seconds) {
  record(times_, phase, seconds, [](double a, double b) { return a + b; });
}

void Stats::add_peak(const std::string& phase, std::int64_t bytes) {
  if (bytes >= 0) record(peaks_, phase, bytes, [](std::int64_t a, std::int64_t b) { return std::max(a, b); });
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
