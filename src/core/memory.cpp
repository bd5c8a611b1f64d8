#include "pss/core/memory.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <utility>
#include <vector>

#include <unistd.h>

namespace pss {
namespace {

// VmHWM of /proc/self/status in bytes: the peak resident size since the process began or
// the mark was last reset; -1 where there is no such file (not Linux).
std::int64_t high_water_mark() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return -1;
  char line[256];
  std::int64_t kib = -1;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) {
      long long value = 0;
      if (std::sscanf(line + 6, "%lld", &value) == 1) kib = value;
      break;
    }
  std::fclose(f);
  return kib < 0 ? -1 : kib * 1024;
}

// Writing 5 to clear_refs sets the mark to the current resident size (Linux 4.0).
bool reset_high_water_mark() {
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool written = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && written;
}

struct Watches {
  std::mutex mutex;
  std::vector<std::pair<int, std::int64_t>> open;  // each open watch's id and peak so far
  int next = 0;
  bool on = false;
  std::int64_t process = -1;
  bool resettable = true;

  // What the mark holds now, into every open watch and the process's peak.
  void fold() {
    const std::int64_t mark = high_water_mark();
    for (auto& [id, peak] : open) peak = std::max(peak, mark);
    process = std::max(process, mark);
  }
};

Watches& watches() {
  static Watches w;
  return w;
}

}  // namespace

void watch_peak_memory(bool on) {
  Watches& w = watches();
  std::lock_guard lock(w.mutex);
  w.on = on;
}

int begin_peak_watch() {
  Watches& w = watches();
  std::lock_guard lock(w.mutex);
  if (!w.on) return -1;
  w.fold();
  w.resettable = w.resettable && reset_high_water_mark();
  const int id = w.next++;
  w.open.emplace_back(id, -1);
  w.fold();
  return id;
}

std::int64_t end_peak_watch(int id) {
  if (id < 0) return -1;
  Watches& w = watches();
  std::lock_guard lock(w.mutex);
  w.fold();
  const auto it = std::find_if(w.open.begin(), w.open.end(), [&](const auto& o) { return o.first == id; });
  if (it == w.open.end()) return -1;
  const std::int64_t peak = it->second;
  w.open.erase(it);
  return w.resettable ? peak : -1;
}

std::int64_t process_peak_bytes() {
  Watches& w = watches();
  std::lock_guard lock(w.mutex);
  if (!w.on) return -1;
  w.fold();
  return w.process;
}

std::int64_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  std::int64_t bytes = pages > 0 && page > 0 ? std::int64_t(pages) * page : -1;
  // cgroup v2's limit: a number of bytes, or "max" for none.
  if (std::FILE* f = std::fopen("/sys/fs/cgroup/memory.max", "r")) {
    long long limit = 0;
    if (std::fscanf(f, "%lld", &limit) == 1 && limit > 0 && (bytes < 0 || limit < bytes)) bytes = limit;
    std::fclose(f);
  }
  return bytes;
}

}  // namespace pss
