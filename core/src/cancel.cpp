#include "prism/cancel.hpp"

#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>
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

namespace {
std::atomic<int> uninterruptible{0};
static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");
}  // namespace

UninterruptibleWork::UninterruptibleWork() noexcept { uninterruptible.fetch_add(1); }
UninterruptibleWork::~UninterruptibleWork() { uninterruptible.fetch_sub(1); }
bool uninterruptible_work_running() noexcept { return uninterruptible.load(std::memory_order_relaxed) > 0; }

namespace {
std::mutex fault_mutex;
std::string fault_message;  // guarded by fault_mutex; set before pending becomes kFaultStop
}  // namespace

void request_stop_for_fault(const std::string& message) {
  std::lock_guard lock(fault_mutex);
  if (pending.load() != 0) return;
  fault_message = message;
  pending.store(kFaultStop);
}

void throw_if_cancelled() {
  const int signal = cancel_requested();
  if (signal == 0) return;
  if (signal != kFaultStop) throw Cancelled(signal);
  std::string message;
  {
    std::lock_guard lock(fault_mutex);
    message = fault_message;
    int fault = kFaultStop;
    pending.compare_exchange_strong(fault, 0);
  }
  throw RuntimeError(message);
}

namespace {
// A slot is claimed by a compare-exchange of `state` 0 -> 1 (being written),
// then 2 (live); the handler unlinks only live slots.
struct TemporarySlot {
  std::atomic<int> state{0};
  char name[kMaxTemporaryNameBytes];
};
TemporarySlot temporary_slots[kMaxTemporaryFiles];
}  // namespace

int register_temporary_file(const char* path) noexcept {
  const size_t length = std::strlen(path);
  if (length >= kMaxTemporaryNameBytes) return -1;
  for (int i = 0; i < kMaxTemporaryFiles; ++i) {
    int free_slot = 0;
    if (!temporary_slots[i].state.compare_exchange_strong(free_slot, 1)) continue;
    std::memcpy(temporary_slots[i].name, path, length + 1);
    temporary_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void unregister_temporary_file(int slot) noexcept {
  if (slot >= 0 && slot < kMaxTemporaryFiles) temporary_slots[slot].state.store(0);
}

void remove_temporary_files() noexcept {
  for (TemporarySlot& slot : temporary_slots)
    if (slot.state.load() == 2) ::unlink(slot.name);
}

}  // namespace prism
