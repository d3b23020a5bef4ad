#include "hexdyn/core/cancel.hpp"

namespace hexdyn {
namespace {
thread_local const std::atomic<bool>* cancel_flag = nullptr;
}  // namespace

CancelScope::CancelScope(const std::atomic<bool>* flag) : previous_(cancel_flag) {
  cancel_flag = flag;
}

CancelScope::~CancelScope() { cancel_flag = previous_; }

void check_cancelled() {
  if (cancel_flag != nullptr && cancel_flag->load(std::memory_order_relaxed)) throw Cancelled();
}

}  // namespace hexdyn
