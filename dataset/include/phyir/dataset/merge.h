#pragma once
// `phyir dataset merge OUT SHARD_DIR...`: joins finished shards into one dataset whose bytes
// equal an unsharded run's. It refuses, naming the shard folders and the first difference:
// a shard without manifest.json (unfinished), shards with different settings, generator or
// shard counts, a scene whose contents differ between shards, a view in two shards, and
// views in none (a shard not given). View folders are hard-linked into OUT when the file
// system allows (no extra space; files are never modified in place, only replaced by rename)
// and copied otherwise, each through a temporary folder renamed into place; settings.json and
// manifest.json are written last. Re-running an interrupted merge finishes it.
#include <cstddef>
#include <filesystem>
#include <vector>

namespace phyir::dataset {

struct MergeSummary {
  size_t views = 0;
  size_t merged = 0;   // view folders placed by this run
  size_t kept = 0;     // already in OUT from an earlier merge
  size_t linked_files = 0;
  size_t copied_files = 0;
};

MergeSummary merge_shards(const std::filesystem::path& out, const std::vector<std::filesystem::path>& shards);

}  // namespace phyir::dataset
