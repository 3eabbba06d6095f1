// phyir scenes info FILE [--json]: what a glTF file holds once loaded, and what the loader
// skipped or approximated.
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/scenes/scene_info.h"

namespace phyir::cli {

namespace {

struct InfoOptions {
  std::string file;
  bool json = false;
};

void run(const InfoOptions& options) {
  // Loading textures too, so that a broken or missing image is reported here.
  const scenes::Scene scene = scenes::load_gltf(options.file);
  if (options.json) {
    std::cout << scenes::scene_info_json(scene).dump(2) << "\n";
  } else {
    std::cout << scenes::scene_info_text(scene);
  }
}

}  // namespace

void add_scenes_info_command(CLI::App& scenes) {
  auto options = std::make_shared<InfoOptions>();
  auto* cmd = scenes.add_subcommand(
      "info",
      "Load a glTF 2.0 file (.gltf or .glb) and summarise it: meshes, triangles, materials "
      "(textures, extensions, emissive/transmissive), emitters and their power, cameras, "
      "candidate viewpoints, bounds, source counts and the loader's warnings");
  cmd->add_option("file", options->file, "the .gltf or .glb file")->required();
  cmd->add_flag("--json", options->json, "print pretty JSON instead of text");
  cmd->callback([options] { run(*options); });
}

}  // namespace phyir::cli
