#pragma once
// The flags of one training stage, registered on a command: `phyir train` itself, and the
// command line that `phyir train slurm` checks before repeating it in its batch script.
#ifdef PHYIR_HAVE_MODEL
#include <string>
#include <vector>

#include "commands.h"
#include "phyir/model/training.h"

namespace phyir::cli {

struct TrainFlags {
  model::TrainOptions options;
  std::string stage = "gmnet";
  bool quiet = false;
  model::LossWeights weights;  // the --w-* flags given (the others keep the stage's defaults)
  std::vector<double> jitter;  // --exposure-jitter LO,HI
  CLI::App* cmd = nullptr;

  // After parsing: the stage, weights, jitter and progress into `options`. Throws phyir::Error
  // (a missing --data or --out, an unknown stage).
  void finish();
};

// Registers every training flag on `cmd`, writing into `flags` (which must outlive `cmd`).
void add_train_flags(CLI::App* cmd, TrainFlags& flags);

}  // namespace phyir::cli
#endif
