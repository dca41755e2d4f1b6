// Ctrl-C during a render or trace. The GIL is released while the backend
// works, so Python's own SIGINT handler cannot run; instead, for the length
// of the call, a C handler asks the core to cancel (prism/cancel.hpp). The
// core stops between tiles and throws Cancelled, which becomes
// KeyboardInterrupt; the previous handler comes back and the core's cancel
// flag is cleared, so the next render starts clean.
#pragma once

#include "bindings.hpp"
#include "prism/cancel.hpp"

namespace prism::python {

// Installs the handler while Python handles SIGINT (not when SIGINT is
// ignored or left at its default); nests across threads. Made and destroyed
// with the GIL held.
class SigintCancels {
 public:
  SigintCancels();
  ~SigintCancels();
  SigintCancels(const SigintCancels&) = delete;
  SigintCancels& operator=(const SigintCancels&) = delete;
};

// Runs `work` without the GIL and with SIGINT cancelling it; raises
// KeyboardInterrupt when it was cancelled (or Ctrl-C came as it finished).
template <class Work>
auto interruptible(Work&& work) -> decltype(work()) {
  SigintCancels sigint;
  bool cancelled = false;
  decltype(work()) result{};
  try {
    py::gil_scoped_release release;
    result = work();
  } catch (const Cancelled&) {
    cancelled = true;
  }
  if (cancelled || cancel_requested() != 0) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  return result;
}

}  // namespace prism::python
