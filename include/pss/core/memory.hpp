// Resident memory as the kernel counts it (Linux /proc): the peak of each phase of a run,
// which --stats records (issue 28). The kernel keeps one high-water mark per process; a
// phase resets it when it begins, having folded what it held into the phases still open
// around it, so nested phases each get their own peak.
#pragma once

#include <cstdint>
#include <vector>

namespace pss {

// Whether phases watch their peaks: off until a run asks (--stats). A watch resets the
// process's mark, which getrusage and /usr/bin/time then report as the peak since the last
// phase began; and it costs a read and a write of /proc at each phase (each viewer frame).
void watch_peak_memory(bool on);

// Opens a phase's watch: its peak counts from now (-1, no watch, while watching is off).
int begin_peak_watch();
// Closes it: the peak resident bytes since begin_peak_watch(id); -1 for no watch, or where
// this system neither tells the resident size nor lets the mark be reset.
std::int64_t end_peak_watch(int id);
// The peak resident bytes of the whole process so far; -1 where unknown or not watched.
std::int64_t process_peak_bytes();

// The memory this process may take in all: the machine's RAM, or its control group's limit
// where that is lower (a container's); -1 where neither is known.
std::int64_t physical_memory_bytes();

// Frees a vector's buffer now (clear() keeps it): a long run hands back what each step is
// done with before the next allocates.
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

}  // namespace pss
