// Stopping a render or trace from outside, e.g. from `prism`'s SIGINT and
// SIGTERM handlers. The request is one process-wide flag: setting it is a
// lock-free atomic store, so a signal handler may do it. Renders and traces
// check it between tiles (CPU) or dispatches (GPU) and then throw Cancelled;
// image_io checks it before renaming a finished temporary file over the
// target, so an interrupted run never replaces an older output.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

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
// The first request's number, 0 when none is pending, kFaultStop when a
// plugin fault stopped the run (request_stop_for_fault).
int cancel_requested() noexcept;
// Forgets a request (for a program that carries on after a cancelled run).
void clear_cancel() noexcept;
// Throws Cancelled when a request is pending; for a fault, RuntimeError with
// its message (and the fault is forgotten: the next run starts clean).
void throw_if_cancelled();

// Work that cannot look at a cancel request for seconds (a driver compiling
// a GPU kernel) holds one of these while it runs. A program's interrupt
// handler may then end the process at once rather than wait for a check
// that will not come (prism does: nothing is half-written during a
// compile). uninterruptible_work_running() is async-signal-safe.
class PRISM_CORE_API UninterruptibleWork {
 public:
  UninterruptibleWork() noexcept;
  ~UninterruptibleWork();
  UninterruptibleWork(const UninterruptibleWork&) = delete;
  UninterruptibleWork& operator=(const UninterruptibleWork&) = delete;
};
bool uninterruptible_work_running() noexcept;

// Temporary files that must not outlive the process: a program's deadline
// handler (prism's, after a signal the run did not stop for) removes them
// with remove_temporary_files(). The names live in a fixed table, so all
// three are async-signal-safe. A name that does not fit (too long, table
// full) is not registered: the normal clean-up still covers it.
inline constexpr int kMaxTemporaryFiles = 16;
inline constexpr size_t kMaxTemporaryNameBytes = 4096;
int register_temporary_file(const char* path) noexcept;  // its slot, -1 when not registered
void unregister_temporary_file(int slot) noexcept;       // -1: nothing
void remove_temporary_files() noexcept;

// A plugin fault found where no exception may be thrown (inside Embree's
// callbacks, which swallow exceptions): it stops the run like a cancel
// request, and throw_if_cancelled() then throws it as a RuntimeError
// (exit status 1). The first request wins. Process-wide, like the signal:
// renders running at the same time in one process stop too.
inline constexpr int kFaultStop = -1;
void request_stop_for_fault(const std::string& message);

}  // namespace prism
