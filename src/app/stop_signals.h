// SIGINT and SIGTERM as a request to stop: the runner finishes the current step, flushes its output,
// prints its summary and exits with 128 + the signal number (130 for SIGINT, 143 for SIGTERM).
#pragma once

namespace sph {

// Installs the handlers (once per process). A signal that was ignored when the program started (for
// example SIGINT for a background job of a script) stays ignored. The handler is one-shot: a second signal
// of the same kind ends the program at once, as without the handler.
void install_stop_handlers();

// The signal number received since install_stop_handlers(), or 0.
int stop_requested();

// "SIGINT" or "SIGTERM" (the signals handled here), "signal" for any other number.
const char* stop_signal_name(int signal_number);

}  // namespace sph
