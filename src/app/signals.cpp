#include "src/app/signals.hpp"

#include <csignal>

namespace mpsolid {

namespace {
volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int signal) {
  g_stop_signal = signal;
}
}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // A second signal takes the default action; interrupted system calls go on.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int stop_signal() {
  return g_stop_signal;
}
void request_stop(int signal) {
  g_stop_signal = signal;
}
void clear_stop_request() {
  g_stop_signal = 0;
}

}  // namespace mpsolid
