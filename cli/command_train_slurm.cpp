// phyir train slurm: one training as a Slurm job of N tasks, one rank each (docs/commands/train.md).
#ifdef PHYIR_HAVE_MODEL
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "phyir/core/error.h"
#include "slurm_script.h"
#include "train_flags.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

struct TrainSlurmFlags {
  std::vector<std::string> train_args;  // after --: the flags of phyir train
  SbatchResources resources;
  std::string phyir;
  bool submit = false;
};

// Parses the training flags as `phyir train` would, so a typo fails here, not in the queue.
TrainFlags checked_train_flags(const std::vector<std::string>& args) {
  TrainFlags f;
  CLI::App app("phyir train", "phyir train");
  add_train_flags(&app, f);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 reads a vector from its end
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    fail("train slurm: the training flags after -- do not parse: {} (--nproc, --rank, --world-size and "
         "--rendezvous are the script's to set)", e.what());
  }
  f.finish();
  return f;
}

}  // namespace

void add_train_slurm_command(CLI::App& train) {
  auto s = std::make_shared<TrainSlurmFlags>();
  SbatchResources& r = s->resources;
  r.job_name = "phyir-train";
  r.ntasks = 2;
  auto* cmd = train.add_subcommand(
      "slurm", "Write (and with --submit, submit) a Slurm batch script that runs one training as N tasks, one rank "
               "each, requeued from its checkpoint on failure: OUT/slurm/train.sbatch. The phyir train flags come "
               "after --");
  cmd->add_option("--ntasks", r.ntasks, "ranks (Slurm tasks) in all")->check(CLI::Range(2, 1 << 16))
      ->capture_default_str();
  cmd->add_option("--nodes", r.nodes, "nodes to spread them over (default: as Slurm places them)");
  cmd->add_option("--cpus-per-task", r.cpus_per_task, "CPUs per rank (its --threads unless the flags give one)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--time", r.time, "time limit (sbatch --time), e.g. 24:00:00");
  cmd->add_option("--partition", r.partition, "sbatch --partition");
  cmd->add_option("--account", r.account, "sbatch --account");
  cmd->add_option("--mem", r.mem, "memory per node (sbatch --mem), e.g. 32G");
  cmd->add_option("--job-name", r.job_name, "job name")->capture_default_str();
  cmd->add_option("--sbatch", r.extra, "extra sbatch option, e.g. --sbatch=--qos=low (repeatable)");
  cmd->add_option("--phyir", s->phyir, "phyir binary the job runs (default: this one)");
  cmd->add_flag("--submit", s->submit, "submit the job now (sbatch)");
  cmd->add_option("train-flags", s->train_args, "-- then the phyir train flags (--data, --out, --stage, ...)")
      ->required();
  cmd->callback([s] {
    const TrainFlags train = checked_train_flags(s->train_args);
    s->resources.validate();
    TrainSlurmJob job;
    job.phyir = s->phyir.empty() ? this_executable() : fs::absolute(s->phyir);
    job.workdir = fs::current_path();
    job.out_dir = fs::absolute(job.workdir / train.options.out_dir);
    job.train_args = s->train_args;
    job.resources = s->resources;
    const fs::path folder = job.out_dir / "slurm";
    const fs::path logs = folder / "logs";
    std::error_code ec;
    fs::create_directories(logs, ec);  // Slurm does not create the folder of the job's log
    if (ec) fail("{}: cannot create: {}", logs.string(), ec.message());
    const fs::path script = folder / "train.sbatch";
    write_script(script, train_slurm_script(job, logs));
    std::printf("wrote %s (%d ranks; logs in %s)\n", script.c_str(), job.resources.ntasks, logs.c_str());
    if (!s->submit) {
      std::printf("submit with: sbatch %s\n", script.c_str());
      return;
    }
    const std::string output = run_submission("sbatch --parsable " + shell_quote(script.string()), script.string());
    const std::string id = output.substr(0, output.find_first_of(";\n"));
    std::printf("submitted job %s; watch: squeue -j %s; log: %s/train-%s.log\njob=%s\n", id.c_str(), id.c_str(),
                logs.c_str(), id.c_str(), id.c_str());
  });
}

}  // namespace phyir::cli
#endif
