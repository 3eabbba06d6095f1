// phyir render: one view of a glTF scene to HDR colour, AOVs and render.json.
#include <memory>
#include <optional>
#include <sstream>

#include "commands.h"
#include "exposure_flag.h"
#include "phyir/core/error.h"
#include "phyir/render/render_job.h"

namespace phyir::cli {

namespace {

struct RenderFlags {
  render::RenderJob job;
  std::string scene;
  std::string out;
  std::string camera;
  std::string projection = "equirect";
  std::string environment;
  bool no_aovs = false;
  bool quiet = false;
  bool no_probe_punctual = false;
  std::string probe_grid = "128x256";
  std::string probe_res = "16x32";
  std::string probe_mode = "cache";
  std::string exposure = "auto";
};

glm::vec3 parse_position(const std::string& text) {
  std::istringstream in(text);
  glm::vec3 p;
  char c1 = 0, c2 = 0;
  if (!(in >> p.x >> c1 >> p.y >> c2 >> p.z) || c1 != ',' || c2 != ',' || !in.eof())
    fail("--camera '{}' is not X,Y,Z (three comma-separated numbers, metres)", text);
  return p;
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto flags = std::make_shared<RenderFlags>();
  auto* cmd = app.add_subcommand(
      "render", "Render one view of a glTF scene: color.exr/png, AOVs (depth, normal, base colour, "
                "roughness, metalness, masks) and render.json");
  render::RenderJob& job = flags->job;
  cmd->add_option("scene", flags->scene, "glTF 2.0 scene (.gltf or .glb)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", flags->out, "output folder")->required();
  cmd->add_option("--width", job.width, "image width in pixels")->capture_default_str();
  cmd->add_option("--height", job.height, "image height in pixels")->capture_default_str();
  cmd->add_option("--spp", job.settings.spp, "paths per pixel")->capture_default_str();
  cmd->add_option("--camera", flags->camera, "camera position X,Y,Z in metres (default: the scene's camera)");
  cmd->add_option("--camera-index", job.camera_index, "which scene camera to use")->capture_default_str();
  cmd->add_option("--projection", flags->projection, "equirect (360x180 panorama) or perspective")->capture_default_str();
  cmd->add_option("--max-bounces", job.settings.path.max_bounces, "scattering events after the first hit")->capture_default_str();
  cmd->add_option("--seed", job.settings.seed, "random seed (same seed, same output)")->capture_default_str();
  cmd->add_option("--threads", job.threads, "worker threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--environment", flags->environment, "HDR equirectangular environment map (EXR/HDR)");
  cmd->add_option("--environment-scale", job.environment_scale, "multiplier on the environment")->capture_default_str();
  cmd->add_option("--exposure", flags->exposure,
                  "color.png's exposure: auto (the 95th percentile of color.exr's values maps to 0.9, as the "
                  "dataset's input.png) or a number of stops; written to render.json")
      ->capture_default_str();
  cmd->add_option("--view", job.view, "OpenColorIO view for color.png: Standard or Raw")->capture_default_str();
  cmd->add_flag("--no-aovs", flags->no_aovs, "write color only");
  cmd->add_flag("--force-all-effects", job.settings.force_all_effects,
                "run every integrator feature even if the scene lacks it (benchmarking; same output)");
  cmd->add_flag("--quiet", flags->quiet, "no progress display");
  // Light probes (docs/probes.md).
  cmd->add_flag("--probes", job.probes, "also render per-pixel light probes: probes.exr, probe_position.exr, "
                                        "probe_normal.exr, probe_mask.exr and a \"probes\" block in render.json");
  cmd->add_option("--probe-grid", flags->probe_grid, "probes HxW (the paper: 128x256 for a 256x512 panorama)")->capture_default_str();
  cmd->add_option("--probe-res", flags->probe_res, "texels per probe hxw (equirectangular)")->capture_default_str();
  cmd->add_option("--probe-spp", job.probe.spp, "directions per probe texel")->capture_default_str();
  cmd->add_option("--probe-mode", flags->probe_mode, "cache (shared irradiance cache) or path (unbiased reference, slow)")->capture_default_str();
  cmd->add_option("--probe-offset", job.probe.offset, "probe origin's distance off the surface along its normal, metres")->capture_default_str();
  cmd->add_option("--probe-cache-cell", job.probe.cache.cell_size, "cache mode: cell size, metres")->capture_default_str();
  cmd->add_option("--probe-cache-spp", job.probe.cache.samples_per_cell, "cache mode: irradiance samples per cell")->capture_default_str();
  cmd->add_option("--probe-cache-direct-cells", job.probe.cache.direct_distance_cells,
                  "cache mode: cache direct light too in cells at least this many cell sizes from every emitter (0: never)")
      ->capture_default_str();
  cmd->add_option("--probe-spread-threshold", job.probe.spread_threshold,
                  "cache mode: a texel whose first samples spread over more than this times their mean gets hard-texel sampling")
      ->capture_default_str();
  cmd->add_option("--probe-share-radius", job.probe.sharing.radius,
                  "cache mode: average each texel with the probes up to this many grid cells away on the same surface "
                  "where parallax is small (0: off)")
      ->capture_default_str();
  cmd->add_option("--probe-share-parallax", job.probe.sharing.parallax_texels,
                  "cache mode: largest parallax between shared probes, in texel heights")
      ->capture_default_str();
  cmd->add_option("--probe-photons", job.probe.photons_per_light,
                  "cache mode: photons from each point and spot light, and per square metre of the sun's beam where it "
                  "reaches the probes, which take the light they reflect where they land densely (0: none)")
      ->capture_default_str();
  cmd->add_flag("--no-probe-punctual-lights", flags->no_probe_punctual,
                "leave the punctual lights out of the probes (to measure what they add; docs/probes.md)");
  cmd->callback([flags] {
    render::RenderJob& job = flags->job;
    job.probe.punctual_lights = !flags->no_probe_punctual;
    job.scene_path = flags->scene;
    job.out_dir = flags->out;
    job.projection = render::parse_projection(flags->projection);
    if (!flags->camera.empty()) job.camera_position = parse_position(flags->camera);
    job.environment_path = flags->environment;
    const std::optional<float> stops = parse_exposure_flag(flags->exposure);
    job.auto_exposure = !stops;
    job.exposure = stops.value_or(0.0f);
    job.settings.aovs = !flags->no_aovs;
    job.settings.progress = !flags->quiet;
    render::parse_size(flags->probe_grid, "--probe-grid", &job.probe.layout.grid_height, &job.probe.layout.grid_width);
    render::parse_size(flags->probe_res, "--probe-res", &job.probe.layout.res_height, &job.probe.layout.res_width);
    job.probe.mode = render::parse_probe_mode(flags->probe_mode);
    render::run_render_job(job);
  });
}

}  // namespace phyir::cli
