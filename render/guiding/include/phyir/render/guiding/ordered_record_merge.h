#pragma once
// Thread-safe recording with results independent of the thread count: workers record into
// their own buffer per chunk of work (a tile) and submit it; the buffers go into the SD-tree
// in chunk order, each as soon as every earlier chunk is in. The tree's sums are then added in
// one fixed order, so the same records give the same tree (bit for bit) for any thread count
// and any schedule. Buffers wait only while an earlier chunk is still being worked on, so a
// pass holds about as many buffers as there are workers when chunks are handed out in order.
#include <cstddef>
#include <mutex>
#include <optional>
#include <vector>

#include "phyir/render/guiding/radiance_record.h"
#include "phyir/render/guiding/sd_tree.h"

namespace phyir::render::guiding {

class OrderedRecordMerge {
 public:
  OrderedRecordMerge(SDTree* tree, size_t chunks);

  // Hands over chunk `chunk`'s records (each chunk once); merges what is now in order.
  void submit(size_t chunk, RecordBuffer&& records);
  // Whether every chunk has been merged.
  bool complete() const;

 private:
  SDTree* tree_;
  mutable std::mutex mutex_;
  std::vector<std::optional<RecordBuffer>> waiting_;
  size_t next_ = 0;  // the first chunk not yet merged
};

}  // namespace phyir::render::guiding
