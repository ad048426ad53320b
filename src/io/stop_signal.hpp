#pragma once
// SIGINT/SIGTERM turn into a flag the step loop polls, so a long stage stops at a step
// boundary, writes its checkpoint and exits with code 130.

namespace tidalcrust {

/// Installs the handlers (idempotent). Until then the flag is never set.
void install_stop_handlers();
/// True once SIGINT or SIGTERM arrived.
bool stop_requested();

}  // namespace tidalcrust
