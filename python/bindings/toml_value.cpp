#include "python/bindings/toml_value.hpp"

#include <fmt/format.h>
#include <toml.hpp>

#include "src/case/case_overrides.hpp"

namespace py = pybind11;

namespace mpsolid::python {

namespace {
// One line, "..." with TOML's escapes (toml11 would pick """...""" for text
// with quotes, which is harder to read back in an error message).
std::string basic_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\')
      out += {'\\', c};
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
    else
      out += c;
  }
  return out + "\"";
}
}  // namespace

std::string toml_value_text(py::handle value) {
  // bool before int: True is an int in Python.
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return basic_string(value.cast<std::string>());
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text = "[";
    for (py::handle item : value) text += (text.size() > 1 ? ", " : "") + toml_value_text(item);
    return text + "]";
  }
  if (py::isinstance<py::dict>(value)) {
    std::string text = "{";
    for (auto [k, v] : value.cast<py::dict>())
      text += (text.size() > 1 ? ", " : " ") + toml::format_key(py::str(k).cast<std::string>()) +
              " = " + toml_value_text(v);
    return text + " }";
  }
  // Python's own int and float, or anything that converts like one (numpy
  // scalars: numpy 2's repr of a float64 is "np.float64(...)", not TOML).
  if (py::hasattr(value, "__index__")) {
    PyObject* integer = PyNumber_Index(value.ptr());
    if (!integer) throw py::error_already_set();
    return py::str(py::reinterpret_steal<py::object>(integer));
  }
  if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
  throw py::type_error(
      "a case value must be a bool, int, float, str, or a list or dict of them, not " +
      std::string(py::str(py::type::handle_of(value).attr("__name__"))));
}

}  // namespace mpsolid::python
