#include "phyir/view/view_files.h"

namespace phyir::view {

const std::vector<std::string>& prediction_map_files() {
  static const std::vector<std::string> files = {kDepthFile, kNormalFile, kBaseColorFile, kRoughnessFile,
                                                 kMetalnessFile};
  return files;
}

}  // namespace phyir::view
