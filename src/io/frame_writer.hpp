#pragma once
// frames.h5: one group per frame (/frames/000000, ...), every particle field in
// id order, optionally deflate-compressed; and its XDMF sidecar frames.xdmf.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/frame_rows.hpp"
#include "src/core/gas_frame.hpp"
#include "src/core/solver_state.hpp"
#include "src/io/xdmf_writer.hpp"

namespace mpsolid {

namespace h5 {
class Group;
}

class FrameWriter {
 public:
  // A new file, written to a staging file; publish() renames it to `path`.
  // Deflate level spec.compression (0: off, to 9). `run_id` ties it to its checkpoints.
  // `particles`: the run's (`state` may hold none: over MPI ranks every rank
  // writes its own rows).
  FrameWriter(const std::filesystem::path& path, const SolverState& state, const CaseSpec& spec,
              std::uint64_t run_id, std::size_t particles);
  // A resumed run: continues the published file at `path` from its first
  // `keep_frames` frames (later ones are dropped). Throws InputError if that
  // file is missing, belongs to another run or has fewer frames.
  FrameWriter(const std::filesystem::path& path, const SolverState& state, const CaseSpec& spec,
              std::uint64_t run_id, std::size_t particles, int keep_frames);
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // The current state (fields must be refreshed) as the next frame, with
  // the gas's fields (none when `gas` is empty).
  void write(const SolverState& state, const CaseSpec& spec, const GasFrame& gas = {});
  // The next frame at `step` with its particles' rows written in place by
  // `placer` (over MPI ranks, every rank its own), or, compressed, given by
  // it chunk by chunk (RowPlacement::chunk_sink).
  void write_placed(std::int64_t step, const CaseSpec& spec, const GasFrame& gas,
                    const RowPlacer& placer);
  // Publishes a copy of the file as it is now (and the sidecar); writing goes on.
  void publish_copy();
  // Closes the file and renames it to `path`; writes the sidecar.
  void publish();
  int frames_written() const { return frames_total() - first_frame_; }   // by this writer
  int frames_total() const { return static_cast<int>(frames_.size()); }  // in the file
  std::uintmax_t bytes_written() const;                                  // by this writer

 private:
  struct File;
  // A frame's group with its step and time; its gas, and the frame counted.
  h5::Group begin_frame(std::int64_t step, const CaseSpec& spec);
  void end_frame(const h5::Group& group, std::int64_t step, const CaseSpec& spec,
                 const GasFrame& gas);
  void write_sidecar() const;
  std::filesystem::path path_;
  std::unique_ptr<File> file_;
  std::vector<XdmfFrame> frames_;
  XdmfGasGrid gas_grid_;  // cells 0 x 0 without a gas
  // In the plane, the surfaces a frame marks, built at the first frame.
  std::vector<FrameSurface> surfaces_;
  bool surfaces_built_ = false;
  int first_frame_ = 0;
  int compression_ = 0;
  std::size_t particles_ = 0;
  int dimension_ = 2;
  std::uintmax_t start_bytes_ = 0, published_bytes_ = 0;
};

// The datasets of a frame besides `position`, as the XDMF sidecar lists them,
// for a case of `dimension` 2 or 3 (in space, vectors have three components,
// `rotation` is the rotation vector (axis times angle) and the quaternion
// `orientation` (w, x, y, z) is in the frame but not the sidecar).
const std::vector<XdmfField>& frame_fields(int dimension = 2);
// A frame's gas datasets (cell-centred, row by row), named gas_ + the field.
const std::vector<XdmfField>& gas_frame_fields();

// The run id stored in a frames file. Throws InputError if it cannot be read.
std::uint64_t frames_run_id(const std::filesystem::path& path);

}  // namespace mpsolid
