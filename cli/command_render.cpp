// phyir render (being built).
#include "commands.h"

namespace phyir::cli {

void add_render_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "render");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("render", 2); });
}

}  // namespace phyir::cli
