// One-line notices of a slow step that is about to start (a GPU kernel
// compiled because the program cache has no entry for it), for a front end
// to show. The command line prints them on stderr; the library is silent
// until a handler is set. Safe to call from any thread.
#pragma once

#include <functional>
#include <string>

namespace prism {

using StatusHandler = std::function<void(const std::string& message)>;

// Replaces the handler (an empty one: silence).
void set_status_handler(StatusHandler handler);

// Passes `message` to the handler, if any.
void notify_status(const std::string& message);

}  // namespace prism
