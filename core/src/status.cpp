#include "prism/status.hpp"

#include <mutex>

namespace prism {

namespace {
std::mutex status_mutex;
StatusHandler status_handler;
}  // namespace

void set_status_handler(StatusHandler handler) {
  std::lock_guard lock(status_mutex);
  status_handler = std::move(handler);
}

void notify_status(const std::string& message) {
  std::lock_guard lock(status_mutex);  // one notice at a time on the screen
  if (status_handler) status_handler(message);
}

}  // namespace prism
