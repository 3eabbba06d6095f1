#include "phyir/dataset/shard.h"

#include <cstdio>

#include "phyir/core/setting_error.h"

namespace phyir::dataset {

Shard parse_shard(const std::string& text) {
  int index = -1, count = -1, consumed = 0;
  if (std::sscanf(text.c_str(), "%d/%d%n", &index, &count, &consumed) != 2 || consumed != int(text.size()) ||
      count < 1 || index < 0 || index >= count)
    fail_setting("shard", "'{}' must be i/N with 0 <= i < N (e.g. 0/4)", text);
  return {index, count};
}

std::string shard_name(const Shard& shard) { return std::to_string(shard.index) + "/" + std::to_string(shard.count); }

std::pair<size_t, size_t> shard_range(size_t total_views, const Shard& shard) {
  // 128-bit products: total_views * count cannot overflow for any real dataset, but cheap.
  const auto edge = [&](int i) {
    return static_cast<size_t>((static_cast<unsigned __int128>(total_views) * unsigned(i)) / unsigned(shard.count));
  };
  return {edge(shard.index), edge(shard.index + 1)};
}

}  // namespace phyir::dataset
