// mpsolid.Case: a case file (or TOML text) with --set overrides.
#include <pybind11/stl.h>

#include "python/bindings/bindings.hpp"
#include "python/bindings/case_handle.hpp"
#include "python/bindings/toml_value.hpp"

namespace py = pybind11;

namespace mpsolid::python {

namespace {
std::string path_text(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

std::string case_repr(const CaseHandle& c) {
  std::string text = "Case(" + std::string(py::repr(py::str(c.source_name()))) +
                     ", name=" + std::string(py::repr(py::str(c.spec().name))) +
                     ", model=" + std::string(py::repr(py::str(c.spec().model)));
  if (!c.overrides().empty())
    text += ", overrides=" + std::string(py::repr(py::cast(c.overrides())));
  return text + ")";
}
}  // namespace

void bind_case(py::module_& m) {
  m.def(
      "toml_value", [](py::handle value) { return toml_value_text(value); }, py::arg("value"),
      "A Python value as the TOML text `--set` reads (what Case.set applies).");
  py::class_<CaseHandle>(m, "Case",
                         "A case: a TOML case file (or text) with --set style overrides.")
      .def_static(
          "load", [](const py::object& path) { return CaseHandle::from_file(path_text(path)); },
          py::arg("path"), "Reads a case file (InputError when it is missing or not valid).")
      .def_static("from_text", &CaseHandle::from_text, py::arg("toml_text"),
                  py::arg("name") = "<text>",
                  "A case from TOML text; `name` stands in for the file name in messages.")
      .def(
          "set",
          [](py::object self, const std::string& key, py::handle value) {
            self.cast<CaseHandle&>().set(key, toml_value_text(value));
            return self;
          },
          py::arg("key"), py::arg("value"),
          "Overrides a case key as `--set key=value` does (same checks and messages); returns "
          "the case. Raises InputError and leaves the case unchanged when the result is not "
          "valid.")
      .def(
          "set_text",
          [](py::object self, const std::string& key, const std::string& text) {
            self.cast<CaseHandle&>().set(key, text);
            return self;
          },
          py::arg("key"), py::arg("text"),
          "Like set, with the value as the command line gives it (TOML text, a bare word a "
          "string): `mpsolid study` checks its --vary and --set values with it.")
      .def("copy", [](const CaseHandle& c) { return c; })
      .def("__copy__", [](const CaseHandle& c) { return c; })
      .def("__deepcopy__", [](const CaseHandle& c, py::handle) { return c; })
      .def_property_readonly("overrides", &CaseHandle::overrides,
                             "The overrides so far, as 'key=value' strings (a copy).")
      .def_property_readonly("path", &CaseHandle::path, "The case file, or None for text.")
      .def_property_readonly("name", [](const CaseHandle& c) { return c.spec().name; })
      .def_property_readonly("model", [](const CaseHandle& c) { return c.spec().model; })
      .def_property_readonly("l0", [](const CaseHandle& c) { return c.spec().l0; })
      .def_property_readonly(
          "dt",
          [](const CaseHandle& c) -> py::object {
            if (c.spec().dt_auto) return py::none();
            return py::float_(c.spec().dt);
          },
          "The time step (s); None for time.dt = \"auto\" (chosen by Simulation).")
      .def_property_readonly("end_time", [](const CaseHandle& c) { return c.spec().end; })
      .def_property_readonly("frame_interval",
                             [](const CaseHandle& c) { return c.spec().frame_interval; })
      .def_property_readonly("particle_count",
                             [](const CaseHandle& c) { return c.spec().particle_count(); })
      .def_property_readonly(
          "notes", [](const CaseHandle& c) { return c.spec().notes; },
          "What the reader rounded to whole steps, in words.")
      .def(
          "resolved_toml", [](const CaseHandle& c) { return c.spec().resolved_toml; },
          "The case with every default and override filled in (case.resolved.toml).")
      .def(
          "resolved",
          [](const CaseHandle& c) {
            return py::module_::import("tomllib").attr("loads")(c.spec().resolved_toml);
          },
          "resolved_toml() read into a dict.")
      .def("__repr__", &case_repr);
}

}  // namespace mpsolid::python
