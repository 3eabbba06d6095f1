// The Slurm scripts: a job array with one task per shard, requeue, per-task logs, the
// settings flags repeated verbatim and quoted, and a merge + verify job submitted with
// afterok on the array. (tests/scripts/slurm_dataset_test.sh runs them on a real Slurm.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/dataset/slurm.h"

namespace phyir::dataset {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(Slurm, ScriptsHoldTheArrayTheMergeAndTheDependency) {
  const auto dir = test::fresh_test_dir();
  SlurmOptions o;
  o.phyir = "/opt/phyir/bin/phyir";
  o.workdir = dir;
  o.scenes_dir = "rooms";
  o.out_dir = "data set";  // a space, to check quoting
  o.generate_args = {"--preset", "tiny", "--views-per-scene", "2", "--split", "0.5,0.5,0"};
  o.shards = 3;
  o.cpus_per_task = 2;
  o.time = "01:00:00";
  o.partition = "cpu";
  o.sbatch_options = {"--qos=low"};
  const SlurmScripts s = write_slurm_scripts(o);
  EXPECT_EQ(s.folder, dir / "data set" / "slurm");
  EXPECT_TRUE(std::filesystem::is_directory(s.logs));

  const std::string g = read_file(s.generate);
  EXPECT_THAT(g, HasSubstr("#SBATCH --array=0-2\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --requeue\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --cpus-per-task=2\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --time=01:00:00\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --partition=cpu\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --qos=low\n"));
  EXPECT_THAT(g, HasSubstr("#SBATCH --chdir=" + dir.string() + "\n"));
  EXPECT_THAT(g, HasSubstr("generate-%A_%a.log"));
  EXPECT_THAT(g, HasSubstr("'/opt/phyir/bin/phyir' dataset generate --scenes 'rooms' --out 'data set/shards'/shard-${shard}-of-3 "
                           "--shard ${shard}/3 --threads ${SLURM_CPUS_PER_TASK:-2} '--preset' 'tiny' "
                           "'--views-per-scene' '2' '--split' '0.5,0.5,0'"));

  const std::string m = read_file(s.merge);
  EXPECT_THAT(m, HasSubstr("dataset merge 'data set' \\\n  'data set/shards/shard-0-of-3' \\\n  'data set/shards/shard-1-of-3' "
                           "\\\n  'data set/shards/shard-2-of-3'\n"));
  EXPECT_THAT(m, HasSubstr("dataset verify 'data set'"));
  EXPECT_THAT(m, Not(HasSubstr("--array")));

  const std::string u = read_file(s.submit);
  EXPECT_THAT(u, HasSubstr("sbatch --parsable \"$here/generate.sbatch\""));
  EXPECT_THAT(u, HasSubstr("--dependency=afterok:${array} --kill-on-invalid-dep=yes"));
  EXPECT_TRUE((std::filesystem::status(s.submit).permissions() & std::filesystem::perms::owner_exec) !=
              std::filesystem::perms::none);
}

TEST(Slurm, QuotingAndBadOptions) {
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_EQ(shard_folder("out", 2, 5), std::filesystem::path("out/shards/shard-2-of-5"));
  SlurmOptions o;
  o.phyir = "/bin/phyir";
  o.workdir = test::fresh_test_dir();
  o.out_dir = "out";
  o.shards = 0;
  EXPECT_THROW(write_slurm_scripts(o), Error);
  o.shards = 2;
  o.sbatch_options = {"qos=low"};
  EXPECT_THROW(write_slurm_scripts(o), Error);
}

}  // namespace
}  // namespace phyir::dataset
