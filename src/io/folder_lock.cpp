#include "src/io/folder_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>

#include "src/core/types.hpp"
#include "src/io/atomic_file.hpp"

namespace mpsolid {

namespace {
std::filesystem::path owner_path(const std::filesystem::path& dir) {
  return dir / ".owner";
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown host";
  return name;
}
}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir) : dir_(dir) {
  fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0)
    throw InputError(
        fmt::format("{}: cannot open the output folder: {}", dir.string(), std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  const int error = errno;
  ::close(fd_);
  fd_ = -1;
  if (error != EWOULDBLOCK)
    throw InputError(
        fmt::format("{}: cannot lock the output folder: {}", dir.string(), std::strerror(error)));
  std::string owner = "a process that has not recorded itself yet";
  if (std::ifstream in(owner_path(dir)); in) {
    std::ostringstream text;
    text << in.rdbuf();
    owner = text.str();
    while (!owner.empty() && owner.back() == '\n') owner.pop_back();
  }
  throw InputError(fmt::format(
      "{}: the folder is in use by another mpsolid run ({}); wait for it to end, or write this "
      "run elsewhere with --out",
      dir.string(), owner));
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  if (recorded_) {
    std::error_code ignored;
    std::filesystem::remove(owner_path(dir_), ignored);
  }
  ::close(fd_);  // releases the lock
}

void FolderLock::record_owner() {
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char when[64] = {};
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  write_file_atomically(owner_path(dir_), fmt::format("pid {} on host {}, since {}\n", ::getpid(),
                                                      host_name(), when));
  recorded_ = true;
}

void prepare_output_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw InputError(
        fmt::format("{}: the output folder is a file; give --out a folder", dir.string()));
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw InputError(
        fmt::format("{}: cannot create the output folder: {}", dir.string(), ec.message()));
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(fmt::format("{}: the output folder is not writable: {}", dir.string(),
                                 std::strerror(errno)));
}

}  // namespace mpsolid
