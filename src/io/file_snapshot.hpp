#pragma once
// Publishing a copy of a file that is still being written: the live staging
// file (NAME.tmp) is copied to a temporary name beside NAME, synced and
// renamed over NAME, so NAME is always a complete file (the old one or the
// new one) while the run goes on appending to the staging file.
#include <filesystem>

namespace mpsolid {

// Copies `from` over `to` atomically (via `to`.snapshot.tmp, fsync, rename).
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);

// fsync of a file, and of a folder (makes renames in it durable).
void sync_path(const std::filesystem::path& path);

}  // namespace mpsolid
