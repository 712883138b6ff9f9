#include "python/bindings/stop_handlers.hpp"

#include "src/app/signals.hpp"

namespace mpsolid::python {

StopHandlerScope::StopHandlerScope(bool install) : installed_(install) {
  clear_stop_request();
  if (!installed_) return;
  sigaction(SIGINT, nullptr, &saved_int_);
  sigaction(SIGTERM, nullptr, &saved_term_);
  install_stop_handlers();
}

StopHandlerScope::~StopHandlerScope() {
  if (installed_) {
    sigaction(SIGINT, &saved_int_, nullptr);
    sigaction(SIGTERM, &saved_term_, nullptr);
  }
  clear_stop_request();  // the next run starts unstopped
}

}  // namespace mpsolid::python
