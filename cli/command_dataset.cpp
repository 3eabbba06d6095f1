// phyir dataset: generate, verify, merge, slurm and stats (docs/dataset.md, docs/commands/dataset.md).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.h"
#include "exposure_flag.h"
#include "phyir/core/atomic_file.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/dataset/dataset_stats.h"
#include "phyir/dataset/generate.h"
#include "phyir/dataset/layout.h"
#include "phyir/dataset/merge.h"
#include "phyir/dataset/settings.h"
#include "phyir/dataset/slurm.h"
#include "phyir/dataset/verify.h"

namespace phyir::cli {

void add_dataset_futurehouse_commands(CLI::App* dataset);  // command_dataset_futurehouse.cpp

namespace fs = std::filesystem;

namespace {

// The flags that make up DatasetSettings, shared by `generate` and `slurm`. A preset fills
// every field; each flag given overrides one.
struct SettingsFlags {
  std::string preset = "cpu";
  int views_per_scene = 8;
  uint64_t seed = 1;
  int width = 0, height = 0, spp = 0, max_bounces = 0;
  bool probes = false, no_probes = false;
  std::string probe_grid, probe_res, probe_mode;
  int probe_spp = 0, probe_cache_spp = 0, probe_share_radius = 0, probe_photons = 0;
  float probe_offset = 0, probe_cache_cell = 0, probe_cache_direct_cells = 0, probe_spread_threshold = 0;
  float probe_share_parallax = 0;
  std::string exposure = "auto";
  double exposure_percentile = 0, exposure_target = 0;
  float exposure_jitter = 0, preview_exposure = 0;
  std::string view = "Standard";
  float clearance = 0, min_spacing = 0;
  std::string split = "0.8,0.1,0.1";

  struct Given {
    CLI::Option* option;
    bool flag;
  };
  std::vector<Given> options;

