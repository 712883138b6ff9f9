// _mpsolid: the solver as a Python extension (the package mpsolid re-exports
// it; docs/python.md). Bad input is mpsolid.InputError (a ValueError) with the
// command line's message; std::bad_alloc is MemoryError, other failures
// RuntimeError (pybind11's translations).
#include <pybind11/pybind11.h>

#include "python/bindings/bindings.hpp"
#include "src/app/version.hpp"
#include "src/core/types.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_mpsolid, m) {
  using namespace mpsolid;
  m.doc() = "mpsolid: elastic MPS solver (in plane strain or in space)";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  python::bind_case(m);
  python::bind_simulation(m);
  python::bind_run(m);
  m.def(
      "version",
      [] {
        const VersionFacts f = version_facts();
        py::dict d;
        d["version"] = f.version;
        d["git_commit"] = f.git_commit;
        d["compiler"] = f.compiler;
        d["build_type"] = f.build_type;
        d["cxx_flags"] = f.cxx_flags;
        d["openmp"] = f.openmp;
        d["cores"] = f.cores;
        d["text"] = version_text();
        return d;
      },
      "What `mpsolid --version` says, field by field ('text': all of it).");
  m.attr("__version__") = version_facts().version;
}
