// The count of decoded views alive (view_census.h).
#include "view_census.h"

namespace phyir::model {

std::shared_ptr<const void> ViewCensus::enrol() {
  const int64_t now = alive_.fetch_add(1) + 1;
  decoded_.fetch_add(1);
  int64_t seen = peak_.load();
  while (now > seen && !peak_.compare_exchange_weak(seen, now)) {
  }
  std::shared_ptr<ViewCensus> self = shared_from_this();
  return std::shared_ptr<const void>(static_cast<const void*>(this), [self](const void*) { self->release(); });
}

}  // namespace phyir::model
