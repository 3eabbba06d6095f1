// phyir bench (being built).
#include "commands.h"

namespace phyir::cli {

void add_bench_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("bench", "bench");
  cmd->allow_extras();
  cmd->callback([] { not_yet_available("bench", 2); });
}

}  // namespace phyir::cli
