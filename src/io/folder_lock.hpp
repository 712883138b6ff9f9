#pragma once
// A run folder is owned by one process at a time: an advisory lock (flock)
// on the folder itself, which the kernel releases when the process ends, so a
// killed run never leaves the folder locked. The owner's pid, host and start
// time go into DIR/.owner once the run is accepted, for the message a second
// process gets; a refused process writes nothing.
#include <filesystem>
#include <string>

namespace mpsolid {

class FolderLock {
 public:
  // Locks `dir` (which must exist). Throws InputError naming the owner when
  // another process holds it.
  explicit FolderLock(const std::filesystem::path& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  // Writes DIR/.owner (pid, host, time): call once the run is accepted.
  void record_owner();

 private:
  std::filesystem::path dir_;
  int fd_ = -1;
  bool recorded_ = false;
};

// The folder a run writes to, made ready: an existing folder, or one created
// with its parents. Throws InputError (exit 2) naming the folder when it is a
// file, cannot be created or is not writable.
void prepare_output_folder(const std::filesystem::path& dir);

}  // namespace mpsolid
