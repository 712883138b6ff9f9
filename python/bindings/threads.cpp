#include "python/bindings/threads.hpp"

#include <fmt/format.h>

#include "src/app/thread_choice.hpp"
#include "src/core/parallel.hpp"
#include "src/core/types.hpp"

namespace py = pybind11;

namespace mpsolid::python {

int chosen_threads(const py::object& threads) {
  int requested = 0;
  if (!threads.is_none()) {
    const long long n = threads.cast<long long>();
    // The command line's --threads range (CLI::Range(1, 4096)).
    if (n < 1 || n > 4096)
      throw InputError(fmt::format("threads = {}: expected a whole number from 1 to 4096", n));
    requested = static_cast<int>(n);
  }
  const ThreadChoice choice = choose_threads(requested, available_cores());
  // A warning filter may turn the warning into an exception.
  if (!choice.warning.empty() && PyErr_WarnEx(PyExc_RuntimeWarning, choice.warning.c_str(), 1) != 0)
    throw py::error_already_set();
  return choice.threads;
}

std::mutex& solver_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace mpsolid::python
