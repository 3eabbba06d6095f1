// phyir render: one view of a glTF scene to HDR colour, AOVs and render.json.
#include <memory>

#include "camera_flags.h"
#include "commands.h"
#include "exposure_flag.h"
#include "flag_registry.h"
#include "guiding_flags.h"
#include "probe_flags.h"
#include "sampling_flags.h"
#include "phyir/render/render_job.h"

namespace phyir::cli {

namespace {

struct RenderFlags {
  render::RenderJob job;
  std::string scene;
  std::string out;
  std::string environment;
  bool no_aovs = false;
  bool quiet = false;
};

}  // namespace

void add_render_command(CLI::App& app) {
  auto flags = std::make_shared<RenderFlags>();
  auto* cmd = app.add_subcommand(
      "render", "Render one view of a glTF scene: color.exr/png, AOVs (depth, normal, base colour, "
                "roughness, metalness, masks) and render.json");
  render::RenderJob& job = flags->job;
  cmd->add_option("scene", flags->scene, "glTF 2.0 scene (.gltf or .glb)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", flags->out, "output folder")->required();
  sets(cmd, "environment",
       cmd->add_option("--environment", flags->environment, "HDR equirectangular environment map (EXR/HDR)"));
  sets(cmd, "environment_scale",
       cmd->add_option("--environment-scale", job.environment_scale, "multiplier on the environment"))
      ->capture_default_str();
  cmd->add_flag("--no-aovs", flags->no_aovs, "write color only");
  cmd->add_flag("--force-all-effects", job.settings.force_all_effects,
                "run every integrator feature even if the scene lacks it (benchmarking; same output)");
  cmd->add_flag("--quiet", flags->quiet, "no progress display");
  add_camera_flags(cmd, job);
  add_sampling_flags(cmd, job.settings, job.threads);
  add_guiding_flags(cmd, job.settings.guiding);
  CLI::Option* exposure = add_exposure_flag(cmd, job.auto_exposure, job.exposure, "color.png", "exposure");
  exposure->description(exposure->get_description() + "; written to render.json");
  add_view_flag(cmd, job.view, "color.png", "view");
  // Light probes (docs/probes.md).
  cmd->add_flag("--probes", job.probes, "also render per-pixel light probes: probes.exr, probe_position.exr, "
                                        "probe_normal.exr, probe_mask.exr and a \"probes\" block in render.json")
      ->group("Light probes");
  add_probe_flags(cmd, job.probe);
  cmd->callback([flags] {
    render::RenderJob& job = flags->job;
    job.scene_path = flags->scene;
    job.out_dir = flags->out;
    job.environment_path = flags->environment;
    job.settings.aovs = !flags->no_aovs;
    job.settings.progress = !flags->quiet;
    render::run_render_job(job);
  });
}

}  // namespace phyir::cli
