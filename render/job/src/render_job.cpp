#include "phyir/render/render_job.h"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "phyir/core/atomic_file.h"
#include "phyir/core/auto_exposure.h"
#include "phyir/core/colour.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/core/log.h"
#include "phyir/core/safe_math.h"
#include "phyir/core/setting_error.h"
#include "phyir/core/stopwatch.h"
#include "phyir/render/equirect.h"
#include "phyir/scenes/gltf_loader.h"
#include "phyir/view/input_exposure.h"
#include "phyir/view/probe_mosaic.h"
#include "phyir/view/view_files.h"

namespace phyir::render {

namespace fs = std::filesystem;

namespace {

nlohmann::json vec_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

void validate(const RenderJob& job) {
  if (job.width <= 0 || job.height <= 0 || job.width > 65536 || job.height > 65536)
    fail_setting("size", "{}x{} must be between 1 and 65536", job.width, job.height);
  if (job.projection == Projection::Equirectangular && job.width != 2 * job.height)
    spdlog::warn("equirectangular image {}x{} is not 2:1; pixels will not be square in angle",
                 job.width, job.height);
  if (job.settings.spp <= 0) fail_setting("spp", "{} must be positive", job.settings.spp);
  if (job.settings.path.max_bounces < 0) fail_setting("max_bounces", "{} must be >= 0", job.settings.path.max_bounces);
  if (job.threads < 0) fail_setting("threads", "{} must be >= 0 (0 = all cores)", job.threads);
  if (job.camera_position && !is_finite(*job.camera_position))
    fail_setting("camera_position", "must be three finite numbers");
  if (!std::isfinite(job.exposure)) fail_setting("exposure", "must be finite");
  if (job.probes) job.probe.validate();
}

// The probes of the view and their four files.
RenderReport::Probes render_and_write_probes(const RenderJob& job, const RenderScene& scene, const CameraModel& camera,
                                             const Effects& effects) {
  RenderReport::Probes report;
  ProbeSettings& settings = report.settings;
  settings = job.probe;
  settings.seed = job.settings.seed;
  settings.path = job.settings.path;
  settings.progress = job.settings.progress;
  spdlog::info("rendering {}x{} probes of {}x{} texels, {} spp, mode {}", settings.layout.grid_height,
               settings.layout.grid_width, settings.layout.res_height, settings.layout.res_width, settings.spp,
               probe_mode_name(settings.mode));
  const ProbeOutput probes = ProbeRenderer(scene, effects, settings).render(camera);
  const Stopwatch watch;
  report.files = view::write_probe_images(
      job.out_dir, {probes.mosaic, probes.position, probes.normal, probes.mask, probes.standard_error});
  report.write_seconds = watch.seconds();
  report.stats = probes.stats;
  if (probes.stats.counters.nonfinite_samples > 0)
    spdlog::warn("{} non-finite probe samples were caught and zeroed", probes.stats.counters.nonfinite_samples);
  spdlog::info("probes: {:.2f} s ({} valid of {}, {:.1f} Mrays)", probes.stats.total_seconds, probes.stats.valid,
               probes.stats.probes, double(probes.stats.counters.rays) / 1e6);
  return report;
}

// The probes' block of render.json.
nlohmann::json probes_json(const RenderReport::Probes& probes) {
  nlohmann::json block = probes.settings.to_json();
  block.update(probes.stats.to_json());
  block["write_seconds"] = probes.write_seconds;
  block["files"] = probes.files;
  block["conventions"] = {
      {"probes", "mosaic of (H h) x (W w) RGB radiance: probe (i, j) is the h x w block at rows i h.., columns j w.., "
                 "an equirectangular image in the panorama's mapping, world-aligned; texel = incident radiance at the "
                 "probe origin averaged over the texel's solid angle"},
      {"placement", "probe (i, j) sits on the first surface seen from the camera at the continuous pixel position "
                    "((j + 0.5) width / W, (i + 0.5) height / H): for W = width / 2 the corner shared by pixels "
                    "(2i..2i+1, 2j..2j+1), for W = width the pixel centre"},
      {"probe_position", "H x W, X,Y,Z: the probe origin = surface point + offset * shading normal (facing the camera), metres; 0 where nothing is seen"},
      {"probe_normal", "H x W, X,Y,Z: the unit shading normal the origin is offset along; 0 where nothing is seen"},
      {"probe_stderr", "(H h) x (W w), Y: each texel's standard error in luminance as its own samples estimate it "
                       "(the shared cache's, the exact emission's and the photons' noise are not in it; docs/probes.md)"},
      {"probe_mask", "H x W, Y: 1 for a valid label; 0 where nothing is seen (probe all 0), on emitters and on glass or "
                     "alpha-blended surfaces (probe computed anyway), as the paper's M_mask"}};
  return block;
}

// The job's environment file when given, else the scene's declared environment, else none.
RenderReport::Environment choose_environment(const RenderJob& job, const scenes::Scene& scene) {
  RenderReport::Environment chosen;
  if (!job.environment_path.empty()) {
    chosen = {"file", job.environment_path.string(), job.environment_scale};
  } else if (scene.environment) {
    chosen = {"scene", scene.environment->path.string(), scene.environment->scale * job.environment_scale};
  }
  return chosen;
}

std::unique_ptr<EnvironmentLight> read_environment(const std::string& path, float scale) {
  Image image = read_image(path);
  if (image.channels < 3) fail("{}: environment map needs RGB, found {} channel(s)", path, image.channels);
  for (float v : image.pixels)
    if (!std::isfinite(v) || v < 0.0f) fail("{}: environment map holds a negative or non-finite value", path);
  return std::make_unique<EnvironmentLight>(image, scale);
}

// A scene's map that cannot be read fails naming the glTF file and the extras that declare it.
std::unique_ptr<EnvironmentLight> load_environment(const RenderReport::Environment& chosen, const scenes::Scene& scene) {
  if (chosen.source == "none") return nullptr;
  if (chosen.source != "scene") return read_environment(chosen.path, chosen.scale);
  try {
    return read_environment(chosen.path, chosen.scale);
  } catch (const Error& e) {
    fail("{}: environment '{}' (scene extras.phyir.environment): {}", scene.source, scene.environment->uri, e.what());
  }
}

}  // namespace

std::unique_ptr<EnvironmentLight> scene_environment(const scenes::Scene& scene) {
  if (!scene.environment) return nullptr;
  return load_environment({"scene", scene.environment->path.string(), scene.environment->scale}, scene);
}

nlohmann::json output_conventions() {
  return {
      {"world", "metres, right-handed, +Y up (glTF)"},
      {"equirect_mapping",
       "row 0 looks up (+Y), centre column looks along -Z; u = 0.5 + atan2(d.x, -d.z)/(2 pi), "
       "v = acos(d.y)/pi, pixel centres at (i + 0.5)/W (Blender's convention); panoramas are world-aligned"},
      {"color", "linear Rec.709 radiance (HDR), box-filtered over each pixel"},
      {"color_png", "color.exr through OpenColorIO config/phyir.ocio: exposure then the sRGB display view"},
      {"depth", "Euclidean distance from the camera centre to the first surface through the pixel centre, metres; 0 where mask_geometry is 0"},
      {"normal", "world-space unit shading normal facing the camera (X,Y,Z channels); 0 where no geometry"},
      {"basecolor", "linear Rec.709 base colour (textures sRGB-decoded), first surface"},
      {"roughness", "perceptual roughness R (GGX alpha = R^2)"},
      {"metalness", "metalness M"},
      {"mask_emissive", "1 where the first surface emits towards the camera"},
      {"mask_transparent", "1 where the first surface transmits (glass) or is not opaque"},
      {"mask_geometry", "1 where the pixel centre sees a surface, 0 where it sees nothing (AOVs are 0 there)"},
  };
}

CameraModel job_camera(const RenderJob& job, const scenes::Scene& scene, std::string* description) {
  CameraModel camera;
  camera.projection = job.projection;
  camera.width = job.width;
  camera.height = job.height;
  if (job.camera_position) {
    camera.position = *job.camera_position;
    if (description) *description = "position";
    if (job.projection == Projection::Perspective && !scene.cameras.empty()) {
      camera.forward = scene.cameras[0].forward;
      camera.up = scene.cameras[0].up;
      camera.yfov = scene.cameras[0].yfov;
    }
    return camera;
  }
  if (scene.cameras.empty())
    fail_setting("camera_position", "{}: the scene has no camera node: give a position X,Y,Z", scene.source);
  if (job.camera_index < 0 || size_t(job.camera_index) >= scene.cameras.size())
    fail_setting("camera_index", "{} is out of range ({} has {} camera(s))", job.camera_index, scene.source,
                 scene.cameras.size());
  const scenes::Camera& c = scene.cameras[job.camera_index];
  camera.position = c.position;
  camera.forward = c.forward;
  camera.up = c.up;
  camera.yfov = c.yfov;
  if (description) *description = "scene camera " + std::to_string(job.camera_index) + " '" + c.name + "'";
  return camera;
}

RenderReport run_render_job(const RenderJob& job) {
  validate(job);
  ensure_writable_directory(job.out_dir);
  const Stopwatch total_watch;
  RenderReport report;
  report.job = job;
  report.threads = job.threads > 0 ? job.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, report.threads);

