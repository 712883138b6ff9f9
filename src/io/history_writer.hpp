#pragma once
// history.csv: a row every output.history_interval and at every frame, 17
// significant digits, SI units.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/diagnostics.hpp"
#include "src/core/solver_state.hpp"

namespace mpsolid {

// Column names for a case: the fixed diagnostics, then per rigid body
// B.x, B.y, B.theta, then per elastic body B.xmin, B.xmax, B.ymin, B.ymax,
// then per probe probe.NAME.x, probe.NAME.y (current position).
std::vector<std::string> history_columns(const SolverState& state, const CaseSpec& spec);
std::vector<double> history_row(const SolverState& state, const CaseSpec& spec,
                                const Diagnostics& d);
// The row with the particles' readings given (the state's particles are
// not read: over ranks they may be elsewhere), and those readings of the
// whole state.
std::vector<double> history_row(const SolverState& state, const CaseSpec& spec,
                                const Diagnostics& d, const HistoryReadings& r);
HistoryReadings history_readings(const SolverState& state, const CaseSpec& spec);

class HistoryWriter {
 public:
  // Writes to a staging file; publish() renames it to `path`.
  HistoryWriter(const std::filesystem::path& path, const SolverState& state, const CaseSpec& spec);
  // A resumed run: continues the published file at `path` from its first
  // `keep_bytes` bytes (later rows are dropped). Throws InputError if that
  // file is missing, shorter or has other columns.
  HistoryWriter(const std::filesystem::path& path, const SolverState& state, const CaseSpec& spec,
                std::uintmax_t keep_bytes);
  ~HistoryWriter();
  HistoryWriter(const HistoryWriter&) = delete;
  HistoryWriter& operator=(const HistoryWriter&) = delete;

  void write(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
             const HistoryReadings& readings);
  // Publishes a copy of the file as it is now; writing goes on.
  void publish_copy();
  void publish();
  std::uintmax_t bytes_written() const { return bytes_; }    // by this writer
  std::uintmax_t file_bytes() const { return file_bytes_; }  // in the file, header included

 private:
  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  std::uintmax_t bytes_ = 0, file_bytes_ = 0;
};

}  // namespace mpsolid
