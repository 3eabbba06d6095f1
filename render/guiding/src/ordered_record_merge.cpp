#include "phyir/render/guiding/ordered_record_merge.h"

#include <utility>

#include "phyir/core/error.h"

namespace phyir::render::guiding {

OrderedRecordMerge::OrderedRecordMerge(SDTree* tree, size_t chunks) : tree_(tree), waiting_(chunks) {}

void OrderedRecordMerge::submit(size_t chunk, RecordBuffer&& records) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (chunk >= waiting_.size() || chunk < next_ || waiting_[chunk])
    throw Error("guiding: chunk " + std::to_string(chunk) + " submitted twice or out of range (" +
                std::to_string(waiting_.size()) + " chunks)");
  waiting_[chunk] = std::move(records);
  // The merge runs under the lock: it is cheap beside tracing the chunk's paths.
  while (next_ < waiting_.size() && waiting_[next_]) {
    tree_->record(*waiting_[next_]);
    waiting_[next_].reset();
    ++next_;
  }
}

bool OrderedRecordMerge::complete() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_ == waiting_.size();
}

}  // namespace phyir::render::guiding
