// Stopping a render or trace from outside, e.g. from `prism`'s SIGINT and
// SIGTERM handlers. The request is one process-wide flag: setting it is a
// lock-free atomic store, so a signal handler may do it. Renders and traces
// check it between tiles (CPU) or dispatches (GPU) and then throw Cancelled;
// image_io checks it before renaming a finished temporary file over the
// target, so an interrupted run never replaces an older output.
#pragma once

#include <stdexcept>

#include "prism/errors.hpp"

namespace prism {

// Thrown by whatever stopped because cancellation was requested. Not a
// RuntimeError: code that turns failures into a report (conform, plugin
// check) must let it through.
class PRISM_CORE_API Cancelled : public std::runtime_error {
 public:
  explicit Cancelled(int signal);
  ~Cancelled() override;
  int signal() const { return signal_; }  // what request_cancel was given

 private:
  int signal_;
};

// Async-signal-safe. `signal` is reported back by Cancelled::signal() (the
// first request wins); pass a positive number, e.g. the signal's.
void request_cancel(int signal) noexcept;
// The first request's number, 0 when none is pending.
int cancel_requested() noexcept;
// Forgets a request (for a program that carries on after a cancelled run).
void clear_cancel() noexcept;
// Throws Cancelled when a request is pending.
void throw_if_cancelled();

}  // namespace prism
