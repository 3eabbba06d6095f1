#include "phyir/dataset/slurm.h"

#include "phyir/core/setting_error.h"

namespace phyir::dataset {

void ShardPlan::validate() const {
  if (shards < 1) fail_setting("shards", "{} must be at least 1", shards);
}

std::filesystem::path ShardPlan::root() const { return out_dir / "shards"; }

std::string ShardPlan::folder_name(const std::string& index) const {
  return "shard-" + index + "-of-" + std::to_string(shards);
}

std::filesystem::path ShardPlan::folder(int index) const { return root() / folder_name(std::to_string(index)); }

}  // namespace phyir::dataset
