#include "src/app/study_launcher.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include "python_paths.hpp"

namespace mpsolid {

namespace {
namespace fs = std::filesystem;

bool holds_package(const fs::path& dir) {
  return fs::exists(dir / "mpsolid" / "study.py");
}

// The folder holding the `mpsolid` package: for an installed executable, where
// cmake --install put the package relative to bin/, or the package the
// executable sits in (pip's mpsolid/bin/mpsolid); else the build tree's.
fs::path package_parent(const fs::path& self) {
  std::vector<fs::path> candidates;
  if (!self.empty()) {
    const fs::path bin = self.parent_path();
    if (*python_paths::installed_package_parent)
      candidates.push_back(bin / python_paths::installed_package_parent);
    if (bin.filename() == "bin" && bin.parent_path().filename() == "mpsolid")
      candidates.push_back(bin.parent_path().parent_path());
  }
  candidates.emplace_back(python_paths::build_package_parent);
  for (const fs::path& dir : candidates)
    if (holds_package(dir)) return dir.lexically_normal();
  return {};
}
}  // namespace

int launch_study(const std::vector<std::string>& args) {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  const fs::path parent = package_parent(error ? fs::path() : self);
  if (parent.empty()) {
    fmt::print(stderr,
               "mpsolid: failed: the study needs the Python package mpsolid, found neither in the "
               "build tree ({}) nor installed beside this executable ({}): build with "
               "-DMPSOLID_PYTHON=ON (Debian: pybind11-dev, python3-dev)\n",
               python_paths::build_package_parent, self.string());
    return 1;
  }
  std::string path = parent.string();
  if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
  setenv("PYTHONPATH", path.c_str(), 1);
  // The study runs its points with this very executable.
  if (!self.empty()) setenv("MPSOLID_EXECUTABLE", self.c_str(), 1);

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
