// phyir scenes generate (being built).
#include "commands.h"

namespace phyir::cli {

void add_scenes_generate_command(CLI::App& scenes) {
  auto* cmd = scenes.add_subcommand("generate", "generate");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("scenes generate", 2); });
}

}  // namespace phyir::cli
