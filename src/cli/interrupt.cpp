#include "cli/interrupt.hpp"

#include <csignal>

namespace collide2d::cli {
namespace {

volatile std::sig_atomic_t received = 0;

// The first signal is recorded for the work to poll; a second one (the user
// pressing Ctrl-C again while the work finishes its step) kills at once.
extern "C" void record_signal(int sig) {
  if (received != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  received = sig;
}

}  // namespace

Interrupted::Interrupted(int sig) : std::runtime_error("interrupted by " + signal_name(sig)), signal(sig) {}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = record_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking read returns early
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() { return received; }

std::string signal_name(int sig) {
  if (sig == SIGINT) return "SIGINT";
  if (sig == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(sig);
}

}  // namespace collide2d::cli
