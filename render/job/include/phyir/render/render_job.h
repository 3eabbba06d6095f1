#pragma once
// `phyir render` as a library call (the dataset pipeline reuses it): load a glTF scene,
// pick the camera, render colour and AOVs, write every file atomically and render.json
// last, so a present render.json means a complete output folder.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "phyir/core/auto_exposure.h"
#include "phyir/render/camera.h"
#include "phyir/render/environment_light.h"
#include "phyir/render/probe_renderer.h"
#include "phyir/render/render_view.h"

namespace phyir::render {

struct RenderJob {
  std::filesystem::path scene_path;
  std::filesystem::path out_dir;
  Projection projection = Projection::Equirectangular;
  int width = 1024;
  int height = 512;
  std::optional<glm::vec3> camera_position;  // else the scene's camera `camera_index`
  int camera_index = 0;
  RenderSettings settings;
  int threads = 0;                           // 0 = all cores
  // An HDR equirect environment file. Empty: the scene's own, declared in its
  // extras.phyir.environment, if any (docs/gltf-support.md#environment). The scale multiplies
  // whichever is used (the scene's times its own scale).
  std::filesystem::path environment_path;
  float environment_scale = 1.0f;
  // color.png's exposure: the toolkit's auto exposure (core/auto_exposure.h, as the
  // dataset's input.png) unless a fixed number of stops is given. color.exr is never scaled.
  bool auto_exposure = true;
  float exposure = 0.0f;                     // stops, when !auto_exposure
  std::string view = "Standard";             // OCIO view for color.png
  // Per-pixel light probes (docs/probes.md): rendered after the view, only when asked, from
  // streams of their own (color.exr is the same with or without them). Their seed and path
  // settings are the view's (`settings`); the fields of `probe` for those are ignored.
  bool probes = false;
  ProbeSettings probe;
};

// What a job did: everything render.json holds, typed.
struct RenderReport {
  struct SceneSummary {
    std::string path;
    size_t meshes = 0, triangles = 0, materials = 0;
    size_t emissive_triangles = 0;
    size_t enclosed_emissive_triangles = 0;  // emit only into closed geometry: never sampled
    size_t twin_emissive_triangles = 0;      // coincident copies of double-sided emitters: sampled once
    std::vector<std::string> warnings;       // what the loader skipped or approximated
    int point_lights = 0, spot_lights = 0, directional_lights = 0;  // KHR_lights_punctual
    size_t emitter_clusters = 0;             // what light sampling chooses among first (EmitterSampler)
    bool emitters_chosen_by_power = false;   // too many clusters and punctual lights: chosen by power alone
  };
  struct Timings {
    double load_seconds = 0.0, build_seconds = 0.0, write_seconds = 0.0, total_seconds = 0.0;
  };
  // The probes' part (when the job asked for them).
  struct Probes {
    ProbeSettings settings;  // as rendered: the view's seed and path settings
    ProbeStats stats;
    double write_seconds = 0.0;
    std::vector<std::string> files;
  };

  // The environment the view was lit by.
  struct Environment {
    std::string source = "none";  // "file" (the job's environment_path), "scene" (its extras.phyir.environment) or "none"
    std::string path;             // the file read; empty for none
    float scale = 1.0f;           // as applied
  };

  SceneSummary scene;
  Environment environment;
  std::string camera_source;  // "position" (the job's camera_position) or the scene camera's index and name
  CameraModel camera;
  RenderJob job;              // the settings it ran with
  int threads = 0;            // as used (0 in the job: all cores)
  Effects effects;            // what the scene called for, and ran
  RenderStats stats;          // the colour and AOV passes
  Timings timings;
  std::optional<Probes> probes;
  AutoExposure exposure;      // color.png's: the stops used (fixed or auto) and, auto, the percentile
  std::vector<std::string> files;  // written into job.out_dir, render.json excluded

  // render.json (docs/conventions.md).
  nlohmann::json to_json() const;
};

// Throws phyir::Error for bad input (names the file, the setting and the value). Writes every file and
// render.json (RenderReport::to_json) last.
RenderReport run_render_job(const RenderJob& job);

// The camera the job will use (exposed for tests and the dataset pipeline).
CameraModel job_camera(const RenderJob& job, const scenes::Scene& scene, std::string* description);

// The scene's own environment (extras.phyir.environment) as a render loads it, for commands that
// build their RenderScene themselves (the bench commands): null when the scene has none; the
// same checks and errors (naming the glTF file and its extras) as run_render_job's.
std::unique_ptr<EnvironmentLight> scene_environment(const scenes::Scene& scene);

// The text of render.json's "conventions" block, shared with docs and the dataset.
nlohmann::json output_conventions();

}  // namespace phyir::render
