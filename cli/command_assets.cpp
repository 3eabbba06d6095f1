// phyir assets: the Sweet Home 3D furniture libraries (docs/assets.md).
#include "command_assets.h"

#include <filesystem>

#include "commands.h"
#include "phyir/core/error.h"

namespace phyir::cli {

void add_assets_dir_option(CLI::App& cmd, std::string& dir) {
  cmd.add_option("--assets", dir,
                 "Folder of .sh3f furniture libraries, or one .sh3f file (default: Debian package "
                 "sweethome3d-furniture's folder)")
      ->capture_default_str();
}

scenes::AssetLibrary open_asset_library(const std::string& dir) {
  std::error_code ec;
  if (std::filesystem::path(dir) == scenes::kDefaultAssetDir && !std::filesystem::exists(dir, ec)) {
    fail("no furniture library at {}: install the Debian package sweethome3d-furniture "
         "(apt-get install sweethome3d-furniture, or scripts/install_deps.sh) or give --assets DIR",
         dir);
  }
  return scenes::AssetLibrary::open(dir);
}

void add_assets_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "assets", "List and inspect the Sweet Home 3D furniture libraries (.sh3f): catalog entries, "
                "normalised models and their PBR materials");
  cmd->require_subcommand(1);
  add_assets_list_command(*cmd);
  add_assets_info_command(*cmd);
}

}  // namespace phyir::cli
