// phyir scenes: inspect glTF files, generate procedural rooms and skies.
#include "commands.h"

namespace phyir::cli {

void add_scenes_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("scenes", "Inspect glTF scenes and generate procedural indoor rooms");
  cmd->require_subcommand(1);
  add_scenes_info_command(*cmd);
  add_scenes_generate_command(*cmd);
  add_scenes_sky_command(*cmd);
}

}  // namespace phyir::cli
