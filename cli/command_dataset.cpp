// phyir dataset: generate, verify, merge, slurm and stats (docs/dataset.md, docs/commands/dataset.md).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.h"
#include "dataset_flags.h"
#include "flag_registry.h"
#include "sampling_flags.h"
#include "slurm_script.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/dataset/dataset_stats.h"
#include "phyir/dataset/generate.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/merge.h"
#include "phyir/dataset/verify.h"

namespace phyir::cli {

void add_dataset_futurehouse_commands(CLI::App* dataset);  // command_dataset_futurehouse.cpp

namespace fs = std::filesystem;

namespace {

struct GenerateFlags {
  DatasetSettingsFlags settings;
  dataset::GenerateOptions options;
  std::string shard = "0/1";
  bool quiet = false;
};

struct SlurmFlags {
  DatasetSettingsFlags settings;
  std::string scenes, out, phyir;
  DatasetSlurmJob job;
  bool submit = false;
};

void add_generate(CLI::App* dataset) {
  auto f = std::make_shared<GenerateFlags>();
  dataset::GenerateOptions& o = f->options;
  auto* cmd = dataset->add_subcommand(
      "generate",
      "Render every view of every glTF scene of a folder into a dataset: one folder per view (render outputs, "
      "input.png, render.json, view.json) and manifest.json. Killed runs resume: run the same command again.");
  sets(cmd, "scenes_dir",
       cmd->add_option("--scenes", o.scenes_dir, "folder of .gltf/.glb scenes (e.g. from 'phyir scenes generate')"))
      ->required()
      ->check(CLI::ExistingDirectory);
  sets(cmd, "out_dir", cmd->add_option("--out", o.out_dir, "dataset folder (created; an unfinished one is completed)"))
      ->required();
  add_dataset_settings_flags(cmd, f->settings);
  add_threads_flag(cmd, o.threads)->group("Options");
  sets(cmd, "views_in_flight",
       cmd->add_option("--views-in-flight", o.views_in_flight, "views rendered at once (0 = --threads)"))
      ->capture_default_str();
  sets(cmd, "shard",
       cmd->add_option("--shard", f->shard, "render only shard i of N (i/N); 'phyir dataset merge' joins the shards"))
      ->capture_default_str();
  cmd->add_flag("--quiet", f->quiet, "no progress line");
  cmd->callback([f] {
    dataset::GenerateOptions& o = f->options;
    o.settings = f->settings.resolve();
    o.shard = dataset::parse_shard(f->shard);
    o.progress = !f->quiet;
    dataset::generate_dataset(o);
  });
}

void add_verify(CLI::App* dataset) {
  auto dir = std::make_shared<std::string>();
  auto threads = std::make_shared<int>(0);
  auto remove_damaged = std::make_shared<bool>(false);
  auto* cmd = dataset->add_subcommand(
      "verify", "Re-read every file a dataset's manifest lists (sizes, SHA-256, OpenImageIO decodes) and list every "
                "problem; exit status 1 when there is any");
  cmd->add_option("dir", *dir, "dataset (or shard) folder holding manifest.json")->required();
  cmd->add_option("--threads", *threads, "worker threads (0 = all cores)")->capture_default_str();
  cmd->add_flag("--remove-damaged", *remove_damaged,
                "delete the views with problems (and manifest.json), so the same generate command renders them again");
  cmd->callback([dir, threads, remove_damaged] {
    const dataset::VerifyReport report = dataset::verify_dataset(*dir, *threads);
    for (const std::string& p : report.problems) std::printf("%s\n", p.c_str());
    std::printf("%s: %zu views, %zu files, %.1f MB checked: %s\n", dir->c_str(), report.views, report.files,
                double(report.bytes) / 1e6,
                report.ok() ? "OK" : (std::to_string(report.problems.size()) + " problem(s)").c_str());
    std::fflush(stdout);
    if (report.ok()) return;
    if (*remove_damaged) {
      const size_t removed = dataset::remove_damaged_views(*dir, report);
      fail("{}: {} problem(s) found (listed on stdout); removed {} damaged view(s) and manifest.json: run the same "
           "'phyir dataset generate' command again to render them",
           *dir, report.problems.size(), removed);
    }
    fail("{}: {} problem(s) found (listed on stdout); 'verify --remove-damaged' then the same generate command "
         "repairs damaged views",
         *dir, report.problems.size());
  });
}

void add_merge(CLI::App* dataset) {
  auto out = std::make_shared<std::string>();
  auto shards = std::make_shared<std::vector<std::string>>();
  auto* cmd = dataset->add_subcommand(
      "merge", "Join finished shards (generate --shard i/N) into one dataset, byte-identical to an unsharded run; "
               "refuses shards with different settings, overlapping or missing views");
  cmd->add_option("out", *out, "merged dataset folder")->required();
  cmd->add_option("shards", *shards, "shard folders")->required()->expected(-1);
  cmd->callback([out, shards] {
    std::vector<fs::path> dirs(shards->begin(), shards->end());
    dataset::merge_shards(*out, dirs);
  });
}

void add_slurm_resource_flags(CLI::App* cmd, SlurmFlags& f) {
  DatasetSlurmJob& job = f.job;
  SbatchResources& r = job.resources;
  sets(cmd, "shards", cmd->add_option("--shards", job.plan.shards, "array tasks (shards)"))->required();
  cmd->add_option("--cpus-per-task", r.cpus_per_task, "CPUs per task (its generate --threads)")->capture_default_str();
  cmd->add_option("--time", r.time, "time limit per task (sbatch --time), e.g. 12:00:00");
  cmd->add_option("--merge-time", job.merge_time, "time limit of the merge + verify job");
  cmd->add_option("--partition", r.partition, "sbatch --partition");
  cmd->add_option("--account", r.account, "sbatch --account");
  cmd->add_option("--mem", r.mem, "memory per task (sbatch --mem), e.g. 8G");
  cmd->add_option("--job-name", r.job_name, "job name")->capture_default_str();
  cmd->add_option("--sbatch", r.extra, "extra sbatch option for every job, e.g. --sbatch=--qos=low (repeatable)");
  cmd->add_option("--phyir", f.phyir, "phyir binary the jobs run (default: this one)");
  cmd->add_flag("--submit", f.submit, "submit the jobs now (runs OUT/slurm/submit.sh)");
}

void add_slurm(CLI::App* dataset) {
  auto f = std::make_shared<SlurmFlags>();
  f->job.resources.job_name = "phyir-dataset";
  auto* cmd = dataset->add_subcommand(
      "slurm", "Write (and with --submit, submit) a Slurm job array for 'dataset generate': one task per shard, "
               "requeued on failure, then a merge + verify job that waits for all of them");
  sets(cmd, "scenes_dir", cmd->add_option("--scenes", f->scenes, "folder of .gltf/.glb scenes, as for generate"))
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", f->out, "dataset folder; shards go to OUT/shards, scripts and logs to OUT/slurm")->required();
  add_dataset_settings_flags(cmd, f->settings);
  add_slurm_resource_flags(cmd, *f);
  cmd->callback([f] {
    DatasetSlurmJob& job = f->job;
    f->settings.resolve();  // bad settings fail here, not in the cluster
    dataset::list_scenes(f->scenes);
    job.phyir = f->phyir.empty() ? this_executable() : fs::absolute(f->phyir);
    job.workdir = fs::current_path();
    job.scenes_dir = f->scenes;
    job.plan.out_dir = f->out;
    job.generate_args = f->settings.replay();
    const DatasetSlurmScripts s = write_dataset_slurm_scripts(job);
    std::printf("wrote %s (array of %d shard task(s)), %s and %s\n", s.generate.c_str(), job.plan.shards,
                s.merge.c_str(), s.submit.c_str());
    if (!f->submit) {
      std::printf("submit with: bash %s\n", s.submit.c_str());
      return;
    }
    std::printf("%s", submit_dataset_slurm_scripts(s).c_str());
  });
}

void add_stats(CLI::App* dataset) {
  struct StatsFlags {
    std::string dir, out, json;
    dataset::StatsOptions options;
    dataset::ContactSheetOptions sheet;
    bool quiet = false;
  };
  auto f = std::make_shared<StatsFlags>();
  auto* cmd = dataset->add_subcommand(
      "stats", "Summarise a finished dataset: views per split and scene, material mix (metal, mirror, glossy, "
               "diffuse, emissive, transparent pixels), light levels, render cost; optionally a PNG of sample views");
  cmd->add_option("dir", f->dir, "dataset folder holding manifest.json")->required();
  cmd->add_option("--out", f->out, "write a contact sheet of sample views' input.png (PNG)");
  cmd->add_option("--json", f->json, "also write the summary as JSON");
  cmd->add_option("--max-views", f->options.max_views,
                  "read the pixels of at most this many views, evenly spaced (0 = all)")
      ->capture_default_str();
  cmd->add_option("--sheet-views", f->sheet.count, "views on the contact sheet")->capture_default_str();
  cmd->add_option("--sheet-columns", f->sheet.columns, "thumbnails per row")->capture_default_str();
  cmd->add_option("--thumb-width", f->sheet.thumb_width, "thumbnail width in pixels")->capture_default_str();
  cmd->add_option("--threads", f->options.threads, "worker threads (0 = all cores)")->capture_default_str();
  cmd->add_flag("--quiet", f->quiet, "no progress line");
  cmd->callback([f] {
    f->options.progress = !f->quiet;
    const dataset::DatasetStats stats = dataset::compute_dataset_stats(f->dir, f->options);
    std::printf("%s", dataset::format_stats(stats).c_str());
    if (!f->json.empty()) {
      write_file_atomic(f->json, dataset::stats_to_json(stats).dump(2) + "\n");
      std::printf("wrote %s\n", f->json.c_str());
    }
    if (!f->out.empty()) {
      dataset::write_contact_sheet(f->dir, f->out, f->sheet);
      std::printf("wrote %s\n", f->out.c_str());
    }
    std::fflush(stdout);
  });
}

}  // namespace

void add_dataset_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("dataset", "Datasets: generate (resumable, sharded), verify, merge, slurm, stats, import-/export-futurehouse");
  cmd->require_subcommand(1);
  add_generate(cmd);
  add_verify(cmd);
  add_merge(cmd);
  add_slurm(cmd);
  add_stats(cmd);
  add_dataset_futurehouse_commands(cmd);
}

}  // namespace phyir::cli