  const Stopwatch load_watch;
  const scenes::Scene scene = scenes::load_gltf(job.scene_path);
  report.timings.load_seconds = load_watch.seconds();

  const Stopwatch build_watch;
  report.environment = choose_environment(job, scene);
  if (report.environment.source != "none")
    spdlog::info("environment {} (from {}), scale {}", report.environment.path, report.environment.source,
                 report.environment.scale);
  const RenderScene render_scene(scene, load_environment(report.environment, scene));
  report.timings.build_seconds = build_watch.seconds();
  report.scene = {job.scene_path.string(),
                  scene.meshes.size(),
                  scene.triangle_count(),
                  scene.materials.size(),
                  render_scene.emitters().emissive_triangle_count(),
                  render_scene.emitters().enclosed_triangle_count(),
                  render_scene.emitters().twin_triangle_count(),
                  scene.warnings};
  report.scene.emitter_clusters = render_scene.emitters().cluster_count();
  report.scene.emitters_chosen_by_power = render_scene.emitters().chosen_by_power();
  const DeltaLights& lights = render_scene.emitters().delta_lights();
  report.scene.point_lights = lights.count(scenes::PunctualLight::Type::Point);
  report.scene.spot_lights = lights.count(scenes::PunctualLight::Type::Spot);
  report.scene.directional_lights = lights.count(scenes::PunctualLight::Type::Directional);

