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

PlacedFile::PlacedFile(const std::string& path, Access access) : path_(path), access_(access) {
  fd_ = ::open(path.c_str(), (access == Access::write ? O_WRONLY : O_RDONLY) | O_CLOEXEC);
  if (fd_ < 0) fail("open", errno);
}

PlacedFile::~PlacedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void PlacedFile::fail(const char* what, int error) const {
  PlacedRowsError e(fmt::format("{}: cannot {} it to {} rows in place: {}", path_, what,
                                access_ == Access::write ? "write" : "read", std::strerror(error)));
  e.error_number = error;
  throw e;
}

namespace {
// Each run's rows moved by `io` (pwrite or pread: bytes moved, or -1) until
// all are, counted in `bytes`; returns 0, or the error number of the call
// that failed (one that moves nothing: `stuck`).
template <class Byte, class Io>
int move_runs(std::uint64_t offset, std::size_t row_bytes, const IdRuns& runs, Byte* rows, Io io,
              int stuck, double& bytes) {
  for (const IdRuns::Run& run : runs.runs) {
    std::size_t left = run.count * row_bytes;
    auto at = static_cast<off_t>(offset + run.first_id * row_bytes);
    while (left > 0) {
      const ssize_t n = io(rows, left, at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return n < 0 ? errno : stuck;
      rows += n;
      at += n;
      left -= static_cast<std::size_t>(n);
      bytes += static_cast<double>(n);
    }
  }
  return 0;
}
}  // namespace

void PlacedFile::write(std::uint64_t offset, std::size_t row_bytes, const IdRuns& runs,
                       const void* rows) {
  const auto pwrite = [&](const char* from, std::size_t n, off_t at) {
    return ::pwrite(fd_, from, n, at);
  };
  if (const int error = move_runs(offset, row_bytes, runs, static_cast<const char*>(rows), pwrite,
                                  ENOSPC, bytes_))
    fail("write", error);
}

void PlacedFile::read(std::uint64_t offset, std::size_t row_bytes, const IdRuns& runs, void* rows) {
  const auto pread = [&](char* to, std::size_t n, off_t at) { return ::pread(fd_, to, n, at); };
  // A read of nothing: the file ends before the row.
  if (const int error =
          move_runs(offset, row_bytes, runs, static_cast<char*>(rows), pread, EIO, bytes_))
    fail("read", error);
}

void PlacedFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (access_ == Access::write && ::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    fail("flush", error);
  }
  if (::close(fd) != 0) fail("close", errno);
}

}  // namespace mpsolid
