#include "src/io/file_snapshot.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace mpsolid {

void sync_path(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    throw std::runtime_error(
        fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  // Some file systems cannot fsync a folder (EINVAL); the rename still holds.
  if (status != 0 && error != EINVAL)
    throw std::runtime_error(
        fmt::format("cannot sync {}: {}", path.string(), std::strerror(error)));
}

void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to) {
  const std::filesystem::path temporary =
      to.parent_path() / (to.filename().string() + ".snapshot.tmp");
  std::error_code ec;
  std::filesystem::copy_file(from, temporary, std::filesystem::copy_options::overwrite_existing,
                             ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot copy {} to {}: {}", from.string(), temporary.string(), ec.message()));
  sync_path(temporary);
  std::filesystem::rename(temporary, to, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot rename {} to {}: {}", temporary.string(), to.string(), ec.message()));
}

}  // namespace mpsolid
