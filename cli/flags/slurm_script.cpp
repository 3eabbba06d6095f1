#include "slurm_script.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace phyir::cli {

namespace fs = std::filesystem;

namespace {

std::string generate_script(const DatasetSlurmJob& job, const DatasetSlurmScripts& s) {
  const dataset::ShardPlan& plan = job.plan;
  const std::string phyir = shell_quote(job.phyir.string());
  const std::string n = std::to_string(plan.shards);
  const std::string threads = "${SLURM_CPUS_PER_TASK:-" + std::to_string(job.resources.cpus_per_task) + "}";
  std::string settings;
  for (const std::string& arg : job.generate_args) settings += " " + shell_quote(arg);
  std::string g = "#!/bin/bash\n";
  g += "# Written by 'phyir dataset slurm': one array task per shard; submit with submit.sh.\n";
  g += sbatch_header(job.resources, job.workdir);
  g += fmt::format("#SBATCH --array=0-{}\n", plan.shards - 1);
  g += "#SBATCH --output=" + (s.logs / "generate-%A_%a.log").string() + "\n";
  g += "set -euo pipefail\n";
  g += "shard=${SLURM_ARRAY_TASK_ID:?run this script with sbatch (it is a job array)}\n";
  g += "echo \"phyir dataset: shard ${shard}/" + n +
       " on $(hostname), attempt $((${SLURM_RESTART_COUNT:-0} + 1)), $(date -u +%FT%TZ)\"\n";
  g += "# A requeued task runs this again: generate keeps the complete views and renders the rest.\n";
  g += "exec " + phyir + " dataset generate --scenes " + shell_quote(job.scenes_dir.string()) + " --out " +
       shell_quote(plan.root().string()) + "/" + plan.folder_name("${shard}") + " --shard ${shard}/" + n +
       " --threads " + threads + settings + "\n";
  return g;
}

std::string merge_script(const DatasetSlurmJob& job, const DatasetSlurmScripts& s) {
  const dataset::ShardPlan& plan = job.plan;
  const std::string phyir = shell_quote(job.phyir.string());
  SbatchResources merge = job.resources;
  merge.job_name += "-merge";
  merge.time = job.merge_time;
  std::string m = "#!/bin/bash\n";
  m += "# Written by 'phyir dataset slurm': joins the shards and verifies the dataset; submit.sh runs it after\n";
  m += "# every array task succeeded (--dependency=afterok).\n";
  m += sbatch_header(merge, job.workdir);
  m += "#SBATCH --output=" + (s.logs / "merge-%j.log").string() + "\n";
  m += "set -euo pipefail\n";
  m += phyir + " dataset merge " + shell_quote(plan.out_dir.string());
  for (int i = 0; i < plan.shards; ++i) m += " \\\n  " + shell_quote(plan.folder(i).string());
  m += "\nexec " + phyir + " dataset verify " + shell_quote(plan.out_dir.string()) + " --threads ${SLURM_CPUS_PER_TASK:-" +
       std::to_string(job.resources.cpus_per_task) + "}\n";
  return m;
}

std::string submit_script(const DatasetSlurmJob& job, const DatasetSlurmScripts& s) {
  std::string u = "#!/bin/bash\n";
  u += "# Written by 'phyir dataset slurm': submits the shard array and the merge job that waits for it.\n";
  u += "set -euo pipefail\n";
  u += "here=" + shell_quote(s.folder.string()) + "\n";
  u += "array=$(sbatch --parsable \"$here/generate.sbatch\")\n";
  u += "array=${array%%;*}  # --parsable prints id[;cluster]\n";
  u += "merge=$(sbatch --parsable --dependency=afterok:${array} --kill-on-invalid-dep=yes \"$here/merge.sbatch\")\n";
  u += "merge=${merge%%;*}\n";
  u += "echo \"submitted array job ${array} (" + std::to_string(job.plan.shards) +
       " shard task(s)) and merge job ${merge} (after all succeed)\"\n";
  u += "echo \"watch: squeue -j ${array},${merge}; logs: " + s.logs.string() + "\"\n";
  u += "echo \"array_job=${array} merge_job=${merge}\"\n";
  return u;
}

// Slurm does not create the folder of --output.
void create_log_folder(const fs::path& logs) {
  std::error_code ec;
  fs::create_directories(logs, ec);
  if (ec) fail("{}: cannot create: {}", logs.string(), ec.message());
}

}  // namespace

void SbatchResources::validate() const {
  if (cpus_per_task < 1) fail("--cpus-per-task {} must be at least 1", cpus_per_task);
  for (const std::string& option : extra)
    if (option.rfind("--", 0) != 0 || option.find('\n') != std::string::npos)
      fail("--sbatch '{}' must be one sbatch option starting with --", option);
}

