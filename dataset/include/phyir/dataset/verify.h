#pragma once
// `phyir dataset verify DIR`: re-reads every file the manifest lists and reports every
// problem found (missing, wrong size, checksum mismatch, an image OpenImageIO cannot decode
// or whose size or channels differ from the record, non-finite EXR values, a view.json that
// disagrees with the manifest, a scene in two splits, a view outside its scene's split,
// stray files in a view folder, interrupted writes left behind).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace phyir::dataset {

// One file read once: its manifest record (path, size, sha256; for .exr and .png also
// width, height, channels from an OpenImageIO decode) and, if something is wrong with it
// (unreadable, undecodable, non-finite EXR values), `problem`: what is wrong, without the
// file's name (callers prefix the name they show).
struct FileCheck {
  nlohmann::json record;
  std::string problem;
};
FileCheck inspect_file(const std::filesystem::path& folder, const std::string& name);

struct VerifyReport {
  size_t views = 0;
  size_t files = 0;
  uint64_t bytes = 0;
  std::vector<std::string> problems;  // sorted; empty = the dataset is whole
  std::vector<std::string> damaged_views;  // "dir" of every view with a problem, sorted
  bool ok() const { return problems.empty(); }
};

// `threads` 0 = all cores. Throws phyir::Error only when there is no readable manifest.
VerifyReport verify_dataset(const std::filesystem::path& dir, int threads = 0);

// Deletes the folders of report.damaged_views (through a temporary name) and manifest.json,
// holding the folder's lock, so the same `generate` command renders exactly those views
// again. Returns how many were removed.
size_t remove_damaged_views(const std::filesystem::path& dir, const VerifyReport& report);

}  // namespace phyir::dataset
