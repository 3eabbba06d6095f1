#include "phyir/insert/insert_object.h"

#include "phyir/core/stopwatch.h"
#include "phyir/render/camera.h"
#include "phyir/render/render_view.h"
#include "phyir/insert/pixel_render.h"
#include "phyir/view/input_exposure.h"

namespace phyir::insert {

namespace {

nlohmann::json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// The local scene as the view's camera sees it: same panorama, same centre. Both renders use
// the same seed, so the noise of the surface mostly cancels in their difference. The geometry
// (one ray per pixel centre) comes from a one-path render; the colour is then summed at full
// spp only where the geometry is, the only pixels the composite reads (pixel_render.h: each
// bit-identical to a full render's). Elsewhere the colour is 0.
LocalRender render_local(const scenes::Scene& scene, const Lighting& lighting, const InsertView& view,
                         const InsertRequest& request) {
  const render::RenderScene rs(scene, std::make_unique<render::EnvironmentLight>(*lighting.environment));
  const render::CameraModel camera = panorama_camera(view);
  render::RenderSettings settings;
  settings.spp = 1;
  settings.seed = request.seed;
  settings.path.max_bounces = request.max_bounces;
  settings.aovs = true;
  settings.progress = false;
  const render::RenderOutput geometry = render::render_view(rs, camera, settings);
  LocalRender out{Image(camera.width, camera.height, 3), geometry.film.aov("depth"), geometry.film.aov("mask_geometry")};
  settings.spp = request.spp;
  render_pixels(rs, camera, settings, dilated_pixels(out.mask, 0), out.color);
  return out;
}

}  // namespace

InsertResult insert_object(const InsertView& view, const scenes::Scene& object, const InsertRequest& request) {
  const Stopwatch total;
  InsertResult result;
  result.ground = surface_at(view, request.x, request.y);
  const Lighting lighting = make_lighting(request.lighting, view, request.x, request.y);
  const scenes::Scene placed = place_object(object, result.ground, request.placement);
  const float radius = disc_radius_for(placed, result.ground);
  const scenes::Scene disc = support_disc(result.ground, radius);
  const scenes::Scene local = merge_scenes(disc, placed);
  const double setup_seconds = total.seconds();
  const Stopwatch render_watch;
  result.with_object = render_local(local, lighting, view, request);
  result.without_object = render_local(disc, lighting, view, request);
  const double render_seconds = render_watch.seconds();
  result.composite = differential_composite(view.color, view.depth, view.normal, glm::normalize(result.ground.normal),
                                            result.with_object, result.without_object);
  const scenes::Bounds b = placed.compute_bounds();
  result.record = {
      {"view", view.dir.string()},
      {"object", {{"file", object.source}, {"triangles", object.triangle_count()},
                  {"bounds_min", vec(b.min)}, {"bounds_max", vec(b.max)}}},
      {"placement", {{"pixel", {request.x, request.y}}, {"world_position", vec(result.ground.position)},
                     {"normal", vec(result.ground.normal)}, {"scale", request.placement.scale},
                     {"yaw_radians", request.placement.yaw}}},
      {"support_surface", {{"radius", radius}, {"base_color", vec(result.ground.base_color)},
                           {"roughness", result.ground.roughness}, {"metalness", result.ground.metalness}}},
      {"lighting", lighting.record},
      {"settings", {{"spp", request.spp}, {"max_bounces", request.max_bounces}, {"seed", request.seed}}},
      {"display", {{view::kExposureStopsKey, view.exposure_stops}, {"view", view.display_view}}},
      {"timings", {{"setup_seconds", setup_seconds}, {"render_seconds", render_seconds},
                   {"total_seconds", total.seconds()}}}};
  return result;
}

}  // namespace phyir::insert
