#include "phyir/insert/insert_view.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "phyir/core/equirect.h"
#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/view/input_exposure.h"
#include "phyir/view/view_files.h"
#include "phyir/view/view_record.h"

namespace phyir::insert {

namespace fs = std::filesystem;

namespace {

Image read_map(const fs::path& dir, const char* name, int channels, const Image* size_of) {
  const fs::path path = dir / name;
  if (!fs::is_regular_file(path)) fail("{}: missing (insertion needs the view's {})", path.string(), name);
  Image image = read_image(path);
  if (image.channels < channels) fail("{}: {} channels, expected {}", path.string(), image.channels, channels);
  if (size_of && (image.width != size_of->width || image.height != size_of->height))
    fail("{}: {}x{}, but the view's color.exr is {}x{}", path.string(), image.width, image.height, size_of->width,
         size_of->height);
  return image;
}

nlohmann::json read_render_record(const fs::path& dir) {
  std::ifstream in(dir / view::kRenderRecordFile);
  if (!in) return nlohmann::json();
  return nlohmann::json::parse(in, nullptr, false);
}

// The camera and exposure: view.json first (dataset views), then render.json.
void read_records(InsertView* v) {
  const view::ViewRecord record = view::read_view(v->dir);
  const nlohmann::json render = read_render_record(v->dir);
  if (record.camera) {
    v->camera = *record.camera;
  } else if (render.is_object() && render.contains("camera") && render["camera"].contains("position")) {
    const auto& p = render["camera"]["position"];
    v->camera = glm::vec3(p.at(0).get<float>(), p.at(1).get<float>(), p.at(2).get<float>());
  } else {
    fail("{}: no camera position (neither view.json's viewpoint nor render.json's camera)", v->dir.string());
  }
  if (record.input.recorded) {
    v->exposure_stops = record.input.stops;
    v->display_view = record.input.view;
  } else if (render.is_object() && render.contains("color_png")) {
    v->exposure_stops = render["color_png"].value(view::kExposureStopsKey, 0.0);
    v->display_view = render["color_png"].value("view", std::string("Standard"));
  }
}

}  // namespace

InsertView read_insert_view(const fs::path& dir, const fs::path& maps_dir) {
  if (!fs::is_directory(dir)) fail("{}: not a view folder", dir.string());
  const fs::path maps = maps_dir.empty() ? dir : maps_dir;
  InsertView v;
  v.dir = dir;
  v.color = read_map(dir, view::kColorFile, 3, nullptr);
  v.depth = read_map(maps, view::kDepthFile, 1, &v.color);
  v.normal = read_map(maps, view::kNormalFile, 3, &v.color);
  v.basecolor = read_map(maps, view::kBaseColorFile, 3, &v.color);
  v.roughness = read_map(maps, view::kRoughnessFile, 1, &v.color);
  v.metalness = read_map(maps, view::kMetalnessFile, 1, &v.color);
  read_records(&v);
  return v;
}

SurfacePoint surface_at(const InsertView& view, int x, int y) {
  if (x < 0 || y < 0 || x >= view.width() || y >= view.height())
    fail("pixel ({}, {}) is outside the {}x{} view {}", x, y, view.width(), view.height(), view.dir.string());
  const float d = view.depth.at(x, y, 0);
  if (!(d > 0.0f))
    fail("pixel ({}, {}) of {} is on no surface (depth.exr is 0 there): pick a pixel on the floor or a table", x, y,
         view.dir.string());
  const glm::vec2 uv((float(x) + 0.5f) / float(view.width()), (float(y) + 0.5f) / float(view.height()));
  SurfacePoint s;
  s.position = view.camera + d * equirect_direction(uv);
  const glm::vec3 n(view.normal.at(x, y, 0), view.normal.at(x, y, 1), view.normal.at(x, y, 2));
  if (glm::dot(n, n) > 1e-8f) s.normal = glm::normalize(n);
  s.base_color = glm::vec3(view.basecolor.at(x, y, 0), view.basecolor.at(x, y, 1), view.basecolor.at(x, y, 2));
  s.roughness = view.roughness.at(x, y, 0);
  s.metalness = view.metalness.at(x, y, 0);
  return s;
}

render::CameraModel panorama_camera(const InsertView& view) {
  render::CameraModel camera;
  camera.projection = render::Projection::Equirectangular;
  camera.position = view.camera;
  camera.width = view.width();
  camera.height = view.height();
  return camera;
}

}  // namespace phyir::insert
