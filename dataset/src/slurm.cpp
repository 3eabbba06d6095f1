#include "phyir/dataset/slurm.h"

#include <sys/wait.h>

#include <cstdio>

#include <fmt/format.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"

namespace phyir::dataset {

namespace fs = std::filesystem;

namespace {

std::string sbatch_header(const SlurmOptions& o, const std::string& job_name, const std::string& time) {
  std::string h;
  const auto line = [&](const std::string& option) { h += "#SBATCH " + option + "\n"; };
  line("--job-name=" + job_name);
  line("--ntasks=1");
  line(fmt::format("--cpus-per-task={}", o.cpus_per_task));
  line("--chdir=" + o.workdir.string());
  line("--requeue");
  line("--open-mode=append");
  if (!time.empty()) line("--time=" + time);
  if (!o.partition.empty()) line("--partition=" + o.partition);
  if (!o.account.empty()) line("--account=" + o.account);
  if (!o.mem.empty()) line("--mem=" + o.mem);
  for (const std::string& extra : o.sbatch_options) line(extra);
  return h;
}

void write_script(const fs::path& path, const std::string& text) {
  write_file_atomic(path, text);
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

}  // namespace

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

fs::path shard_folder(const fs::path& out_dir, int index, int count) {
  return out_dir / "shards" / fmt::format("shard-{}-of-{}", index, count);
}

SlurmScripts write_slurm_scripts(const SlurmOptions& o) {
  if (o.shards < 1) fail("--shards {} must be at least 1", o.shards);
  if (o.cpus_per_task < 1) fail("--cpus-per-task {} must be at least 1", o.cpus_per_task);
  if (!o.phyir.is_absolute() || !o.workdir.is_absolute()) fail("dataset slurm: the binary and working folder must be absolute paths");
  for (const std::string& extra : o.sbatch_options)
    if (extra.rfind("--", 0) != 0 || extra.find('\n') != std::string::npos)
      fail("--sbatch '{}' must be one sbatch option starting with --", extra);
  SlurmScripts s;
  const fs::path out_abs = o.out_dir.is_absolute() ? o.out_dir : o.workdir / o.out_dir;
  s.folder = out_abs / "slurm";
  s.logs = s.folder / "logs";
  s.generate = s.folder / "generate.sbatch";
  s.merge = s.folder / "merge.sbatch";
  s.submit = s.folder / "submit.sh";
  std::error_code ec;
  fs::create_directories(s.logs, ec);  // Slurm does not create the folders of --output
  if (ec) fail("{}: cannot create: {}", s.logs.string(), ec.message());

  const std::string phyir = shell_quote(o.phyir.string());
  const std::string n = std::to_string(o.shards);
  std::string settings;
  for (const std::string& arg : o.generate_args) settings += " " + shell_quote(arg);

  std::string g = "#!/bin/bash\n";
  g += "# Written by 'phyir dataset slurm': one array task per shard; submit with submit.sh.\n";
  g += sbatch_header(o, o.job_name, o.time);
  g += fmt::format("#SBATCH --array=0-{}\n", o.shards - 1);
  g += "#SBATCH --output=" + (s.logs / "generate-%A_%a.log").string() + "\n";
  g += "set -euo pipefail\n";
  g += "shard=${SLURM_ARRAY_TASK_ID:?run this script with sbatch (it is a job array)}\n";
  g += "echo \"phyir dataset: shard ${shard}/" + n +
       " on $(hostname), attempt $((${SLURM_RESTART_COUNT:-0} + 1)), $(date -u +%FT%TZ)\"\n";
  g += "# A requeued task runs this again: generate keeps the complete views and renders the rest.\n";
  g += "exec " + phyir + " dataset generate --scenes " + shell_quote(o.scenes_dir.string()) + " --out " +
       shell_quote((o.out_dir / "shards").string()) + "/shard-${shard}-of-" + n + " --shard ${shard}/" + n +
       " --threads ${SLURM_CPUS_PER_TASK:-" + std::to_string(o.cpus_per_task) + "}" + settings + "\n";
  write_script(s.generate, g);

  std::string m = "#!/bin/bash\n";
  m += "# Written by 'phyir dataset slurm': joins the shards and verifies the dataset; submit.sh runs it after\n";
  m += "# every array task succeeded (--dependency=afterok).\n";
  m += sbatch_header(o, o.job_name + "-merge", o.merge_time);
  m += "#SBATCH --output=" + (s.logs / "merge-%j.log").string() + "\n";
  m += "set -euo pipefail\n";
  m += phyir + " dataset merge " + shell_quote(o.out_dir.string());
  for (int i = 0; i < o.shards; ++i) m += " \\\n  " + shell_quote(shard_folder(o.out_dir, i, o.shards).string());
  m += "\nexec " + phyir + " dataset verify " + shell_quote(o.out_dir.string()) + " --threads ${SLURM_CPUS_PER_TASK:-" +
       std::to_string(o.cpus_per_task) + "}\n";
  write_script(s.merge, m);

  std::string u = "#!/bin/bash\n";
  u += "# Written by 'phyir dataset slurm': submits the shard array and the merge job that waits for it.\n";
  u += "set -euo pipefail\n";
  u += "here=" + shell_quote(s.folder.string()) + "\n";
  u += "array=$(sbatch --parsable \"$here/generate.sbatch\")\n";
  u += "array=${array%%;*}  # --parsable prints id[;cluster]\n";
  u += "merge=$(sbatch --parsable --dependency=afterok:${array} --kill-on-invalid-dep=yes \"$here/merge.sbatch\")\n";
  u += "merge=${merge%%;*}\n";
  u += "echo \"submitted array job ${array} (" + n + " shard task(s)) and merge job ${merge} (after all succeed)\"\n";
  u += "echo \"watch: squeue -j ${array},${merge}; logs: " + s.logs.string() + "\"\n";
  u += "echo \"array_job=${array} merge_job=${merge}\"\n";
  write_script(s.submit, u);
  return s;
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

std::string submit_slurm_scripts(const SlurmScripts& scripts) {
  return run_submission("bash " + shell_quote(scripts.submit.string()), scripts.submit.string());
}

}  // namespace phyir::dataset
