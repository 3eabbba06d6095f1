#pragma once
// `phyir render` as a library call (the dataset pipeline reuses it): load a glTF scene,
// pick the camera, render colour and AOVs, write every file atomically and render.json
// last, so a present render.json means a complete output folder.
#include <filesystem>
#include <optional>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "phyir/render/camera.h"
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
  std::filesystem::path environment_path;    // optional HDR equirect environment
  float environment_scale = 1.0f;
  float exposure = 0.0f;                     // stops, for color.png only
  std::string view = "Standard";             // OCIO view for color.png
  // Per-pixel light probes (docs/probes.md): rendered after the view, only when asked, from
  // streams of their own (color.exr is the same with or without them). Their seed and path
  // settings are the view's (`settings`); the fields of `probe` for those are ignored.
  bool probes = false;
  ProbeSettings probe;
};

// Throws phyir::Error for bad input (names the file / flag / value). Returns render.json.
nlohmann::json run_render_job(const RenderJob& job);

// The camera the job will use (exposed for tests and the dataset pipeline).
CameraModel job_camera(const RenderJob& job, const scenes::Scene& scene, std::string* description);

// The text of render.json's "conventions" block, shared with docs and the dataset.
nlohmann::json output_conventions();

}  // namespace phyir::render
