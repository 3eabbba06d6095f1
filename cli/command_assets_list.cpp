// phyir assets list [--assets DIR] [--category C]: the catalog entries, one per line.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>

#include "command_assets.h"
#include "phyir/core/error.h"

namespace phyir::cli {

namespace {

struct ListOptions {
  std::string dir = scenes::kDefaultAssetDir.string();
  std::string category;
};

std::string flags(const scenes::AssetEntry& e) {
  std::string text;
  if (e.is_door_or_window) text += e.opening.kind == scenes::OpeningKind::Door ? " door" : " window";
  if (e.is_light()) text += fmt::format(" light x{}", e.light_sources.size());
  if (!e.movable) text += " fixed";
  return text;
}

void print_archives(const scenes::AssetLibrary& library) {
  for (const scenes::AssetArchive& a : library.archives()) {
    std::cout << fmt::format("# {} ({} entries, {}): {}\n", a.name, a.entry_count, a.path.filename().string(), a.licence);
  }
}

void run(const ListOptions& options) {
  const scenes::AssetLibrary library = open_asset_library(options.dir);
  const auto counts = library.category_counts();
  if (!options.category.empty() && counts.count(options.category) == 0) {
    std::string known;
    for (const auto& [name, count] : counts) known += (known.empty() ? "" : ", ") + name;
    fail("no category '{}' (categories: {})", options.category, known);
  }
  print_archives(library);
  std::cout << "# id | category | name | width x height x depth (m) | creator | flags\n";
  for (const scenes::AssetEntry& e : library.entries()) {
    if (!options.category.empty() && e.category != options.category) continue;
    std::cout << fmt::format("{} | {} | {} | {:.3f} x {:.3f} x {:.3f} | {} |{}\n", e.id, e.category, e.name,
                             e.size_m.x, e.size_m.y, e.size_m.z, e.creator, flags(e));
  }
  std::cout << "# categories:";
  for (const auto& [name, count] : counts) std::cout << fmt::format(" {} {};", name, count);
  std::cout << fmt::format(" total {}\n", library.entries().size());
}

}  // namespace

void add_assets_list_command(CLI::App& assets) {
  auto options = std::make_shared<ListOptions>();
  auto* cmd = assets.add_subcommand(
      "list", "One line per catalog entry: id, category, name, size in metres, creator, door/window/light "
              "flags; the libraries' licences first and the counts per category last");
  add_assets_dir_option(*cmd, options->dir);
  cmd->add_option("--category", options->category, "Only this category (exact name, e.g. \"Living room\")");
  cmd->callback([options] { run(*options); });
}

}  // namespace phyir::cli
