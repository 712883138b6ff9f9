#pragma once
// Output files appear only when complete: written under a temporary name,
// flushed to disk, then renamed over the final name. A crash leaves either
// the old file or the new one, never half of one.
#include <filesystem>
#include <string>

namespace mpsolid {

// Writes `content` to `path` atomically.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

// The temporary name used while `path` is being written.
std::filesystem::path staging_path(const std::filesystem::path& path);

// fsync(staging_path(path)) and rename it to `path`.
void publish_staged_file(const std::filesystem::path& path);

}  // namespace mpsolid
