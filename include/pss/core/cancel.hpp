// Cooperative cancellation of host work: a caller that may give up on what it starts (the
// viewer's render thread, when the camera moves on) installs a flag for the work it runs on
// its thread; the CPU backend's parallel_for then skips the items of its chunks once the flag
// is set, and the caller discards the result. GPU launches run to their end.
#pragma once

#include <atomic>

namespace pss {

// The flag of the innermost CancelScope of this thread, or nullptr.
const std::atomic<bool>* cancel_flag();

class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>* flag);
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<bool>* outer_;
};

}  // namespace pss
