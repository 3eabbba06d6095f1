#pragma once
// Shards: views are numbered globally, scenes in name order and then view index
// (g = scene * views_per_scene + view), and shard i of N holds the contiguous block
// [floor(i T / N), floor((i + 1) T / N)) of the T views. Blocks keep a shard's views on few
// scenes (each shard loads only the scenes it renders); every view is in exactly one shard;
// a view's seed and files do not depend on the shard, so the union of the shards is the
// unsharded dataset.
#include <cstddef>
#include <string>
#include <utility>

namespace phyir::dataset {

struct Shard {
  int index = 0;
  int count = 1;
  bool whole() const { return count == 1; }
};

// "i/N" with 0 <= i < N. Throws phyir::Error naming the value.
Shard parse_shard(const std::string& text);
std::string shard_name(const Shard& shard);  // "i/N"

// [begin, end) of the global view numbers in `shard`.
std::pair<size_t, size_t> shard_range(size_t total_views, const Shard& shard);

}  // namespace phyir::dataset
