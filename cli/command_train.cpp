// phyir train: one stage of the PhyIR network's training (appendix B.1). docs/commands/train.md
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "commands.h"
#include "torch_handoff.h"

#ifdef PHYIR_HAVE_MODEL
#include "flag_registry.h"
#include "local_ranks.h"
#include "phyir/core/error.h"
#include "phyir/model/training.h"
#include "train_flags.h"
#endif

namespace phyir::cli {

#ifdef PHYIR_HAVE_MODEL

void add_train_command(CLI::App& app) {
  auto f = std::make_shared<TrainFlags>();
  auto nproc = std::make_shared<int>(1);
  auto* cmd = app.add_subcommand(
      "train", "Train one stage of the PhyIR network (gmnet, lnet, joint, gsnet): checkpoint.pt, best.pt, "
               "train_log.csv/json, val_log.csv, loss_curve.png");
  add_train_flags(cmd, *f);
  model::DistributedOptions& d = f->options.distributed;
  auto* dist = cmd->add_option_group("data-parallel", "several processes train as one at the same --batch "
                                                      "(docs/model-scale.md \"Training on several processes\")");
  dist->add_option("--nproc", *nproc, "train as N local processes, --batch split between them (each with --threads "
                   "threads)")->check(CLI::PositiveNumber)->capture_default_str();
  dist->add_option("--world-size", d.world_size, "ranks in all (set by --nproc and by train slurm's script)")
      ->check(CLI::PositiveNumber);
  dist->add_option("--rank", d.rank, "this process's rank, 0..world-size-1 (default: $SLURM_PROCID)")
      ->check(CLI::NonNegativeNumber);
  dist->add_option("--rendezvous", d.rendezvous, "where the ranks meet: file:PATH (a shared file system; must not "
                   "exist yet) or tcp:HOST:PORT (rank 0 serves it on HOST)");
  dist->add_option("--dist-timeout", d.timeout_seconds, "seconds a rank waits for the others (rank 0's validation "
                   "included) before it fails")->check(CLI::PositiveNumber)->capture_default_str();
  for (const auto& [setting, flag] : {std::pair<const char*, const char*>{"distributed.world_size", "--world-size"},
                                      {"distributed.rank", "--rank"},
                                      {"distributed.rendezvous", "--rendezvous"},
                                      {"distributed.timeout_seconds", "--dist-timeout"}})
    sets(cmd, setting, flag);
  add_train_slurm_command(*cmd);
  cmd->callback([f, nproc, cmd] {
    if (cmd->got_subcommand("slurm")) return;
    f->finish();
    model::DistributedOptions& d = f->options.distributed;
    if (*nproc > 1) {
      if (d.world_size > 1) fail("--nproc and --world-size: give one of them (--nproc starts the ranks itself)");
      run_local_ranks(*nproc, without_option(command_line(), "--nproc"), f->options.out_dir);
      return;
    }
    if (d.world_size > 1 && cmd->count("--rank") == 0) {
      const char* slurm_rank = std::getenv("SLURM_PROCID");
      if (!slurm_rank) fail("--world-size {}: give --rank (or run under srun, which sets SLURM_PROCID)", d.world_size);
      d.rank = std::atoi(slurm_rank);
    }
    if (d.world_size > 1 && d.rendezvous.empty()) fail("--world-size {}: give --rendezvous", d.world_size);
    model::train(f->options);
  });
}

#else

// `phyir` lists the command in --help. With the network built, main() hands the command to
// phyir-torch before parsing (torch_handoff.h); without it, the callback says it was not built.
void add_train_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("train", "Train the PhyIR network" + torch_build_note());
  // Every argument after the command is the network command's: kept here, not passed up to
  // phyir (main() sets fallthrough, which would refuse them there).
  cmd->fallthrough(false)->prefix_command();
  cmd->callback([] { run_in_torch_cli("train"); });
}

#endif

}  // namespace phyir::cli
