// phyir infer: placeholder until issue 6 lands; listed in --help so users see it coming.
#include "commands.h"

namespace phyir::cli {

void add_infer_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("infer", "Run a trained network on panoramas (arrives with issue 6)");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("infer", 6); });
}

}  // namespace phyir::cli
