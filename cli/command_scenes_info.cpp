// phyir scenes info (being built).
#include "commands.h"

namespace phyir::cli {

void add_scenes_info_command(CLI::App& scenes) {
  auto* cmd = scenes.add_subcommand("info", "info");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("scenes info", 2); });
}

}  // namespace phyir::cli
