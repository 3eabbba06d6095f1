#pragma once
// `phyir dataset slurm`: the dataset as a Slurm job array (docs/dataset.md, "On a cluster").
// Writes three scripts into OUT/slurm/:
//   generate.sbatch  one array task per shard: `phyir dataset generate ... --shard $i/N`
//                    into OUT/shards/shard-<i>-of-<N>, --requeue (a task killed by a node
//                    failure or preemption restarts and resumes: completed views are kept),
//                    one log per task in OUT/slurm/logs (appended across requeues);
//   merge.sbatch     `phyir dataset merge OUT <every shard>` then `phyir dataset verify OUT`;
//   submit.sh        sbatch --parsable generate.sbatch, then merge.sbatch with
//                    --dependency=afterok:<array job> (it runs once every task succeeded) and
//                    --kill-on-invalid-dep=yes (it is cancelled if one fails for good).
// Jobs run in the folder the command was run in (--chdir), so relative paths mean the same.
#include <filesystem>
#include <string>
#include <vector>

namespace phyir::dataset {

struct SlurmOptions {
  std::filesystem::path phyir;       // the binary the jobs run (absolute)
  std::filesystem::path workdir;     // the jobs' working folder (absolute)
  std::filesystem::path scenes_dir;  // as given
  std::filesystem::path out_dir;     // as given
  std::vector<std::string> generate_args;  // the settings flags of `generate`, repeated verbatim
  int shards = 1;
  int cpus_per_task = 4;             // also the generate --threads of each task
  std::string time;                  // --time of each task ("" = the partition's default)
  std::string merge_time;            // --time of the merge job
  std::string partition;
  std::string account;
  std::string mem;                   // --mem of each task, e.g. 8G
  std::string job_name = "phyir-dataset";
  std::vector<std::string> sbatch_options;  // extra #SBATCH lines ("--qos=low", ...)
};

struct SlurmScripts {
  std::filesystem::path folder, generate, merge, submit, logs;
};

// OUT/shards/shard-<i>-of-<N>
std::filesystem::path shard_folder(const std::filesystem::path& out_dir, int index, int count);

// Writes the three scripts (atomically, executable). Throws phyir::Error on bad options.
SlurmScripts write_slurm_scripts(const SlurmOptions& options);

// Runs submit.sh; returns its output (the job ids). Throws phyir::Error when sbatch fails.
std::string submit_slurm_scripts(const SlurmScripts& scripts);

// Runs a submission command (`bash submit.sh`, `sbatch ...`) through the shell and returns its
// output, stderr included. Throws phyir::Error naming `what` and the output when it fails.
std::string run_submission(const std::string& command, const std::string& what);

// 'text' quoted for bash (single quotes, embedded ones escaped).
std::string shell_quote(const std::string& text);

}  // namespace phyir::dataset
