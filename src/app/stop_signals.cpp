#include "stop_signals.h"

#include <signal.h>  // sigaction (POSIX)

namespace sph {
namespace {

// Only a lock-free sig_atomic_t may be written from a signal handler.
volatile sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int signal_number) { g_stop_signal = signal_number; }

void install(int signal_number) {
  struct sigaction old {};
  if (sigaction(signal_number, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESTART: a write interrupted by the signal continues instead of failing with EINTR (which would be
  // reported as an output error); SA_RESETHAND: a second signal is not caught.
  action.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

void install_stop_handlers() {
  install(SIGINT);
  install(SIGTERM);
}

int stop_requested() { return int(g_stop_signal); }

const char* stop_signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "signal";
  }
}

}  // namespace sph
