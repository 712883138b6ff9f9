// mpsolid.run and mpsolid.resume: the command line's `run` and `resume`,
// with its outputs, progress line, summary and exit codes.
#include <cstdio>
#include <filesystem>

#include <pybind11/stl.h>

#include "python/bindings/bindings.hpp"
#include "python/bindings/case_handle.hpp"
#include "python/bindings/stop_handlers.hpp"
#include "python/bindings/threads.hpp"
#include "python/bindings/toml_value.hpp"
#include "src/app/progress.hpp"
#include "src/app/run.hpp"

namespace py = pybind11;

namespace mpsolid::python {

namespace {
std::string path_text(const py::handle& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

RunOptions options_for(const py::object& threads, const py::object& progress, bool fixed_threads) {
  RunOptions o;
  o.threads = chosen_threads(threads);
  o.adaptive_threads = !fixed_threads;
  o.progress = progress.is_none() ? stderr_is_terminal() : progress.cast<bool>();
  return o;
}

// run.json's command line: the call, as Python would repeat it.
std::string call_text(const std::string& function, const py::dict& arguments) {
  std::string text = "python: mpsolid." + function + "(";
  bool first = true;
  for (auto [name, value] : arguments) {
    if (value.is_none()) continue;
    text += (first ? "" : ", ") + py::str(name).cast<std::string>() + "=" +
            py::repr(value).cast<std::string>();
    first = false;
  }
  return text + ")";
}

bool on_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

// Runs body with the stop handlers in place, the GIL released and the solver
// lock held; C and Python output stay in order around it.
template <class Body>
int run_stoppable(Body&& body) {
  py::module_::import("sys").attr("stdout").attr("flush")();
  StopHandlerScope stop(on_main_thread());
  int code = 0;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(solver_mutex());
    code = body();
    std::fflush(stdout);
  }
  return code;
}
}  // namespace

void bind_run(py::module_& m) {
  m.def(
      "run",
      [](const CaseHandle& c, const py::object& out, const py::object& threads, bool force,
         const py::object& progress, bool fixed_threads) {
        RunOptions o = options_for(threads, progress, fixed_threads);
        o.overrides = c.overrides();
        o.out_dir = out.is_none() ? default_out_dir(c.spec().name, o.overrides)
                                  : std::filesystem::path(path_text(out));
        o.force = force;
        py::dict args;
        args["case"] = c.source_name();
        args["overrides"] = py::cast(c.overrides());
        args["out"] = o.out_dir.string();
        args["threads"] = threads;
        o.command_line = call_text("run", args);
        const CaseSpec spec = c.spec();
        return run_stoppable([&] { return run_case(spec, o); });
      },
      py::arg("case"), py::arg("out") = py::none(), py::arg("threads") = py::none(),
      py::arg("force") = false, py::arg("progress") = py::none(), py::arg("fixed_threads") = false,
      "`mpsolid run`: runs the case to its end with every output in `out` (default "
      "out/<name>, plus a hash of the overrides). Returns the exit code: 0 completed, 3 "
      "unstable, 4 stopped by Ctrl-C or SIGTERM (checkpoint written: mpsolid.resume(out) "
      "continues). Raises InputError for bad input.");
  m.def(
      "resume",
      [](const py::object& out, const py::object& threads, const py::object& end_time,
         const py::object& checkpoint_interval, const py::object& compression,
         const py::object& progress, bool fixed_threads) {
        RunOptions o = options_for(threads, progress, fixed_threads);
        o.out_dir = path_text(out);
        const std::pair<const char*, py::object> keys[] = {
            {"time.end", end_time},
            {"output.checkpoint_interval", checkpoint_interval},
            {"output.compression", compression}};
        for (const auto& [key, value] : keys)
          if (!value.is_none())
            o.overrides.push_back(std::string(key) + "=" + toml_value_text(value));
        py::dict args;
        args["out"] = o.out_dir.string();
        args["overrides"] = o.overrides.empty() ? py::object(py::none()) : py::cast(o.overrides);
        args["threads"] = threads;
        o.command_line = call_text("resume", args);
        return run_stoppable([&] { return resume_run(o.overrides, o); });
      },
      py::arg("out"), py::arg("threads") = py::none(), py::arg("end_time") = py::none(),
      py::arg("checkpoint_interval") = py::none(), py::arg("compression") = py::none(),
      py::arg("progress") = py::none(), py::arg("fixed_threads") = false,
      "`mpsolid resume`: continues the run in `out` from its checkpoint, to the same bits; "
      "end_time, checkpoint_interval and compression as --set time.end=..., ... Returns the "
      "exit code as run() does.");
}

}  // namespace mpsolid::python
