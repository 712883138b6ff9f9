#include "src/io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace mpsolid {

namespace {
void sync_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    throw std::runtime_error(
        fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  ::fsync(fd);
  ::close(fd);
}
}  // namespace

std::filesystem::path staging_path(const std::filesystem::path& path) {
  return path.parent_path() / (path.filename().string() + ".tmp");
}

void publish_staged_file(const std::filesystem::path& path) {
  const auto staged = staging_path(path);
  sync_file(staged);
  std::error_code ec;
  std::filesystem::rename(staged, path, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot rename {} to {}: {}", staged.string(), path.string(), ec.message()));
}

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  {
    std::ofstream out(staging_path(path), std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", staging_path(path).string()));
    out << content;
    if (!out.flush())
      throw std::runtime_error(fmt::format("cannot write {}", staging_path(path).string()));
  }
  publish_staged_file(path);
}

}  // namespace mpsolid
