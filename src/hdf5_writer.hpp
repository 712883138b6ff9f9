#pragma once
// frames.h5: one group per frame (/frames/000000, ...), every particle field in
// id order. HDF5 is used in this file only.
#include <cstdint>
#include <filesystem>
#include <memory>

#include "src/simulation.hpp"

namespace mpsolid {

class FrameWriter {
 public:
  // Writes to a staging file; publish() renames it to `path`.
  FrameWriter(const std::filesystem::path& path, const Simulation& sim);
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // The current state (fields must be refreshed) as the next frame.
  void write(const Simulation& sim);
  void publish();
  int frames_written() const { return frames_; }
  std::uintmax_t bytes_written() const;

 private:
  struct File;
  std::filesystem::path path_;
  std::unique_ptr<File> file_;
  int frames_ = 0;
  std::uintmax_t published_bytes_ = 0;
};

}  // namespace mpsolid
