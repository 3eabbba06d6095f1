// phyir train: placeholder until issue 6 lands; listed in --help so users see it coming.
#include "commands.h"

namespace phyir::cli {

void add_train_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("train", "Train the PhyIR network (arrives with issue 6)");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("train", 6); });
}

}  // namespace phyir::cli
