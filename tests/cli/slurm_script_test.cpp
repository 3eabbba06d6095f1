// The Slurm scripts: a job array with one task per shard, requeue, per-task logs, the
// settings flags repeated verbatim and quoted, and a merge + verify job submitted with
// afterok on the array; the training's script with its log, ranks and resume.
// (tests/scripts/slurm_*_test.sh run them on a real Slurm.)
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "phyir/core/error.h"
#include "phyir/core/setting_error.h"
#include "slurm_script.h"

namespace phyir::cli {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

fs::path fresh_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() / ("phyir_cli_test_" + std::to_string(::getpid())) / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(SlurmScript, DatasetScriptsHoldTheArrayTheMergeAndTheDependency) {
  const fs::path dir = fresh_dir();
  DatasetSlurmJob job;
  job.phyir = "/opt/phyir/bin/phyir";
  job.workdir = dir;
  job.scenes_dir = "rooms";
  job.plan = {"data set", 3};  // a space, to check quoting
  job.generate_args = {"--preset", "tiny", "--views-per-scene", "2", "--split", "0.5,0.5,0"};
  job.resources.job_name = "phyir-dataset";
  job.resources.cpus_per_task = 2;
  job.resources.time = "01:00:00";
  job.resources.partition = "cpu";
  job.resources.extra = {"--qos=low"};
  const DatasetSlurmScripts s = write_dataset_slurm_scripts(job);
  EXPECT_EQ(s.folder, dir / "data set" / "slurm");
  EXPECT_TRUE(fs::is_directory(s.logs));

  const std::string g = read_text(s.generate);
  EXPECT_THAT(g, HasSubstr("#SBATCH --job-name=phyir-dataset\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=2\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --requeue\n#SBATCH --open-mode=append\n#SBATCH --time=01:00:00\n"
                           "#SBATCH --partition=cpu\n#SBATCH --qos=low\n#SBATCH --array=0-2\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --chdir=" + dir.string() + "\n"));
  EXPECT_THAT(g, HasSubstr("generate-%A_%a.log"));
  EXPECT_THAT(g, HasSubstr("'/opt/phyir/bin/phyir' dataset generate --scenes 'rooms' --out 'data set/shards'/shard-${shard}-of-3 "
                           "--shard ${shard}/3 --threads ${SLURM_CPUS_PER_TASK:-2} '--preset' 'tiny' "
                           "'--views-per-scene' '2' '--split' '0.5,0.5,0'"));

  const std::string m = read_text(s.merge);
  EXPECT_THAT(m, HasSubstr("#SBATCH --job-name=phyir-dataset-merge\n"));
  EXPECT_THAT(m, HasSubstr("dataset merge 'data set' \\\n  'data set/shards/shard-0-of-3' \\\n  'data set/shards/shard-1-of-3' "
                           "\\\n  'data set/shards/shard-2-of-3'\n"));
  EXPECT_THAT(m, HasSubstr("dataset verify 'data set'"));
  EXPECT_THAT(m, Not(HasSubstr("--array")));
  EXPECT_THAT(m, Not(HasSubstr("--time")));

  const std::string u = read_text(s.submit);
  EXPECT_THAT(u, HasSubstr("sbatch --parsable \"$here/generate.sbatch\""));
  EXPECT_THAT(u, HasSubstr("--dependency=afterok:${array} --kill-on-invalid-dep=yes"));
  EXPECT_TRUE((fs::status(s.submit).permissions() & fs::perms::owner_exec) != fs::perms::none);
}

TEST(SlurmScript, TrainScriptNamesItsLogBeforeTheLimits) {
  TrainSlurmJob job;
  job.phyir = "/opt/phyir";
  job.workdir = "/work dir";
  job.out_dir = "/work dir/run";
  job.train_args = {"--data", "ds", "--out", "run"};
  job.resources.job_name = "phyir-train";
  job.resources.nodes = 2;
  job.resources.ntasks = 4;
  job.resources.time = "02:00:00";
  const std::string t = train_slurm_script(job, "/work dir/run/slurm/logs");
  EXPECT_THAT(t, HasSubstr("#SBATCH --job-name=phyir-train\n#SBATCH --nodes=2\n#SBATCH --ntasks=4\n"));
  EXPECT_THAT(t, HasSubstr("#SBATCH --open-mode=append\n#SBATCH --output=/work dir/run/slurm/logs/train-%j.log\n"
                           "#SBATCH --time=02:00:00\n"));
  EXPECT_THAT(t, HasSubstr("if [ -f '/work dir/run/checkpoint.pt' ]; then resume=(--resume); fi\n"));
  EXPECT_THAT(t, HasSubstr("'/opt/phyir' train '--data' 'ds' '--out' 'run' --threads \"${SLURM_CPUS_PER_TASK}\""));
  job.train_args.push_back("--threads=2");
  EXPECT_THAT(train_slurm_script(job, "logs"), Not(HasSubstr("SLURM_CPUS_PER_TASK")));
}

TEST(SlurmScript, QuotingAndBadOptions) {
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(dataset::ShardPlan({"out", 5}).folder(2), fs::path("out/shards/shard-2-of-5"));
  DatasetSlurmJob job;
  job.phyir = "/bin/phyir";
  job.workdir = fresh_dir();
  job.plan = {"out", 0};
  EXPECT_THROW(write_dataset_slurm_scripts(job), SettingError);
  job.plan.shards = 2;
  job.resources.extra = {"qos=low"};
  EXPECT_THROW(write_dataset_slurm_scripts(job), Error);
}

}  // namespace
}  // namespace phyir::cli
