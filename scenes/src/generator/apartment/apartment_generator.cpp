// generate_apartment(): plan, furnish, light and write one apartment.
#include "phyir/scenes/apartment_generator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "generator/apartment/apartment_gltf.h"
#include "generator/apartment/apartment_steps.h"
#include "phyir/core/image_io.h"
#include "phyir/scenes/sky.h"

namespace phyir::scenes {

namespace fs = std::filesystem;

namespace {

constexpr float kCameraYfov = 1.2f;  // radians, as the single rooms' cameras
constexpr int kSkyWidth = 1024;      // texels around the horizon

// Mixed: even apartments by day, odd ones at night, so any two in a row have both.
ApartmentLighting choose_lighting(const ApartmentOptions& options, int index) {
  if (options.lighting) return *options.lighting;
  return index % 2 == 0 ? ApartmentLighting::Day : ApartmentLighting::Night;
}

// Daylight: a clear sky of random turbidity and a sun between 15 and 60 degrees up.
void add_daylight(GltfDocument& doc, const fs::path& out_dir, const std::string& stem, Pcg32& rng) {
  SkyParameters parameters;
  parameters.turbidity = rng.uniform(2.2f, 4.0f);
  parameters.sun_elevation = rng.uniform(0.26f, 1.05f);
  parameters.sun_azimuth = rng.uniform(-3.14159f, 3.14159f);
  const PreethamSky sky(parameters);
  const std::string uri = stem + "_sky.exr";
  write_image(out_dir / uri, sky_image(sky, kSkyWidth));
  GltfEnvironment environment;
  environment.uri = uri;
  doc.environment = environment;
  doc.lights.push_back(sun_light(sky));
}

// The living room's most open viewpoint, looking level at the room's middle.
GltfCamera living_room_camera(const ApartmentPlan& plan, const std::vector<ApartmentViewpoint>& viewpoints) {
  const ApartmentViewpoint* best = nullptr;
  for (const ApartmentViewpoint& v : viewpoints)
    if (plan.rooms[size_t(v.room)].type == RoomType::LivingRoom && (!best || v.clearance > best->clearance)) best = &v;
  GltfCamera camera;
  camera.name = "camera";
  camera.yfov = kCameraYfov;
  const glm::vec2 middle = plan.rooms[0].floor.centre();
  camera.position = best ? best->position : glm::vec3(middle.x, 1.5f, middle.y);
  glm::vec2 d = middle - glm::vec2(camera.position.x, camera.position.z);
  if (glm::length(d) < 0.3f) d = glm::vec2(0.0f, -1.0f);
  const float yaw = std::atan2(-d.x, -d.y);  // turns the camera's -Z onto d
  camera.rotation = {0.0f, std::sin(0.5f * yaw), 0.0f, std::cos(0.5f * yaw)};
  return camera;
}

// A window to the outside as a light portal (phyir::scenes::Portal): the hole's outer face,
// its edges crossed into the room.
nlohmann::json window_portal(const WallOpening& o) {
  const int along = o.wall_axis == 0 ? 0 : 1, across = 1 - along;
  const float face = o.outward[across] > 0.0f ? o.footprint.max[across] : o.footprint.min[across];
  auto world = [](const glm::vec2& plan, float y) { return glm::vec3(plan.x, y, plan.y); };
  glm::vec2 start, width(0.0f);
  start[along] = o.footprint.min[along];
  start[across] = face;
  width[along] = o.width();
  glm::vec3 u = world(width, 0.0f), v(0.0f, o.top - o.bottom, 0.0f);
  const glm::vec3 inward = -world(o.outward, 0.0f);
  if (glm::dot(glm::cross(u, v), inward) < 0.0f) std::swap(u, v);
  auto mm = [](const glm::vec3& p) {
    return nlohmann::json::array({std::round(p.x * 1000.0) / 1000.0, std::round(p.y * 1000.0) / 1000.0,
                                  std::round(p.z * 1000.0) / 1000.0});
  };
  return {{"corner", mm(world(start, o.bottom))}, {"edge_u", mm(u)}, {"edge_v", mm(v)}};
}

nlohmann::json scene_extras(const ApartmentPlan& plan, const std::vector<ApartmentViewpoint>& viewpoints,
                            ApartmentLighting lighting, const PiecesWritten& pieces, bool with_portals) {
  nlohmann::json points = nlohmann::json::array(), rooms = nlohmann::json::array();
  for (const ApartmentViewpoint& v : viewpoints)
    points.push_back({std::round(v.position.x * 1000.0) / 1000.0, std::round(v.position.y * 1000.0) / 1000.0,
                      std::round(v.position.z * 1000.0) / 1000.0});
  nlohmann::json portals = nlohmann::json::array();
  for (const WallOpening& o : plan.openings)
    if (with_portals && o.kind == WallOpeningKind::Window && o.other < 0) portals.push_back(window_portal(o));
  for (const ApartmentRoom& r : plan.rooms)
    rooms.push_back({{"name", r.name}, {"type", room_type_name(r.type)},
                     {"floor", {r.floor.min.x, r.floor.min.y, r.floor.max.x, r.floor.max.y}}});
  nlohmann::json phyir = {{"candidate_viewpoints", points},
                          {"preset", "apartment"},
                          {"seed", plan.seed},
                          {"index", plan.index},
                          {"lighting", apartment_lighting_name(lighting)},
                          {"rooms", rooms},
                          {"emission_unit", "W/(sr m^2) = emissiveFactor * KHR_materials_emissive_strength"}};
  if (!portals.empty()) phyir["portals"] = portals;
  return {{"phyir", phyir}, {"attribution", pieces.attributions}};
}

}  // namespace

ApartmentSummary generate_apartment(const fs::path& out_dir, int index, uint64_t seed, const AssetLibrary& library,
                                    const ApartmentOptions& options) {
  const ApartmentPlan plan = plan_apartment(seed, index, options.rooms);
  Pcg32 light_rng = apartment_rng(seed, index, ApartmentStream::Lights);
  const ApartmentLighting lighting = choose_lighting(options, index);
  AssetModelCache models;
  const ApartmentFurnishing furnishing = furnish_apartment(plan, library, models, lighting);
  const std::vector<ApartmentViewpoint> viewpoints = plan_apartment_viewpoints(plan, furnishing.items);

  const std::string stem = fmt::format("apartment_{}", index);
  fs::create_directories(out_dir);
  GltfDocument doc;
  doc.generator = std::string("phyir ") + PHYIR_VERSION;
  add_apartment_shell(doc, plan, out_dir, stem);
  Pcg32 material_rng = apartment_rng(seed, index, ApartmentStream::Materials);
  const PiecesWritten pieces = add_apartment_pieces(doc, furnishing, models, stem, material_rng);
  if (lighting == ApartmentLighting::Day) add_daylight(doc, out_dir, stem, light_rng);
  doc.cameras.push_back(living_room_camera(plan, viewpoints));
  doc.scene_extras =
      scene_extras(plan, viewpoints, lighting, pieces, options.portals && lighting == ApartmentLighting::Day);
  write_gltf(out_dir / (stem + ".gltf"), doc);

  ApartmentSummary summary;
  summary.rooms = static_cast<int>(plan.rooms.size());
  summary.lighting = lighting;
  summary.pieces = furnishing.items.size();
  summary.lamps_lit = pieces.lamps_lit;
  summary.punctual_lights = doc.lights.size();
  summary.attributions = pieces.attributions;
  summary.missing_roles = furnishing.unfurnished_roles;
  std::sort(summary.missing_roles.begin(), summary.missing_roles.end());
  summary.missing_roles.erase(std::unique(summary.missing_roles.begin(), summary.missing_roles.end()),
                              summary.missing_roles.end());
  RoomSummary& files = summary.files;
  files.file = stem + ".gltf";
  files.meshes = doc.meshes.size();
  for (const GltfMesh& m : doc.meshes) {
    files.triangles += m.indices.size() / 3;
    const bool glows = m.material >= 0 && glm::length(doc.materials[size_t(m.material)].emissive_factor) > 0.0f;
    files.emissive_meshes += glows;
  }
  files.materials = doc.materials.size();
  files.textures = doc.textures.size();
  files.cameras = doc.cameras.size();
  files.candidate_viewpoints = viewpoints.size();
  files.material_kinds = pieces.material_kinds;
  return summary;
}

}  // namespace phyir::scenes
