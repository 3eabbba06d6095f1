#include "phyir/insert/insert_lighting.h"

#include "phyir/core/error.h"
#include "phyir/core/image_io.h"
#include "phyir/insert/probe_field.h"
#include "phyir/view/view_files.h"

namespace phyir::insert {

namespace fs = std::filesystem;

namespace {

view::ProbeMosaic read_checked_probes(const fs::path& dir, const InsertView& view) {
  if (!view::has_probes(dir))
    fail("{}: missing (render the view with probes, or light the object from an HDR file)",
         (dir / view::kProbesFile).string());
  view::ProbeMosaic probes = view::read_probe_mosaic(dir);
  const view::ProbeLayout& l = probes.layout;
  // One probe per block of pixels: the grid and the panorama share their aspect ratio.
  if (int64_t(l.grid_width) * view.height() != int64_t(l.grid_height) * view.width())
    fail("{}: a {}x{} probe grid does not match the {}x{} view {} (probe grids have the panorama's aspect ratio)",
         (dir / view::kProbeMaskFile).string(), l.grid_height, l.grid_width, view.height(), view.width(),
         view.dir.string());
  return probes;
}

}  // namespace

std::shared_ptr<const view::ProbeMosaic> read_view_probes(const fs::path& dir, const InsertView& view) {
  ProbeCache& cache = *view.probe_cache;
  const std::lock_guard<std::mutex> lock(cache.mutex);
  auto& mosaic = cache.mosaics[dir];
  if (!mosaic) mosaic = std::make_shared<const view::ProbeMosaic>(read_checked_probes(dir, view));
  return mosaic;
}

namespace {

// The probe grid cell of pixel (x, y).
glm::ivec2 pixel_cell(const view::ProbeLayout& l, const InsertView& view, int x, int y) {
  return {std::min(l.grid_height - 1, y * l.grid_height / view.height()),
          std::min(l.grid_width - 1, x * l.grid_width / view.width())};
}

Lighting from_probes(std::shared_ptr<const view::ProbeMosaic> mosaic, const InsertView& view, int x, int y, bool varying,
                     const fs::path& dir, const LightingRequest& request) {
  const view::ProbeMosaic& probes = *mosaic;
  auto field = std::make_shared<ProbeField>(std::move(mosaic), view.camera);
  field->set_blend_power(request.blend_power);
  const fs::path positions = dir / view::kProbePositionFile, normals_file = dir / view::kProbeNormalFile;
  bool local = false;
  const float radius = request.neighbourhood_radius;
  if (varying && radius > 0.0f && fs::is_regular_file(positions)) {
    const SurfacePoint ground = surface_at(view, x, y);
    Image normals;
    SupportPlane support;
    if (request.support_plane_only) {
      if (!fs::is_regular_file(normals_file))
        fail("{}: missing (blending the support plane's probes needs their normals)", normals_file.string());
      normals = read_image(normals_file);
      support = {&normals, ground.normal};
    }
    local = field->use_neighbourhood(read_image(positions), ground.position, radius, support);
    const glm::vec3 normal = glm::normalize(ground.normal);
    if (request.blend_distance == BlendDistance::kRay) {
      field->set_ray_distance(true);
      field->set_support_plane(ground.position, normal);
    }
    if (request.blend_distance == BlendDistance::kFoot) field->set_blend_plane(normal);
  }
  const glm::ivec2 cell = pixel_cell(probes.layout, view, x, y);
  const glm::ivec2 nearest = field->nearest_valid(cell.x, cell.y);
  Lighting lighting;
  // Directions are drawn from the local probes' mean where there is a local blend: every light
  // a blended probe sees is then sampled (the global probe's own map missed a close lamp seen
  // in another texel by its neighbours, which left it to the BRDF's samples: noise).
  const Image sampling = local ? field->local_sampling_map() : probes.probe(nearest.x, nearest.y);
  lighting.environment = std::make_unique<render::EnvironmentLight>(sampling);
  if (varying) lighting.environment->set_positional(field);
  lighting.record = {{"global_probe", {nearest.x, nearest.y}},
                     {"grid", {probes.layout.grid_height, probes.layout.grid_width}},
                     {"resolution", {probes.layout.res_height, probes.layout.res_width}},
                     {"spatially_varying", varying},
                     {"blend", !varying ? "none" : !local ? "projected" : request.support_plane_only ? "local_support_plane" : "local"},
                     {"local_probes", field->local_probe_count()},
                     {"blend_power", request.blend_power},
                     {"blend_distance", blend_distance_name(request.blend_distance)},
                     {"directions_from", local ? "local probes' mean" : "global probe"}};
  return lighting;
}

// Where predicted probes stand: the prediction folder's probe_position.exr when it has one;
// else the view's, when the view's probe grid is the prediction's (a dataset view: the network
// predicts the probes at the grid the dataset renders), so that predicted and GT probes are
// blended alike; else nowhere (the prediction folder: projection mode).
fs::path predicted_probe_geometry(const fs::path& predicted_dir, const InsertView& view, const view::ProbeLayout& layout) {
  if (fs::is_regular_file(predicted_dir / view::kProbePositionFile)) return predicted_dir;
  const fs::path positions = view.dir / view::kProbePositionFile;
  if (!fs::is_regular_file(positions)) return predicted_dir;
  const Image p = read_image(positions);
  return p.width == layout.grid_width && p.height == layout.grid_height ? view.dir : predicted_dir;
}

// No ProbeField: its nearest-valid-probe table is a search over the whole grid, and the mean
// needs none of it.
Lighting constant(const view::ProbeMosaic& probes) {
  const glm::vec3 mean = mean_probe_radiance(probes);
  Image one(1, 1, 3);
  for (int k = 0; k < 3; ++k) one.pixels[size_t(k)] = mean[k];
  Lighting lighting;
  lighting.environment = std::make_unique<render::EnvironmentLight>(one);
  lighting.record = {{"radiance", {mean.x, mean.y, mean.z}}, {"spatially_varying", false}};
  return lighting;
}

}  // namespace

const char* blend_distance_name(BlendDistance d) {
  switch (d) {
    case BlendDistance::kRay: return "ray";
    case BlendDistance::kPoint: return "point";
    case BlendDistance::kFoot: return "foot_point";
  }
  return "?";
}

Lighting make_lighting(const LightingRequest& request, const InsertView& view, int x, int y) {
  Lighting lighting;
  const std::string& s = request.source;
  if (s == "gt" || s == "global") {
    lighting = from_probes(read_view_probes(view.dir, view), view, x, y, s == "gt", view.dir, request);
    lighting.record["probes"] = view.dir.string();
  } else if (s == "predicted") {
    if (request.predicted_dir.empty()) fail("predicted lighting needs the prediction folder (a `phyir infer` result)");
    const auto predicted = read_view_probes(request.predicted_dir, view);
    const fs::path geometry = predicted_probe_geometry(request.predicted_dir, view, predicted->layout);
    lighting = from_probes(predicted, view, x, y, true, geometry, request);
    lighting.record["probes"] = request.predicted_dir.string();
    lighting.record["probe_positions"] = (geometry / view::kProbePositionFile).string();
  } else if (s == "constant") {
    lighting = constant(*read_view_probes(view.dir, view));
    lighting.record["probes"] = view.dir.string();
  } else {
    if (!fs::is_regular_file(s))
      fail("lighting source {}: neither gt, predicted, global, constant nor an existing HDR file", s);
    lighting.environment = std::make_unique<render::EnvironmentLight>(read_image(s));
    lighting.record = {{"file", s}, {"spatially_varying", false}};
  }
  lighting.record["source"] = (s == "gt" || s == "predicted" || s == "global" || s == "constant") ? s : "file";
  return lighting;
}

}  // namespace phyir::insert
