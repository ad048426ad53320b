#include "io/stop_signal.hpp"

#include <fmt/format.h>

#include <csignal>


namespace tidalcrust {
namespace {
volatile std::sig_atomic_t stop_flag = 0;
extern "C" void on_stop_signal(int) { stop_flag = 1; }
}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

bool stop_requested() { return stop_flag != 0; }

void throw_if_stopped(const char* what) {
  if (stop_flag != 0)
    throw Interrupted(fmt::format("stopped during {}; it keeps no checkpoint, so rerun the same command to measure "
                                  "it again (the relaxed body is kept)",
                                  what));
}

}  // namespace tidalcrust
