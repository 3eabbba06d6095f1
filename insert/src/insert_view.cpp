#include "phyir/insert/insert_view.h"

#include <cctype>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "phyir/core/colour.h"
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
    fail("{}: {}x{}, but the view's colour image is {}x{}", path.string(), image.width, image.height, size_of->width,
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

bool is_display_referred(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

// A `phyir infer` folder: the user's own panorama, the one its record names, is the
// background, in the unit of the predicted probes; the camera is the origin (the predicted
// depth is measured from the panorama's centre, world-aligned). An 8-bit panorama was the
// network's input at 2^stops: decoded, it is radiance x 2^stops.
void read_prediction_background(InsertView* v) {
  const fs::path record_path = v->dir / view::kInferRecordFile;
  std::ifstream in(record_path);
  const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
  if (!record.is_object() || !record.contains("input") || !record["input"].is_string())
    fail("{}: not a prediction record (no \"input\" panorama)", record_path.string());
  fs::path input = record["input"].get<std::string>();
  if (input.is_relative() && !fs::exists(input)) input = v->dir / input;
  if (!fs::is_regular_file(input))
    fail("{}: the panorama it was predicted from, {}, is missing", record_path.string(), input.string());
  const nlohmann::json radiance = record.value("radiance", nlohmann::json::object());
  const bool absolute = radiance.value("unit", std::string("input")) == "absolute";
  const nlohmann::json& stops_value = radiance.value(view::kExposureStopsKey, nlohmann::json(0.0));
  const double stops = stops_value.is_number() ? stops_value.get<double>() : 0.0;
  v->color = read_image(input);
  if (v->color.channels < 3) fail("{}: {} channels, expected RGB", input.string(), v->color.channels);
  const bool ldr = is_display_referred(input);
  if (ldr) srgb_to_linear(v->color);
  // To the predicted probes' unit: absolute is radiance, input is radiance x 2^stops.
  const double scale = ldr ? (absolute ? std::exp2(-stops) : 1.0) : (absolute ? 1.0 : std::exp2(stops));
  for (float& value : v->color.pixels) value = float(value * scale);
  v->camera = glm::vec3(0.0f);
  v->exposure_stops = absolute ? stops : 0.0;
}

}  // namespace

InsertView read_insert_view(const fs::path& dir, const fs::path& maps_dir) {
  if (!fs::is_directory(dir)) fail("{}: not a view folder", dir.string());
  const fs::path maps = maps_dir.empty() ? dir : maps_dir;
  InsertView v;
  v.dir = dir;
  const bool prediction = !fs::exists(dir / view::kColorFile) && fs::is_regular_file(dir / view::kInferRecordFile);
  if (prediction)
    read_prediction_background(&v);
  else
    v.color = read_map(dir, view::kColorFile, 3, nullptr);
  v.depth = read_map(maps, view::kDepthFile, 1, &v.color);
  v.normal = read_map(maps, view::kNormalFile, 3, &v.color);
  v.basecolor = read_map(maps, view::kBaseColorFile, 3, &v.color);
  v.roughness = read_map(maps, view::kRoughnessFile, 1, &v.color);
  v.metalness = read_map(maps, view::kMetalnessFile, 1, &v.color);
  if (!prediction) read_records(&v);
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
