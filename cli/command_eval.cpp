// phyir eval: placeholder until issue 7 lands; listed in --help so users see it coming.
#include "commands.h"

namespace phyir::cli {

void add_eval_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("eval", "Compute the paper's metrics and tables (arrives with issue 7)");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("eval", 7); });
}

}  // namespace phyir::cli
