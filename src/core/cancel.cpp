#include "pss/core/cancel.hpp"

namespace pss {

namespace {
thread_local const std::atomic<bool>* current = nullptr;
}  // namespace

const std::atomic<bool>* cancel_flag() { return current; }

CancelScope::CancelScope(const std::atomic<bool>* flag) : outer_(current) { current = flag; }

CancelScope::~CancelScope() { current = outer_; }

}  // namespace pss
