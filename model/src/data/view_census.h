#pragma once
// How many decoded views are alive at once: the instrument behind streaming's memory bound
// (docs/model-scale.md "Streaming"). The dataset enrols each view it decodes; the token
// rides in the view (ViewTensors::census) and in every batch stacked from it (Batch::census),
// so a view counts until the last tensor made from it is gone. Counts, never times.
// Thread-safe: worker threads enrol, the trainer releases. Private header.
#include <atomic>
#include <cstdint>
#include <memory>

namespace phyir::model {

// Made with std::make_shared: each token keeps the census alive.
class ViewCensus : public std::enable_shared_from_this<ViewCensus> {
 public:
  // A token that counts one view alive until its last copy is destroyed.
  std::shared_ptr<const void> enrol();

  int64_t alive() const { return alive_.load(); }
  int64_t peak() const { return peak_.load(); }      // most views alive at one time
  int64_t decoded() const { return decoded_.load(); }  // views enrolled in total

 private:
  void release() { alive_.fetch_sub(1); }
  std::atomic<int64_t> alive_{0}, peak_{0}, decoded_{0};
};

}  // namespace phyir::model
