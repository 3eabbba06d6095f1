// phyir scenes (being built).
#include "commands.h"

namespace phyir::cli {

void add_scenes_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("scenes", "scenes");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("scenes", 2); });
}

}  // namespace phyir::cli