std::string sbatch_header(const SbatchResources& r, const fs::path& workdir, const std::vector<std::string>& own) {
  std::string h;
  const auto line = [&](const std::string& option) { h += "#SBATCH " + option + "\n"; };
  line("--job-name=" + r.job_name);
  if (r.nodes > 0) line(fmt::format("--nodes={}", r.nodes));
  line(fmt::format("--ntasks={}", r.ntasks));
  line(fmt::format("--cpus-per-task={}", r.cpus_per_task));
  line("--chdir=" + workdir.string());
  line("--requeue");
  line("--open-mode=append");
  for (const std::string& option : own) line(option);
  if (!r.time.empty()) line("--time=" + r.time);
  if (!r.partition.empty()) line("--partition=" + r.partition);
  if (!r.account.empty()) line("--account=" + r.account);
  if (!r.mem.empty()) line("--mem=" + r.mem);
  for (const std::string& option : r.extra) line(option);
  return h;
}

DatasetSlurmScripts write_dataset_slurm_scripts(const DatasetSlurmJob& job) {
  job.plan.validate();
  job.resources.validate();
  if (!job.phyir.is_absolute() || !job.workdir.is_absolute())
    fail("dataset slurm: the binary and working folder must be absolute paths");
  DatasetSlurmScripts s;
  const fs::path& out = job.plan.out_dir;
  s.folder = (out.is_absolute() ? out : job.workdir / out) / "slurm";
  s.logs = s.folder / "logs";
  s.generate = s.folder / "generate.sbatch";
  s.merge = s.folder / "merge.sbatch";
  s.submit = s.folder / "submit.sh";
  create_log_folder(s.logs);
  write_script(s.generate, generate_script(job, s));
  write_script(s.merge, merge_script(job, s));
  write_script(s.submit, submit_script(job, s));
  return s;
}

std::string submit_dataset_slurm_scripts(const DatasetSlurmScripts& scripts) {
  return run_submission("bash " + shell_quote(scripts.submit.string()), scripts.submit.string());
}

std::string train_slurm_script(const TrainSlurmJob& job, const fs::path& logs) {
  std::string args;
  for (const std::string& a : job.train_args) args += " " + shell_quote(a);
  const bool threads_given = std::any_of(job.train_args.begin(), job.train_args.end(), [](const std::string& a) {
    return a == "--threads" || a.rfind("--threads=", 0) == 0;
  });
  std::string t = "#!/bin/bash\n";
  t += "# Written by 'phyir train slurm': one training as Slurm tasks, one rank each; submit with sbatch.\n";
  t += sbatch_header(job.resources, job.workdir, {"--output=" + (logs / "train-%j.log").string()});
  t += "set -euo pipefail\n";
  t += "# Rank 0's node serves the rendezvous store, on a port that follows from the job id.\n";
  t += "master=$(scontrol show hostnames \"${SLURM_JOB_NODELIST:?run this script with sbatch}\" | head -n 1)\n";
  t += "port=$((20000 + SLURM_JOB_ID % 20000))\n";
  t += "# A requeued job (a node failed, preemption) continues from the last checkpoint.\n";
  t += "resume=()\n";
  t += "if [ -f " + shell_quote((job.out_dir / "checkpoint.pt").string()) + " ]; then resume=(--resume); fi\n";
  t += "echo \"phyir train: ${SLURM_NTASKS} ranks on ${SLURM_JOB_NODELIST}, rendezvous ${master}:${port}, attempt "
       "$((${SLURM_RESTART_COUNT:-0} + 1)), $(date -u +%FT%TZ)\"\n";
  t += "# srun starts one rank per task (SLURM_PROCID is its rank); one failing rank ends them all.\n";
  t += "exec srun --kill-on-bad-exit=1 --label " + shell_quote(job.phyir.string()) + " train" + args;
  if (!threads_given) t += " --threads \"${SLURM_CPUS_PER_TASK}\"";
  t += " \\\n  --world-size \"${SLURM_NTASKS}\" --rendezvous \"tcp:${master}:${port}\" \"${resume[@]}\"\n";
  return t;
}

void write_script(const fs::path& path, const std::string& text) {
  write_file_atomic(path, text);
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

std::string run_submission(const std::string& command, const std::string& what) {
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) fail("cannot run {}", what);
  std::string output;
  char buffer[4096];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  const int status = ::pclose(pipe);
  if (status != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    fail("submitting {} failed (is sbatch on PATH and the cluster reachable?):\n{}", what, output);
  return output;
}

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace phyir::cli
