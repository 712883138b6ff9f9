#include "src/io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace mpsolid {

namespace {
std::filesystem::path folder_of(const std::filesystem::path& path) {
  return path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
}

void rename_or_throw(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  std::filesystem::rename(from, to, ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot rename {} to {}: {}", from.string(), to.string(), ec.message()));
}
}  // namespace

long long free_bytes(const std::filesystem::path& path) {
  struct statvfs fs {};
  if (::statvfs(path.c_str(), &fs) != 0) return -1;
  return static_cast<long long>(fs.f_bavail) * static_cast<long long>(fs.f_frsize);
}

std::filesystem::path staging_path(const std::filesystem::path& path) {
  return path.parent_path() / (path.filename().string() + ".tmp");
}

void sync_path(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0)
    throw std::runtime_error(
        fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  const int status = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (status != 0 && error != EINVAL)
    throw std::runtime_error(
        fmt::format("cannot sync {}: {}", path.string(), std::strerror(error)));
}

void publish_staged_file(const std::filesystem::path& path) {
  const auto staged = staging_path(path);
  sync_path(staged);
  rename_or_throw(staged, path);
  sync_path(folder_of(path));
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

void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to) {
  const std::filesystem::path temporary =
      to.parent_path() / (to.filename().string() + copy_path_suffix());
  std::error_code ec;
  std::filesystem::copy_file(from, temporary, std::filesystem::copy_options::overwrite_existing,
                             ec);
  if (ec)
    throw std::runtime_error(
        fmt::format("cannot copy {} to {}: {}", from.string(), temporary.string(), ec.message()));
  sync_path(temporary);
  rename_or_throw(temporary, to);
  sync_path(folder_of(to));
}

}  // namespace mpsolid
