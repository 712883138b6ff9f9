#pragma once
// A rank's rows written in place into a file another process laid out (a
// frame's datasets or a checkpoint's particle arrays, src/core/frame_rows.hpp):
// each dataset is contiguous, the row of id k at offset + k * row_bytes, so
// every rank writes its own particles' rows beside the others' with pwrite
// and no rank holds another's. The file is a valid HDF5 file before and
// after: the ranks write only bytes its layout reserved.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "src/core/types.hpp"

namespace mpsolid {

// The particles of a range ordered by id, and their runs of consecutive ids
// (one pwrite each).
struct IdRuns {
  std::vector<std::size_t> members;  // storage indices, by ascending id
  struct Run {
    std::uint64_t first_id = 0;
    std::size_t count = 0;
  };
  std::vector<Run> runs;
};
IdRuns id_runs(const std::vector<std::int32_t>& ids, Range particles);

// A file open for writing rows in place, or for reading them (a resume, each
// rank its own). Failures (a missing file, a full disk, a file cut short)
// throw PlacedRowsError with the file's name and the system's reason.
struct PlacedRowsError : std::runtime_error {
  using std::runtime_error::runtime_error;
  int error_number = 0;
};
class PlacedFile {
 public:
  enum class Access : std::int8_t { write, read };
  explicit PlacedFile(const std::string& path, Access access = Access::write);
  ~PlacedFile();
  PlacedFile(const PlacedFile&) = delete;
  PlacedFile& operator=(const PlacedFile&) = delete;

  // The members' rows (`row_bytes` each, in the members' order) of a
  // dataset at `offset`.
  void write(std::uint64_t offset, std::size_t row_bytes, const IdRuns& runs, const void* rows);
  // The members' rows of a dataset at `offset` into `rows` (members' order).
  void read(std::uint64_t offset, std::size_t row_bytes, const IdRuns& runs, void* rows);
  // Flushes written rows to the disk (fsync) and closes the file.
  void close();
  double bytes() const { return bytes_; }

 private:
  [[noreturn]] void fail(const char* what, int error) const;
  std::string path_;
  Access access_;
  int fd_ = -1;
  double bytes_ = 0;
};

}  // namespace mpsolid
