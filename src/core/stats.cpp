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

double Stats::time(const std::string& phase) const {
  auto it = std::find_if(times_.begin(), times_.end(), [&](const auto& t) { return t.first == phase; });
  return it == times_.end() ? 0.0 : it->second;
}

nlohmann::json Stats::to_json() const {
  nlohmann::json j = values_;
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [phase, s] : times_) seconds[phase] = s;
  j["seconds"] = seconds;
  return j;
}

void Stats::write(const std::filesystem::path& path) const { write_text_file(path, to_json().dump(2) + "\n"); }

}  // namespace pss
