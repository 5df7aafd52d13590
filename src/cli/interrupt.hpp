// SIGINT and SIGTERM during long work (run, resume, replay, study, hardset):
// the handler only records the signal; the work polls it at safe points
// (between events, frames, queries) and stops by throwing Interrupted, so
// files are closed, partial outputs kept or removed on purpose, and the exit
// code is 128 + the signal number, as a shell would report for a kill.
#pragma once

#include <stdexcept>
#include <string>

namespace collide2d::cli {

struct Interrupted : std::runtime_error {
  int signal;
  explicit Interrupted(int sig);
};

// Installs the handlers (idempotent). Commands that never poll do not call it
// and keep the default action: they die at once, having nothing to save.
void install_interrupt_handlers();

// The signal received since install_interrupt_handlers(), or 0.
int interrupt_signal();

// Throws Interrupted if a signal has arrived.
inline void throw_if_interrupted() {
  if (const int sig = interrupt_signal()) throw Interrupted(sig);
}

// "SIGINT", "SIGTERM", else "signal N".
std::string signal_name(int sig);

// The exit code of work stopped by `sig`.
inline int interrupted_exit_code(int sig) { return 128 + sig; }

}  // namespace collide2d::cli
