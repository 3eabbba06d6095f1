#pragma once
// The flags that make up dataset::DatasetSettings, shared by `dataset generate` and `dataset
// slurm`. --preset picks a bundle of every field (dataset/settings.h); each other flag given
// sets one field over it, whatever their order on the command line: CLI11 runs the options'
// callbacks in the order they were added, --preset's first. The help shows the default
// preset's values.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "phyir/dataset/settings.h"

namespace phyir::cli {

struct DatasetSettingsFlags {
  dataset::DatasetSettings settings = dataset::preset_settings(dataset::DatasetSettings().preset);
  std::vector<CLI::Option*> options;  // the settings' flags, in the order added

  // After parsing: the settings, checked (phyir::SettingError naming the setting).
  dataset::DatasetSettings resolve() const;
  // The flags as the user gave them, to repeat in a Slurm script: --name=value, so that
  // values such as "-1.5" do not read as options.
  std::vector<std::string> replay() const;
};

// Registers the settings' flags on `cmd`, writing into `flags` (which must outlive `cmd`).
void add_dataset_settings_flags(CLI::App* cmd, DatasetSettingsFlags& flags);

}  // namespace phyir::cli
