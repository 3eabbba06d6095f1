// phyir train slurm: one training as a Slurm job of N tasks, one rank each (docs/commands/train.md).
#ifdef PHYIR_HAVE_MODEL
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "commands.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/dataset/slurm.h"
#include "train_flags.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

struct TrainSlurmFlags {
  std::vector<std::string> train_args;  // after --: the flags of phyir train
  int ntasks = 2;
  int nodes = 0;                        // 0: as Slurm places the tasks
  int cpus_per_task = 4;
  std::string time, partition, account, mem, job_name = "phyir-train", phyir;
  std::vector<std::string> sbatch_options;
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

std::string sbatch_lines(const TrainSlurmFlags& s, const fs::path& workdir, const fs::path& logs) {
  std::string h;
  const auto line = [&](const std::string& option) { h += "#SBATCH " + option + "\n"; };
  line("--job-name=" + s.job_name);
  if (s.nodes > 0) line(fmt::format("--nodes={}", s.nodes));
  line(fmt::format("--ntasks={}", s.ntasks));
  line(fmt::format("--cpus-per-task={}", s.cpus_per_task));
  line("--chdir=" + workdir.string());
  line("--requeue");
  line("--open-mode=append");
  line("--output=" + (logs / "train-%j.log").string());
  if (!s.time.empty()) line("--time=" + s.time);
  if (!s.partition.empty()) line("--partition=" + s.partition);
  if (!s.account.empty()) line("--account=" + s.account);
  if (!s.mem.empty()) line("--mem=" + s.mem);
  for (const std::string& extra : s.sbatch_options) line(extra);
  return h;
}

std::string train_script(const TrainSlurmFlags& s, const TrainFlags& train, const fs::path& workdir,
                         const fs::path& logs) {
  using dataset::shell_quote;
  const fs::path out = fs::absolute(workdir / train.options.out_dir);
  std::string args;
  for (const std::string& a : s.train_args) args += " " + shell_quote(a);
  const bool threads_given = std::any_of(s.train_args.begin(), s.train_args.end(), [](const std::string& a) {
    return a == "--threads" || a.rfind("--threads=", 0) == 0;
  });
  std::string t = "#!/bin/bash\n";
  t += "# Written by 'phyir train slurm': one training as Slurm tasks, one rank each; submit with sbatch.\n";
  t += sbatch_lines(s, workdir, logs);
  t += "set -euo pipefail\n";
  t += "# Rank 0's node serves the rendezvous store, on a port that follows from the job id.\n";
  t += "master=$(scontrol show hostnames \"${SLURM_JOB_NODELIST:?run this script with sbatch}\" | head -n 1)\n";
  t += "port=$((20000 + SLURM_JOB_ID % 20000))\n";
  t += "# A requeued job (a node failed, preemption) continues from the last checkpoint.\n";
  t += "resume=()\n";
  t += "if [ -f " + shell_quote((out / "checkpoint.pt").string()) + " ]; then resume=(--resume); fi\n";
  t += "echo \"phyir train: ${SLURM_NTASKS} ranks on ${SLURM_JOB_NODELIST}, rendezvous ${master}:${port}, attempt "
       "$((${SLURM_RESTART_COUNT:-0} + 1)), $(date -u +%FT%TZ)\"\n";
  t += "# srun starts one rank per task (SLURM_PROCID is its rank); one failing rank ends them all.\n";
  t += "exec srun --kill-on-bad-exit=1 --label " + shell_quote(s.phyir) + " train" + args;
  if (!threads_given) t += " --threads \"${SLURM_CPUS_PER_TASK}\"";
  t += " \\\n  --world-size \"${SLURM_NTASKS}\" --rendezvous \"tcp:${master}:${port}\" \"${resume[@]}\"\n";
  return t;
}

}  // namespace

void add_train_slurm_command(CLI::App& train) {
  auto s = std::make_shared<TrainSlurmFlags>();
  auto* cmd = train.add_subcommand(
      "slurm", "Write (and with --submit, submit) a Slurm batch script that runs one training as N tasks, one rank "
               "each, requeued from its checkpoint on failure: OUT/slurm/train.sbatch. The phyir train flags come "
               "after --");
  cmd->add_option("--ntasks", s->ntasks, "ranks (Slurm tasks) in all")->check(CLI::Range(2, 1 << 16))
      ->capture_default_str();
  cmd->add_option("--nodes", s->nodes, "nodes to spread them over (default: as Slurm places them)");
  cmd->add_option("--cpus-per-task", s->cpus_per_task, "CPUs per rank (its --threads unless the flags give one)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--time", s->time, "time limit (sbatch --time), e.g. 24:00:00");
  cmd->add_option("--partition", s->partition, "sbatch --partition");
  cmd->add_option("--account", s->account, "sbatch --account");
  cmd->add_option("--mem", s->mem, "memory per node (sbatch --mem), e.g. 32G");
  cmd->add_option("--job-name", s->job_name, "job name")->capture_default_str();
  cmd->add_option("--sbatch", s->sbatch_options, "extra sbatch option, e.g. --sbatch=--qos=low (repeatable)");
  cmd->add_option("--phyir", s->phyir, "phyir binary the job runs (default: this one)");
  cmd->add_flag("--submit", s->submit, "submit the job now (sbatch)");
  cmd->add_option("train-flags", s->train_args, "-- then the phyir train flags (--data, --out, --stage, ...)")
      ->required();
  cmd->callback([s] {
    const TrainFlags train = checked_train_flags(s->train_args);
    for (const std::string& extra : s->sbatch_options)
      if (extra.rfind("--", 0) != 0 || extra.find('\n') != std::string::npos)
        fail("--sbatch '{}' must be one sbatch option starting with --", extra);
    s->phyir = s->phyir.empty() ? this_executable().string() : fs::absolute(s->phyir).string();
    const fs::path workdir = fs::current_path();
    const fs::path folder = fs::absolute(workdir / train.options.out_dir) / "slurm";
    const fs::path logs = folder / "logs";
    std::error_code ec;
    fs::create_directories(logs, ec);  // Slurm does not create the folder of --output
    if (ec) fail("{}: cannot create: {}", logs.string(), ec.message());
    const fs::path script = folder / "train.sbatch";
    write_file_atomic(script, train_script(*s, train, workdir, logs));
    fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
    std::printf("wrote %s (%d ranks; logs in %s)\n", script.c_str(), s->ntasks, logs.c_str());
    if (!s->submit) {
      std::printf("submit with: sbatch %s\n", script.c_str());
      return;
    }
    const std::string output =
        dataset::run_submission("sbatch --parsable " + dataset::shell_quote(script.string()), script.string());
    const std::string id = output.substr(0, output.find_first_of(";\n"));
    std::printf("submitted job %s; watch: squeue -j %s; log: %s/train-%s.log\njob=%s\n", id.c_str(), id.c_str(),
                logs.c_str(), id.c_str(), id.c_str());
  });
}

}  // namespace phyir::cli
#endif
