#pragma once
// The solver's process-wide settings as Python code shares them: the thread
// count a call asks for (threads=None: as the command line chooses), and one
// lock that lets only one call step at a time (the thread count, the float
// mode and the stop flag are per process, not per Simulation).
#include <mutex>

#include <pybind11/pybind11.h>

namespace mpsolid::python {

// threads=None: OMP_NUM_THREADS if set, else every core (choose_threads);
// otherwise 1 to 4096. A count over the cores warns (RuntimeWarning), as the
// command line does on stderr. Throws InputError for a bad count.
int chosen_threads(const pybind11::object& threads);

// Held (with the GIL released) by whatever steps or runs.
std::mutex& solver_mutex();

}  // namespace mpsolid::python
