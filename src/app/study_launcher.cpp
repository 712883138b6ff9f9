#include "src/app/study_launcher.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "python_paths.hpp"

namespace mpsolid {

namespace {
namespace fs = std::filesystem;

// The folder holding the `mpsolid` package: the build tree's when this is the
// build tree's executable, else the installed one.
fs::path package_parent() {
  for (const char* dir : {python_paths::build_package_parent, python_paths::install_package_parent})
    if (*dir && fs::exists(fs::path(dir) / "mpsolid" / "study.py")) return dir;
  return {};
}
}  // namespace

int launch_study(const std::vector<std::string>& args) {
  const fs::path parent = package_parent();
  if (parent.empty()) {
    fmt::print(stderr,
               "mpsolid: failed: the study needs the Python package, found neither in the build "
               "tree ({}) nor installed ({}): build with -DMPSOLID_PYTHON=ON\n",
               python_paths::build_package_parent, python_paths::install_package_parent);
    return 1;
  }
  std::string path = parent.string();
  if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
  setenv("PYTHONPATH", path.c_str(), 1);
  // The study runs its points with this very executable.
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) setenv("MPSOLID_EXECUTABLE", self.c_str(), 1);

  std::vector<std::string> argv_text = {python_paths::python, "-m", "mpsolid", "study"};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(python_paths::python, argv.data());
  fmt::print(stderr, "mpsolid: failed: cannot start {} for the study: {}\n", python_paths::python,
             std::strerror(errno));
  return 1;
}

}  // namespace mpsolid