  report.camera = job_camera(job, scene, &report.camera_source);
  const CameraModel& camera = report.camera;
  spdlog::info("rendering {} ({} triangles) from {} at ({:.3f}, {:.3f}, {:.3f}), {}x{} {}, {} spp",
               job.scene_path.string(), scene.triangle_count(), report.camera_source, camera.position.x,
               camera.position.y, camera.position.z, camera.width, camera.height,
               projection_name(camera.projection), job.settings.spp);

  const RenderOutput out = render_view(render_scene, camera, job.settings);
  report.effects = out.effects;
  report.stats = out.stats;

  const Stopwatch exr_watch;
  fs::create_directories(job.out_dir);
  report.files = out.film.write_exr(job.out_dir);
  const double color_write_seconds = exr_watch.seconds();
  if (job.probes) {
    report.probes = render_and_write_probes(job, render_scene, camera, out.effects);
    report.files.insert(report.files.end(), report.probes->files.begin(), report.probes->files.end());
  }
  const Stopwatch preview_watch;
  report.exposure = job.auto_exposure ? auto_exposure(out.film.color()) : AutoExposure{job.exposure, 0.0f};
  write_image(job.out_dir / view::kColorPreviewFile,
              linear_to_display(out.film.color(), report.exposure.stops, job.view));
  report.files.push_back(view::kColorPreviewFile);
  report.timings.write_seconds = color_write_seconds + preview_watch.seconds();
  report.timings.total_seconds = total_watch.seconds();
  write_file_atomic(job.out_dir / view::kRenderRecordFile, report.to_json().dump(2) + "\n");
  if (out.stats.counters.nonfinite_samples > 0)
    spdlog::warn("{} non-finite path samples were caught and zeroed", out.stats.counters.nonfinite_samples);
  spdlog::info("wrote {} files to {} in {:.2f} s ({:.2f} Mrays/s)", report.files.size() + 1, job.out_dir.string(),
               total_watch.seconds(), out.stats.color_seconds > 0 ? out.stats.counters.rays / out.stats.color_seconds / 1e6 : 0.0);
  return report;
}

