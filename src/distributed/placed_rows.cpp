#include "src/distributed/placed_rows.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <numeric>

namespace mpsolid {

IdRuns id_runs(const std::vector<std::int32_t>& ids, Range particles) {
  IdRuns out;
  out.members.resize(particles.size());
  std::iota(out.members.begin(), out.members.end(), particles.begin);
  std::sort(out.members.begin(), out.members.end(),
            [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  for (const std::size_t i : out.members) {
    const auto id = static_cast<std::uint64_t>(ids[i]);
    if (!out.runs.empty() && out.runs.back().first_id + out.runs.back().count == id)
      ++out.runs.back().count;
    else
      out.runs.push_back({id, 1});
  }
  return out;
}

PlacedFile::PlacedFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) fail("open", errno);
}

PlacedFile::~PlacedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void PlacedFile::fail(const char* what, int error) const {
  PlacedRowsError e(fmt::format("{}: cannot {} it to write rows in place: {}", path_, what,
                                std::strerror(error)));
  e.error_number = error;
  throw e;
}

void PlacedFile::write(std::uint64_t offset, std::size_t row_bytes, const IdRuns& runs,
                       const void* rows) {
  const auto* from = static_cast<const char*>(rows);
  for (const IdRuns::Run& run : runs.runs) {
    std::size_t left = run.count * row_bytes;
    auto at = static_cast<off_t>(offset + run.first_id * row_bytes);
    while (left > 0) {
      const ssize_t n = ::pwrite(fd_, from, left, at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) fail("write", n < 0 ? errno : ENOSPC);
      from += n;
      at += n;
      left -= static_cast<std::size_t>(n);
      bytes_ += static_cast<double>(n);
    }
  }
}

void PlacedFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    fail("flush", error);
  }
  if (::close(fd) != 0) fail("close", errno);
}

}  // namespace mpsolid
