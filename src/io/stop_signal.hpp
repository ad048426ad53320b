#pragma once
// SIGINT/SIGTERM turn into a flag the step loop polls, so a long stage stops at a step
// boundary, writes its checkpoint and exits with code 130.

#include <stdexcept>

namespace tidalcrust {

/// Stopped by SIGINT/SIGTERM in work that keeps no checkpoint (a validation measurement): the
/// message says what was lost and how to redo it. Exit code 130 (exit_interrupted), like a
/// stage's clean stop.
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Installs the handlers (idempotent). Until then the flag is never set.
void install_stop_handlers();
/// True once SIGINT or SIGTERM arrived.
bool stop_requested();
/// Throws Interrupted ("stopped during <what>; ...") once SIGINT or SIGTERM arrived: the poll of a
/// loop that writes no checkpoint (validate's measurements), so that a stop ends it at once.
void throw_if_stopped(const char* what);

}  // namespace tidalcrust
