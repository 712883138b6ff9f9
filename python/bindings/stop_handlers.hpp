#pragma once
// For the length of mpsolid.run / resume: the command line's stop handlers
// (SIGINT and SIGTERM ask the run loop to stop, with a checkpoint) in place
// of Python's, which come back, and the stop flag cleared, when it ends.
// Signals reach only the main thread's handlers in Python, so a call from
// another thread leaves the handlers alone (and cannot be stopped by Ctrl-C).
#include <csignal>

namespace mpsolid::python {

class StopHandlerScope {
 public:
  explicit StopHandlerScope(bool install);
  ~StopHandlerScope();
  StopHandlerScope(const StopHandlerScope&) = delete;
  StopHandlerScope& operator=(const StopHandlerScope&) = delete;

 private:
  bool installed_;
  struct sigaction saved_int_ {
  }, saved_term_{};
};

}  // namespace mpsolid::python
