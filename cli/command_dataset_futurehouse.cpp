// phyir dataset import-futurehouse / export-futurehouse (docs/futurehouse.md).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "exposure_flag.h"
#include "flag_registry.h"
#include "phyir/core/error.h"
#include "phyir/core/log.h"
#include "phyir/dataset/futurehouse.h"

namespace phyir::cli {

namespace {

// Below this fraction of surface pixels with normals facing the camera, the normal axes are
// probably wrong (a yaw of 90 degrees leaves about half the walls facing away).
constexpr double kFacingWarning = 0.9;

void add_import(CLI::App* dataset) {
  struct Flags {
    dataset::FutureHouseImportOptions o;
    std::string probes = "auto", probe_res;
    bool quiet = false;
  };
  auto f = std::make_shared<Flags>();
  auto* cmd = dataset->add_subcommand(
      "import-futurehouse",
      "Convert the FutureHouse release (KePanoData/, KePanoLight/, split.json, as its published loader reads them) "
      "into a phyir dataset with a manifest, for verify, train and eval");
  cmd->add_option("src", f->o.src, "folder holding KePanoData/ (and KePanoLight/, split.json)")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", f->o.out, "new dataset folder (must not exist)")->required();
  sets(cmd, "split_file", cmd->add_option("--split", f->o.split_file, "split file (default: SRC/split.json)"));
  sets(cmd, "views_per_scene",
       cmd->add_option("--views-per-scene", f->o.views_per_scene,
                       "views taken from each plan (the first ones); 0 = the smallest count of any plan, plans with "
                       "fewer are left out"))
      ->capture_default_str();
  cmd->add_option("--probes", f->probes,
                  "auto: probes when every view has a light file; none; only: just the views with a light file")
      ->check(CLI::IsMember({"auto", "none", "only"}))
      ->capture_default_str();
  cmd->add_option("--probe-resolution", f->probe_res,
                  "texels of one probe, HxW (default: SRC/phyir/export.json's, else the loader's 16x32)");
  sets(cmd, "normal_axes",
       cmd->add_option("--normal-axes", f->o.normal_axes,
                       "our x,y,z as FutureHouse's signed axes (default x,y,z; see docs/futurehouse.md)"));
  add_exposure_flag(cmd, f->o.input.auto_exposure, f->o.input.exposure_stops, "input.png", "input.exposure_stops")
      ->group("Options");
  cmd->add_option("--seed", f->o.seed, "seed of the view seeds (exposure jitter)")->capture_default_str();
  cmd->add_option("--threads", f->o.threads, "worker threads (0 = all cores)")->capture_default_str();
  cmd->add_flag("--quiet", f->quiet, "no progress line");
  cmd->callback([f] {
    dataset::FutureHouseImportOptions& o = f->o;
    o.probes = f->probes == "none" ? dataset::ImportProbes::kNone
               : f->probes == "only" ? dataset::ImportProbes::kOnly
                                     : dataset::ImportProbes::kAuto;
    if (!f->probe_res.empty() && std::sscanf(f->probe_res.c_str(), "%dx%d", &o.probe_height, &o.probe_width) != 2)
      fail("--probe-resolution '{}': give HxW, e.g. 16x32", f->probe_res);
    o.progress = !f->quiet;
    const dataset::FutureHouseImportSummary s = dataset::import_futurehouse(o);
    for (const std::string& why : s.left_out) std::printf("left out: %s\n", why.c_str());
    std::printf("wrote %s: %zu plans, %zu views, %s; normals facing the camera: %.1f%% of surface pixels\n",
                o.out.c_str(), s.plans, s.views, s.probes ? "with probes" : "without probes",
                100.0 * s.normals_facing_camera);
    if (s.normals_facing_camera < kFacingWarning)
      spdlog::warn("only {:.1f}% of the normals face the camera: --normal-axes is probably wrong (docs/futurehouse.md)",
                   100.0 * s.normals_facing_camera);
    std::fflush(stdout);
  });
}

void add_export(CLI::App* dataset) {
  struct Flags {
    dataset::FutureHouseExportOptions o;
    std::string probes = "all";
    bool quiet = false;
  };
  auto f = std::make_shared<Flags>();
  auto* cmd = dataset->add_subcommand(
      "export-futurehouse",
      "Write a phyir dataset in FutureHouse's layout (Radiance .hdr maps, light-probe EXR mosaics, split.json), "
      "for code written for FutureHouse");
  cmd->add_option("dataset", f->o.dataset, "dataset folder holding manifest.json")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--out", f->o.out, "new folder (must not exist)")->required();
  cmd->add_option("--probes", f->probes,
                  "all: a light file per view; first: view 0 of each plan only (what the published KePanoLighting "
                  "accepts); none")
      ->check(CLI::IsMember({"all", "first", "none"}))
      ->capture_default_str();
  sets(cmd, "normal_axes",
       cmd->add_option("--normal-axes", f->o.normal_axes, "FutureHouse's axes of our x,y,z (as for import)"))
      ->capture_default_str();
  cmd->add_option("--threads", f->o.threads, "worker threads (0 = all cores)")->capture_default_str();
  cmd->add_flag("--quiet", f->quiet, "no progress line");
  cmd->callback([f] {
    dataset::FutureHouseExportOptions& o = f->o;
    o.probes = f->probes == "none" ? dataset::ExportProbes::kNone
               : f->probes == "first" ? dataset::ExportProbes::kFirst
                                      : dataset::ExportProbes::kAll;
    o.progress = !f->quiet;
    const dataset::FutureHouseExportSummary s = dataset::export_futurehouse(o);
    std::printf("wrote %s: %zu plans, %zu views, %zu light files\n", o.out.c_str(), s.plans, s.views, s.light_files);
    std::fflush(stdout);
  });
}

}  // namespace

void add_dataset_futurehouse_commands(CLI::App* dataset) {
  add_import(dataset);
  add_export(dataset);
}

}  // namespace phyir::cli
