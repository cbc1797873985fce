#include "lagmb/interrupt.hpp"

#include <chrono>

namespace lagmb {

namespace {

// The one thread-local state of the core, and not one a model evaluation
// reads: the interrupt check a caller (the Python binding's Ctrl-C) installs
// for the calls it makes on this thread. It reaches the integrators' loops
// and Newton iterations without a callback passed through every solver and
// SUNDIALS; what a run computes never depends on it.
thread_local InterruptScope* current = nullptr;
thread_local std::function<void()>* current_check = nullptr;
thread_local std::chrono::steady_clock::time_point last_poll{};

}  // namespace

InterruptScope::InterruptScope(std::function<void()> check) : check_(std::move(check)), outer_(current) {
  current = this;
  current_check = &check_;
}

InterruptScope::~InterruptScope() {
  current = outer_;
  current_check = outer_ ? &outer_->check_ : nullptr;
}

void poll_interrupt() {
  if (!current_check) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_poll < std::chrono::milliseconds(20)) return;
  last_poll = now;
  (*current_check)();
}

}  // namespace lagmb
