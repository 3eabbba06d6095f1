#pragma once
// The Slurm batch scripts phyir writes, for `phyir dataset slurm` and `phyir train slurm`: the
// #SBATCH header from a job's resources, the `phyir` command lines the jobs run, shell quoting
// and submission. They hold command lines with flags, so they are written here, in the CLI;
// the dataset library keeps the shard plan (dataset/slurm.h). docs/dataset.md, "On a
// cluster", and docs/model-scale.md, "Training on several processes", describe the jobs.
#include <filesystem>
#include <string>
#include <vector>

#include "phyir/dataset/slurm.h"

namespace phyir::cli {

// One job's resources, as its #SBATCH lines give them.
struct SbatchResources {
  std::string job_name;
  int nodes = 0;       // 0: as Slurm places the tasks (no line)
  int ntasks = 1;
  int cpus_per_task = 4;
  std::string time;    // each of these four: "" = the partition's default (no line)
  std::string partition;
  std::string account;
  std::string mem;
  std::vector<std::string> extra;  // verbatim sbatch options ("--qos=low"), one line each

  // Throws phyir::Error for an extra option that is not one "--option".
  void validate() const;
};

// The #SBATCH lines: job name, [nodes], tasks, CPUs per task, the working folder (`workdir`:
// jobs run where the command was run, so relative paths mean the same), requeue with logs
// appended across attempts, then `own` (the job's own options, e.g. its log), the limits
// (time, partition, account, memory) and the extra options.
std::string sbatch_header(const SbatchResources& resources, const std::filesystem::path& workdir,
                          const std::vector<std::string>& own = {});

// `phyir dataset generate` as a job array, one task per shard (requeued: a task killed by a
// node failure or preemption restarts and resumes), then `phyir dataset merge` and `verify`.
struct DatasetSlurmJob {
  std::filesystem::path phyir;       // the binary the jobs run (absolute)
  std::filesystem::path workdir;     // the jobs' working folder (absolute)
  std::filesystem::path scenes_dir;  // as given
  dataset::ShardPlan plan;           // OUT (as given) and the number of shards
  std::vector<std::string> generate_args;  // the settings flags of `generate`, repeated verbatim
  SbatchResources resources;         // of each task; its CPUs are also each generate's --threads
  std::string merge_time;            // --time of the merge job
};

// Written into OUT/slurm/, with the tasks' logs in OUT/slurm/logs (one per task):
//   generate.sbatch  the array: `phyir dataset generate ... --shard $i/N` into the shard's folder;
//   merge.sbatch     `phyir dataset merge OUT <every shard>` then `phyir dataset verify OUT`;
//   submit.sh        sbatch --parsable generate.sbatch, then merge.sbatch with
//                    --dependency=afterok:<array job> (it runs once every task succeeded) and
//                    --kill-on-invalid-dep=yes (it is cancelled if one fails for good).
struct DatasetSlurmScripts {
  std::filesystem::path folder, generate, merge, submit, logs;
};

// Writes the three scripts (atomically, executable). Throws phyir::Error on bad options.
DatasetSlurmScripts write_dataset_slurm_scripts(const DatasetSlurmJob& job);

// Runs submit.sh; returns its output (the job ids). Throws phyir::Error when sbatch fails.
std::string submit_dataset_slurm_scripts(const DatasetSlurmScripts& scripts);

// One training as Slurm tasks, one rank each, requeued from its checkpoint on failure.
struct TrainSlurmJob {
  std::filesystem::path phyir;          // the binary the job runs (absolute)
  std::filesystem::path workdir;        // the job's working folder (absolute)
  std::filesystem::path out_dir;        // the training's output folder (absolute)
  std::vector<std::string> train_args;  // the `phyir train` flags, repeated verbatim
  SbatchResources resources;            // its CPUs per task are each rank's --threads unless the flags give one
};

// OUT/slurm/train.sbatch's text, its log in `logs`.
std::string train_slurm_script(const TrainSlurmJob& job, const std::filesystem::path& logs);

// Writes a script atomically and makes it executable.
void write_script(const std::filesystem::path& path, const std::string& text);

// Runs a submission command (`bash submit.sh`, `sbatch ...`) through the shell and returns its
// output, stderr included. Throws phyir::Error naming `what` and the output when it fails.
std::string run_submission(const std::string& command, const std::string& what);

// `text` quoted for bash (single quotes, embedded ones escaped).
std::string shell_quote(const std::string& text);

}  // namespace phyir::cli
