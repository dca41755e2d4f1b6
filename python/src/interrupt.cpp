#include "interrupt.hpp"

#include <csignal>

namespace prism::python {

namespace {

// Both only touched with the GIL held.
int depth = 0;            // calls in flight, on any thread
bool installed = false;   // whether the outermost call installed the handler
struct sigaction previous{};

extern "C" void cancel_on_sigint(int signal) { request_cancel(signal); }

bool python_handles_sigint() {
  struct sigaction current{};
  if (sigaction(SIGINT, nullptr, &current) != 0) return false;
  if (current.sa_flags & SA_SIGINFO) return true;
  return current.sa_handler != SIG_IGN && current.sa_handler != SIG_DFL;
}

}  // namespace

SigintCancels::SigintCancels() {
  if (depth++ > 0) return;
  clear_cancel();  // a request left by no one running is stale
  installed = python_handles_sigint();
  if (!installed) return;
  struct sigaction action{};
  action.sa_handler = cancel_on_sigint;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous);
}

SigintCancels::~SigintCancels() {
  if (--depth > 0) return;
  if (installed) sigaction(SIGINT, &previous, nullptr);
  installed = false;
  clear_cancel();
}

}  // namespace prism::python
