#pragma once
// The file layer of a run folder: output files appear only when complete.
// Each is written under a temporary name (NAME.tmp), synced to disk, then
// renamed over NAME, and the folder is synced so the rename survives a crash:
// a reader finds the old file or the new one, never half of one. A file that
// is still being written can have a complete copy published the same way.
// Every failure throws std::runtime_error naming the file and the reason.
#include <filesystem>
#include <string>

namespace mpsolid {

// The temporary name used while `path` is being written.
std::filesystem::path staging_path(const std::filesystem::path& path);

// fsync of a file, or of a folder (makes renames in it durable). A file
// system that cannot sync a folder (EINVAL) is accepted: the rename holds.
void sync_path(const std::filesystem::path& path);

// Syncs staging_path(path), renames it to `path` and syncs the folder.
void publish_staged_file(const std::filesystem::path& path);

// Writes `content` to `path` atomically.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

// Copies `from` (a file still being written, say) over `to` atomically, via
// `to`.copy.tmp.
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);

// Bytes free for an unprivileged writer on the file system holding `path`
// (statvfs), or -1 when it cannot be asked.
long long free_bytes(const std::filesystem::path& path);

// The suffix of copy_file_atomically's temporary file.
inline std::string copy_path_suffix() {
  return ".copy.tmp";
}

}  // namespace mpsolid