  bool given(const std::string& name) const {
    for (const Given& g : options)
      if (g.option->get_name() == name) return g.option->count() > 0;
    return false;
  }
  // The flags as the user gave them, to repeat in a Slurm script.
  std::vector<std::string> replay() const {
    std::vector<std::string> args;
    for (const Given& g : options) {
      if (g.option->count() == 0) continue;
      // --name=value keeps values such as "-1.5" from reading as options.
      if (g.flag) args.push_back(g.option->get_name());
      else
        for (const std::string& value : g.option->results()) args.push_back(g.option->get_name() + "=" + value);
    }
    return args;
  }
};

void add_settings_options(CLI::App* cmd, SettingsFlags& f) {
  const CLI::Validator not_negative(
      [](std::string& value) { return value.rfind('-', 0) == 0 ? "must not be negative, got " + value : std::string(); },
      "");
  const auto opt = [&](CLI::Option* o) { f.options.push_back({o, false}); };
  const auto flag = [&](CLI::Option* o) { f.options.push_back({o, true}); };
  opt(cmd->add_option("--preset", f.preset, "settings bundle: tiny (tests, 64x32), cpu (512x256, the default), "
                                            "paper (256x512 with a 128x256 grid of 16x32 probes)")
          ->capture_default_str());
  opt(cmd->add_option("--views-per-scene", f.views_per_scene,
                      "views per scene: its cameras, then its candidate viewpoints, then points sampled in free space")
          ->capture_default_str());
  opt(cmd->add_option("--seed", f.seed, "dataset seed: viewpoints, per-view render seeds, exposure jitter, splits")
          ->check(not_negative)
          ->capture_default_str());
  opt(cmd->add_option("--width", f.width, "panorama width (= 2 x height) [preset]"));
  opt(cmd->add_option("--height", f.height, "panorama height [preset]"));
  opt(cmd->add_option("--spp", f.spp, "paths per pixel [preset]"));
  opt(cmd->add_option("--max-bounces", f.max_bounces, "scattering events after the first hit [preset]"));
  flag(cmd->add_flag("--probes", f.probes, "render per-pixel light probes [preset: on]"));
  flag(cmd->add_flag("--no-probes", f.no_probes, "no light probes"));
  opt(cmd->add_option("--probe-grid", f.probe_grid, "probe grid HxW, e.g. 128x256 [preset]"));
  opt(cmd->add_option("--probe-res", f.probe_res, "texels per probe hxw, e.g. 16x32 [preset]"));
  opt(cmd->add_option("--probe-spp", f.probe_spp, "directions per probe texel [preset]"));
  opt(cmd->add_option("--probe-mode", f.probe_mode, "probe estimator: cache (fast) or path (reference) [preset: cache]"));
  opt(cmd->add_option("--probe-offset", f.probe_offset, "probe origin's distance off the surface, metres [0.01]"));
  opt(cmd->add_option("--probe-cache-cell", f.probe_cache_cell, "cache mode: cell size, metres [0.05]"));
  opt(cmd->add_option("--probe-cache-spp", f.probe_cache_spp, "cache mode: irradiance samples per cell [preset]"));
  opt(cmd->add_option("--probe-cache-direct-cells", f.probe_cache_direct_cells,
                      "cache mode: cache direct light this many cells from every emitter (0: never) [6]"));
  opt(cmd->add_option("--probe-spread-threshold", f.probe_spread_threshold,
                      "cache mode: texels whose first samples spread over more than this times their mean get 6x the samples [0.75]"));
  opt(cmd->add_option("--probe-share-radius", f.probe_share_radius,
                      "cache mode: average texels with same-surface probes up to this many grid cells away (0: off) [1]"));
  opt(cmd->add_option("--probe-share-parallax", f.probe_share_parallax,
                      "cache mode: largest parallax between shared probes, in texel extents [0.5]"));
  opt(cmd->add_option("--probe-photons", f.probe_photons,
                      "cache mode: photons from each point and spot light, and per square metre of the sun's beam, as "
                      "phyir render's (0: none) [4096]"));
  opt(cmd->add_option("--exposure", f.exposure,
                      "input.png exposure: 'auto' (the 95th percentile of color.exr maps to --exposure-target) or "
                      "stops")
          ->capture_default_str());
  opt(cmd->add_option("--exposure-percentile", f.exposure_percentile, "auto exposure: the percentile used [0.95]"));
  opt(cmd->add_option("--exposure-target", f.exposure_target, "auto exposure: the value it maps to [0.9]"));
  opt(cmd->add_option("--exposure-jitter", f.exposure_jitter,
                      "random exposure: add a per-view draw in [-J, +J] stops (recorded) [0]"));
  opt(cmd->add_option("--view", f.view, "OpenColorIO view of input.png: Standard or Raw")->capture_default_str());
  opt(cmd->add_option("--preview-exposure", f.preview_exposure, "exposure of color.png, the render's preview [0]"));
  opt(cmd->add_option("--clearance", f.clearance, "sampled viewpoints: metres to the nearest surface [0.3]"));
  opt(cmd->add_option("--min-spacing", f.min_spacing, "sampled viewpoints: metres to every other viewpoint [0.5]"));
  opt(cmd->add_option("--split", f.split, "train,val,test fractions of the scenes")->capture_default_str());
}

dataset::DatasetSettings resolve(const SettingsFlags& f) {
  dataset::DatasetSettings s = dataset::preset_settings(f.preset);
  s.views_per_scene = f.views_per_scene;
  s.seed = f.seed;
  if (f.given("--width")) s.width = f.width;
  if (f.given("--height")) s.height = f.height;
  if (f.given("--spp")) s.spp = f.spp;
  if (f.given("--max-bounces")) s.max_bounces = f.max_bounces;
  if (f.probes && f.no_probes) fail("--probes and --no-probes contradict each other");
  if (f.probes) s.probes = true;
  if (f.no_probes) s.probes = false;
  render::ProbeLayout& layout = s.probe.layout;
  if (f.given("--probe-grid")) render::parse_size(f.probe_grid, "--probe-grid", &layout.grid_height, &layout.grid_width);
  if (f.given("--probe-res")) render::parse_size(f.probe_res, "--probe-res", &layout.res_height, &layout.res_width);
  if (f.given("--probe-spp")) s.probe.spp = f.probe_spp;
  if (f.given("--probe-mode")) s.probe.mode = render::parse_probe_mode(f.probe_mode);
  if (f.given("--probe-offset")) s.probe.offset = f.probe_offset;
  if (f.given("--probe-cache-cell")) s.probe.cache.cell_size = f.probe_cache_cell;
  if (f.given("--probe-cache-spp")) s.probe.cache.samples_per_cell = f.probe_cache_spp;
  if (f.given("--probe-cache-direct-cells")) s.probe.cache.direct_distance_cells = f.probe_cache_direct_cells;
  if (f.given("--probe-spread-threshold")) s.probe.spread_threshold = f.probe_spread_threshold;
  if (f.given("--probe-share-radius")) s.probe.sharing.radius = f.probe_share_radius;
  if (f.given("--probe-share-parallax")) s.probe.sharing.parallax_texels = f.probe_share_parallax;
  if (f.given("--probe-photons")) s.probe.photons_per_light = f.probe_photons;
  const std::optional<float> stops = parse_exposure_flag(f.exposure);
  s.input.auto_exposure = !stops;
  if (stops) s.input.exposure_stops = *stops;
  if (f.given("--exposure-percentile")) s.input.percentile = f.exposure_percentile;
  if (f.given("--exposure-target")) s.input.target = f.exposure_target;
  if (f.given("--exposure-jitter")) s.input.jitter_stops = f.exposure_jitter;
  if (f.given("--preview-exposure")) s.preview_exposure = f.preview_exposure;
  s.input.view = f.view;
  if (f.given("--clearance")) s.viewpoints.clearance = f.clearance;
  if (f.given("--min-spacing")) s.viewpoints.min_spacing = f.min_spacing;
  {
    std::istringstream in(f.split);
    char c1 = 0, c2 = 0;
    if (!(in >> s.split.train >> c1 >> s.split.val >> c2 >> s.split.test) || c1 != ',' || c2 != ',' || !in.eof())
      fail("--split '{}' must be three fractions train,val,test (e.g. 0.8,0.1,0.1)", f.split);
  }
  s.validate();
  return s;
}

struct GenerateFlags {
  SettingsFlags settings;
  std::string scenes, out, shard = "0/1";
  int threads = 0, views_in_flight = 0;
  bool quiet = false;
};

struct SlurmFlags {
  SettingsFlags settings;
  std::string scenes, out, phyir;
  dataset::SlurmOptions options;
  bool submit = false;
};

void add_generate(CLI::App* dataset) {
  auto f = std::make_shared<GenerateFlags>();
  auto* cmd = dataset->add_subcommand(
      "generate",
      "Render every view of every glTF scene of a folder into a dataset: one folder per view (render outputs, "
      "input.png, render.json, view.json) and manifest.json. Killed runs resume: run the same command again.");
  cmd->add_option("--scenes", f->scenes, "folder of .gltf/.glb scenes (e.g. from 'phyir scenes generate')")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", f->out, "dataset folder (created; an unfinished one is completed)")->required();
  add_settings_options(cmd, f->settings);
  cmd->add_option("--threads", f->threads, "worker threads in all (0 = all cores); never changes the output")
      ->capture_default_str();
  cmd->add_option("--views-in-flight", f->views_in_flight, "views rendered at once (0 = --threads)")->capture_default_str();
  cmd->add_option("--shard", f->shard, "render only shard i of N (i/N); 'phyir dataset merge' joins the shards")
      ->capture_default_str();
  cmd->add_flag("--quiet", f->quiet, "no progress line");
  cmd->callback([f] {
    dataset::GenerateOptions o;
    o.scenes_dir = f->scenes;
    o.out_dir = f->out;
    o.settings = resolve(f->settings);
    o.shard = dataset::parse_shard(f->shard);
    o.threads = f->threads;
    o.views_in_flight = f->views_in_flight;
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

void add_slurm(CLI::App* dataset) {
  auto f = std::make_shared<SlurmFlags>();
  dataset::SlurmOptions& o = f->options;
  auto* cmd = dataset->add_subcommand(
      "slurm", "Write (and with --submit, submit) a Slurm job array for 'dataset generate': one task per shard, "
               "requeued on failure, then a merge + verify job that waits for all of them");
  cmd->add_option("--scenes", f->scenes, "folder of .gltf/.glb scenes, as for generate")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--out", f->out, "dataset folder; shards go to OUT/shards, scripts and logs to OUT/slurm")->required();
  add_settings_options(cmd, f->settings);
  cmd->add_option("--shards", o.shards, "array tasks (shards)")->required();
  cmd->add_option("--cpus-per-task", o.cpus_per_task, "CPUs per task (its generate --threads)")->capture_default_str();
  cmd->add_option("--time", o.time, "time limit per task (sbatch --time), e.g. 12:00:00");
  cmd->add_option("--merge-time", o.merge_time, "time limit of the merge + verify job");
  cmd->add_option("--partition", o.partition, "sbatch --partition");
  cmd->add_option("--account", o.account, "sbatch --account");
  cmd->add_option("--mem", o.mem, "memory per task (sbatch --mem), e.g. 8G");
  cmd->add_option("--job-name", o.job_name, "job name")->capture_default_str();
  cmd->add_option("--sbatch", o.sbatch_options, "extra sbatch option for every job, e.g. --sbatch=--qos=low (repeatable)");
  cmd->add_option("--phyir", f->phyir, "phyir binary the jobs run (default: this one)");
  cmd->add_flag("--submit", f->submit, "submit the jobs now (runs OUT/slurm/submit.sh)");
  cmd->callback([f] {
    dataset::SlurmOptions& o = f->options;
    resolve(f->settings);  // bad settings fail here, not in the cluster
    dataset::list_scenes(f->scenes);
    o.phyir = f->phyir.empty() ? this_executable() : fs::absolute(f->phyir);
    o.workdir = fs::current_path();
    o.scenes_dir = f->scenes;
    o.out_dir = f->out;
    o.generate_args = f->settings.replay();
    const dataset::SlurmScripts s = dataset::write_slurm_scripts(o);
    std::printf("wrote %s (array of %d shard task(s)), %s and %s\n", s.generate.c_str(), o.shards, s.merge.c_str(),
                s.submit.c_str());
    if (!f->submit) {
      std::printf("submit with: bash %s\n", s.submit.c_str());
      return;
    }
    std::printf("%s", dataset::submit_slurm_scripts(s).c_str());
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
