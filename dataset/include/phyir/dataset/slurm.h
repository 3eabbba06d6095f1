#pragma once
// A dataset rendered as shards on a cluster (docs/dataset.md, "On a cluster"): shard i of N
// (shard.h) renders into OUT/shards/shard-<i>-of-<N>, and `dataset merge` joins the N folders
// into OUT. The Slurm job array that runs them is written by the command line (the scripts
// hold `phyir` command lines: cli/flags/slurm_script.h).
#include <filesystem>
#include <string>

namespace phyir::dataset {

struct ShardPlan {
  std::filesystem::path out_dir;  // the merged dataset
  int shards = 1;

  // Throws phyir::SettingError "shards" unless there is at least one.
  void validate() const;
  std::filesystem::path root() const;  // OUT/shards
  // "shard-<index>-of-<N>"; `index` may be a shell variable ("${shard}").
  std::string folder_name(const std::string& index) const;
  std::filesystem::path folder(int index) const;  // OUT/shards/shard-<i>-of-<N>
};

}  // namespace phyir::dataset
