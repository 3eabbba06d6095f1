// phyir dataset: placeholder until issue 5 lands; listed in --help so users see it coming.
#include "commands.h"

namespace phyir::cli {

void add_dataset_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("dataset", "Render many views per scene into a dataset (arrives with issue 5)");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("dataset", 5); });
}

}  // namespace phyir::cli
