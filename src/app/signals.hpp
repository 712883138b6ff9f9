#pragma once
// Ctrl-C (SIGINT) and SIGTERM ask a run to stop: the handler only records the
// signal; the run loop looks between chunks of steps, writes a checkpoint and
// the closing summary, and exits with kExitStopped. A second signal ends the
// process at once (the default action): the last checkpoint stays intact.
namespace mpsolid {

void install_stop_handlers();
// The signal that asked the run to stop, or 0.
int stop_signal();
inline bool stop_requested() {
  return stop_signal() != 0;
}
// Records a stop request as a signal would (tests).
void request_stop(int signal);
void clear_stop_request();

}  // namespace mpsolid
