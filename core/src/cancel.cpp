#include "prism/cancel.hpp"

#include <atomic>
#include <string>

namespace prism {

namespace {
// Written from signal handlers: only a lock-free atomic is safe there.
std::atomic<int> pending{0};
static_assert(std::atomic<int>::is_always_lock_free);
}  // namespace

Cancelled::Cancelled(int signal)
    : std::runtime_error("interrupted (signal " + std::to_string(signal) + ")"), signal_(signal) {}

// Out of line: anchors the vtable and type_info in libprism_core, as for errors.hpp.
Cancelled::~Cancelled() = default;

void request_cancel(int signal) noexcept {
  int none = 0;
  pending.compare_exchange_strong(none, signal);
}

int cancel_requested() noexcept { return pending.load(std::memory_order_relaxed); }

void clear_cancel() noexcept { pending.store(0); }

void throw_if_cancelled() {
  if (const int signal = cancel_requested()) throw Cancelled(signal);
}

}  // namespace prism