nlohmann::json RenderReport::to_json() const {
  nlohmann::json report;
  report["phyir_version"] = PHYIR_VERSION;
  report["scene"] = {{"path", scene.path},
                     {"meshes", scene.meshes},
                     {"triangles", scene.triangles},
                     {"materials", scene.materials},
                     {"emissive_triangles", scene.emissive_triangles},
                     {"enclosed_emissive_triangles", scene.enclosed_emissive_triangles},
                     {"twin_emissive_triangles", scene.twin_emissive_triangles},
                     {"emitter_clusters", scene.emitter_clusters},
                     {"emitters_chosen_by_power", scene.emitters_chosen_by_power},
                     {"punctual_lights",
                      {{"point", scene.point_lights},
                       {"spot", scene.spot_lights},
                       {"directional", scene.directional_lights}}},
                     {"warnings", scene.warnings}};
  report["camera"] = {{"source", camera_source},
                      {"projection", projection_name(camera.projection)},
                      {"position", vec_json(camera.position)},
                      {"forward", vec_json(camera.forward)},
                      {"up", vec_json(camera.up)},
                      {"yfov", camera.yfov},
                      {"width", camera.width},
                      {"height", camera.height}};
  report["conventions"] = output_conventions();
  report["settings"] = {{"spp", job.settings.spp},
                        {"max_bounces", job.settings.path.max_bounces},
                        {"roulette_start", job.settings.path.roulette_start},
                        {"light_subpaths", job.settings.path.light_subpaths},
                        {"seed", job.settings.seed},
                        {"threads", threads},
                        {"aovs", job.settings.aovs},
                        {"force_all_effects", job.settings.force_all_effects},
                        {"environment", environment.path},
                        {"environment_scale", environment.scale},
                        {"environment_source", environment.source},
                        {"exposure", job.auto_exposure ? nlohmann::json("auto") : nlohmann::json(job.exposure)},
                        {"view", job.view}};
  report["color_png"] = {{view::kExposureStopsKey, exposure.stops}, {"view", job.view}};
  if (job.auto_exposure) report["color_png"]["percentile_value"] = exposure.percentile_value;
  report["effects"] = effects.to_json();
  // What ran: light subpaths join only where there is a point or spot light to start from.
  report["effects"]["light_subpaths"] =
      job.settings.path.light_subpaths && effects.punctual_lights && scene.point_lights + scene.spot_lights > 0;
  report["counters"] = stats.to_json();
  report["guiding"] = stats.guiding.to_json(job.settings.guiding);
  report["timings"] = {{"load_seconds", timings.load_seconds},
                       {"build_seconds", timings.build_seconds},
                       {"color_seconds", stats.color_seconds},
                       {"aov_seconds", stats.aov_seconds},
                       {"write_seconds", timings.write_seconds},
                       {"total_seconds", timings.total_seconds}};
  if (probes) {
    report["timings"]["probe_seconds"] = probes->stats.total_seconds;
    report["probes"] = probes_json(*probes);
  }
  report["files"] = files;
  return report;
}

}  // namespace phyir::render
