#pragma once
// Crash-safe writes: every output goes to a temporary name in the same folder and is
// renamed over the final name only when complete, so a killed process never leaves a
// half-written file that looks whole.
#include <filesystem>
#include <string>

namespace phyir {

// A temporary sibling of `final_path` that keeps its extension (image writers pick the
// format from it): "dir/.color.exr.partial-<pid>.exr".
std::filesystem::path temporary_sibling(const std::filesystem::path& final_path);

// fsyncs `temporary` and renames it to `final_path` (atomic on POSIX file systems).
void commit_file(const std::filesystem::path& temporary, const std::filesystem::path& final_path);

// Writes `contents` to `path` atomically. Throws phyir::Error naming the path on failure.
void write_file_atomic(const std::filesystem::path& path, const std::string& contents);

// Creates `dir` if needed and checks a file can be written in it, so that a command fails
// before hours of work rather than after; throws phyir::Error naming the folder.
void ensure_writable_directory(const std::filesystem::path& dir);

// Reads a whole file; throws phyir::Error naming the path when it cannot.
std::string read_file(const std::filesystem::path& path);

}  // namespace phyir
