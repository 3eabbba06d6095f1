#include "camera_flags.h"

#include <algorithm>
#include <sstream>

#include "flag_registry.h"
#include "phyir/core/error.h"

namespace phyir::cli {

namespace {

constexpr const char* kGroup = "Camera";

glm::vec3 parse_position(const std::string& text, const std::string& flag) {
  std::istringstream in(text);
  glm::vec3 p;
  char c1 = 0, c2 = 0;
  if (!(in >> p.x >> c1 >> p.y >> c2 >> p.z) || c1 != ',' || c2 != ',' || !in.eof())
    fail("{} '{}' is not X,Y,Z (three comma-separated numbers, metres)", flag, text);
  return p;
}

}  // namespace

void add_image_size_flags(CLI::App* cmd, int& width, int& height) {
  sets(cmd, "width", cmd->add_option("--width", width, "image width in pixels (a panorama's: twice its height)"))
      ->capture_default_str()
      ->group(kGroup);
  sets(cmd, "height", cmd->add_option("--height", height, "image height in pixels"))->capture_default_str()->group(kGroup);
  sets(cmd, "size", "--width/--height");
  // One of the two given: the other follows at 2:1 (a panorama's), not the other's default.
  cmd->parse_complete_callback([cmd, &width, &height] {
    const bool width_given = cmd->count("--width") > 0, height_given = cmd->count("--height") > 0;
    if (width_given && !height_given) height = std::max(width / 2, 1);
    if (height_given && !width_given) width = 2 * height;
  });
}

void add_camera_flags(CLI::App* cmd, render::RenderJob& job) {
  add_image_size_flags(cmd, job.width, job.height);
  const std::string camera = "--camera";
  sets(cmd, "camera_position",
       cmd->add_option_function<std::string>(
           camera, [&job, camera](const std::string& text) { job.camera_position = parse_position(text, camera); },
           "camera position X,Y,Z in metres (default: the scene's camera)"))
      ->group(kGroup);
  sets(cmd, "camera_index", cmd->add_option("--camera-index", job.camera_index, "which scene camera to use"))
      ->capture_default_str()
      ->group(kGroup);
  sets(cmd, "projection",
       cmd->add_option_function<std::string>(
           "--projection", [&job](const std::string& name) { job.projection = render::parse_projection(name); },
           "equirect (360x180 panorama) or perspective"))
      ->default_str(render::projection_name(job.projection))
      ->group(kGroup);
}

}  // namespace phyir::cli
