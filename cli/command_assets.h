#pragma once
// What `phyir assets list` and `phyir assets info` share: the library folder option.
#include <CLI/CLI.hpp>

#include <string>

#include "phyir/scenes/asset_library.h"

namespace phyir::cli {

// Adds --assets DIR (default: Debian's /usr/share/sweethome3d/furniture).
void add_assets_dir_option(CLI::App& cmd, std::string& dir);

// Opens the libraries in `dir`; when the default folder is absent, the error names the
// Debian package that provides it and --assets.
scenes::AssetLibrary open_asset_library(const std::string& dir);

void add_assets_list_command(CLI::App& assets);  // command_assets_list.cpp
void add_assets_info_command(CLI::App& assets);  // command_assets_info.cpp

}  // namespace phyir::cli
